// SPDX-License-Identifier: MIT
#include "poly_mesh.hpp"

#include <algorithm>

#include <OpenMesh/Core/System/omstream.hh>

namespace odeskin {

Result<PolyMesh> buildPolyMesh(std::span<const Vec3> positions, const FaceList& faces, const std::string& source) {
  // OpenMesh prints its own line ("PolyMeshT::add_face: complex edge") before returning an invalid
  // handle; the Status below says it with the file and face, and a command prints exactly one line.
  static const bool silenced = [] {
    omerr().disable();
    return true;
  }();
  (void)silenced;
  PolyMesh mesh;
  mesh.reserve(positions.size(), positions.size() * 3, faces.faceCount());
  for (const Vec3& p : positions) mesh.add_vertex(PolyMesh::Point(p.x, p.y, p.z));
  // Buffers reused from face to face, and the face's name only built for an error.
  std::vector<PolyMesh::VertexHandle> face;
  std::vector<std::uint32_t> sorted;
  auto where = [&](std::size_t f) { return source + ": face " + std::to_string(f + 1); };
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    face.clear();
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t end = faces.face_offsets[f + 1];
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t index = faces.indices[k];
      if (index >= positions.size()) {
        return invalidArgument(where(f) + " uses vertex " + std::to_string(index + 1) + " of " +
                               std::to_string(positions.size()));
      }
      face.push_back(PolyMesh::VertexHandle(static_cast<int>(index)));
    }
    if (face.size() < 3) return invalidArgument(where(f) + " has fewer than 3 vertices");
    bool repeats = false;
    if (face.size() <= 4) {
      for (std::size_t i = 0; i < face.size() && !repeats; ++i) {
        for (std::size_t j = i + 1; j < face.size(); ++j) repeats = repeats || face[i] == face[j];
      }
    } else {
      sorted.assign(faces.indices.begin() + begin, faces.indices.begin() + end);
      std::sort(sorted.begin(), sorted.end());
      repeats = std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
    }
    if (repeats) return invalidArgument(where(f) + " repeats a vertex");
    if (!mesh.add_face(face).is_valid()) {
      return invalidArgument(where(f) + " makes the mesh non-manifold (an edge or vertex shared by too many faces, "
                                        "or inconsistent orientation)");
    }
  }
  return mesh;
}

std::vector<std::vector<std::uint32_t>> boundaryLoops(const PolyMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<char> seen(mesh.n_halfedges(), 0);
  for (PolyMesh::HalfedgeHandle start : mesh.halfedges()) {
    if (!mesh.is_boundary(start) || seen[start.idx()]) continue;
    std::vector<std::uint32_t> loop;
    PolyMesh::HalfedgeHandle h = start;
    do {
      seen[h.idx()] = 1;
      loop.push_back(static_cast<std::uint32_t>(mesh.from_vertex_handle(h).idx()));
      h = mesh.next_halfedge_handle(h);
    } while (h != start && !seen[h.idx()]);
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "poly_mesh.hpp"

#include <algorithm>

namespace odeskin {

Result<PolyMesh> buildPolyMesh(std::span<const Vec3> positions, const FaceList& faces, const std::string& source) {
  PolyMesh mesh;
  mesh.reserve(positions.size(), positions.size() * 3, faces.faceCount());
  for (const Vec3& p : positions) mesh.add_vertex(PolyMesh::Point(p.x, p.y, p.z));
  std::vector<PolyMesh::VertexHandle> face;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    face.clear();
    const std::string where = source + ": face " + std::to_string(f + 1);
    for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
      const std::uint32_t index = faces.indices[k];
      if (index >= positions.size()) {
        return invalidArgument(where + " uses vertex " + std::to_string(index + 1) + " of " +
                               std::to_string(positions.size()));
      }
      face.push_back(PolyMesh::VertexHandle(static_cast<int>(index)));
    }
    if (face.size() < 3) return invalidArgument(where + " has fewer than 3 vertices");
    std::vector<PolyMesh::VertexHandle> sorted = face;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      return invalidArgument(where + " repeats a vertex");
    }
    if (!mesh.add_face(face).is_valid()) {
      return invalidArgument(where + " makes the mesh non-manifold (an edge or vertex shared by too many faces, "
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

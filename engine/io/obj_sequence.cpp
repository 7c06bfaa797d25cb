// SPDX-License-Identifier: MIT
#include <algorithm>
#include <string>

#include "../mesh/poly_mesh.hpp"
#include "obj_reader.hpp"

namespace odeskin {
namespace {

std::string fileName(const std::filesystem::path& path) { return path.filename().string(); }

// Face f's 1-based vertex indices, as they were written in the file: "3 9 12".
std::string faceText(const FaceList& faces, std::size_t f) {
  std::string text;
  for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
    if (!text.empty()) text += ' ';
    text += std::to_string(faces.indices[k] + 1);
  }
  return text;
}

bool sameFace(const FaceList& a, const FaceList& b, std::size_t f) {
  return std::equal(a.indices.begin() + a.face_offsets[f], a.indices.begin() + a.face_offsets[f + 1],
                    b.indices.begin() + b.face_offsets[f], b.indices.begin() + b.face_offsets[f + 1]);
}

// `mesh` (read from `path`) must have the reference's vertex count and face list, face for face:
// corresponding vertices are matched by index, so any renumbering would silently pair wrong points.
Status checkSameTopology(const ObjMesh& mesh, const std::filesystem::path& path, const ObjMesh& reference,
                         const std::filesystem::path& reference_path) {
  const std::string name = fileName(path);
  const std::string reference_name = fileName(reference_path);
  if (mesh.positions.size() != reference.positions.size()) {
    return invalidArgument(name + ": " + std::to_string(mesh.positions.size()) + " vertices but " + reference_name +
                           " has " + std::to_string(reference.positions.size()));
  }
  const std::size_t common = std::min(mesh.faces.faceCount(), reference.faces.faceCount());
  for (std::size_t f = 0; f < common; ++f) {
    if (!sameFace(mesh.faces, reference.faces, f)) {
      return invalidArgument(name + ": face " + std::to_string(f + 1) + " is " + faceText(mesh.faces, f) + " but " +
                             reference_name + " has " + faceText(reference.faces, f));
    }
  }
  if (mesh.faces.faceCount() != reference.faces.faceCount()) {
    return invalidArgument(name + ": " + std::to_string(mesh.faces.faceCount()) + " faces but " + reference_name +
                           " has " + std::to_string(reference.faces.faceCount()));
  }
  return okStatus();
}

}  // namespace

Result<ExampleSet> readObjSequence(std::span<const std::filesystem::path> poses, const std::filesystem::path* bind) {
  if (poses.size() < 2) {
    return invalidArgument("an OBJ sequence needs at least 2 example poses, got " + std::to_string(poses.size()));
  }
  ODESKIN_ASSIGN_OR_RETURN(ObjMesh first, readObj(poses[0]));
  // Every file must carry this face list, so one OpenMesh pass checks them all (positions play no part).
  ODESKIN_TRY(buildPolyMesh(first.positions, first.faces, fileName(poses[0])).status());
  ExampleSet set;
  set.poses.reserve(poses.size());
  set.poses.push_back(first.positions);
  for (std::size_t k = 1; k < poses.size(); ++k) {
    ODESKIN_ASSIGN_OR_RETURN(ObjMesh pose, readObj(poses[k]));
    ODESKIN_TRY(checkSameTopology(pose, poses[k], first, poses[0]));
    set.poses.push_back(std::move(pose.positions));
  }
  // The layout is made before the positions move out of the mesh it comes from.
  auto takeLayout = [&set](const ObjMesh& mesh) {
    set.render = objRenderLayout(mesh);
    set.warnings = objLayoutWarnings(mesh);
  };
  if (bind != nullptr) {
    ODESKIN_ASSIGN_OR_RETURN(ObjMesh rest, readObj(*bind));
    ODESKIN_TRY(checkSameTopology(rest, *bind, first, poses[0]));
    // The rest mesh is the one artists texture; poses from a simulation often carry positions only.
    const bool rest_has_layout = !rest.corner_texcoords.empty() || !rest.corner_normals.empty();
    takeLayout(rest_has_layout ? rest : first);
    set.rest_positions = std::move(rest.positions);
  } else {
    takeLayout(first);
    set.rest_positions = std::move(first.positions);
  }
  set.faces = std::move(first.faces);
  set.pose_labels.reserve(poses.size());
  for (const std::filesystem::path& path : poses) set.pose_labels.push_back(fileName(path));
  return set;
}

}  // namespace odeskin

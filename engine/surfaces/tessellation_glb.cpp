// SPDX-License-Identifier: MIT
#include "tessellation_glb.hpp"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <tiny_gltf.h>

#include "../core/finite_vector.hpp"
#include "../io/gltf_baked_writer.hpp"
#include "../io/gltf_buffer_builder.hpp"

namespace odeskin {
namespace {

int addVec3(tinygltf::Model& m, std::span<const Vec3> values, bool bounds) {
  std::vector<float> xyz;
  xyz.reserve(values.size() * 3);
  for (const Vec3& v : values) xyz.insert(xyz.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
  return gltf::appendFloatAccessor(m, xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, bounds);
}

}  // namespace

Status writeSurfaceGlb(const std::filesystem::path& path, const SurfaceMesh& mesh, std::span<const Vec3> normals,
                       const Vec3& up, const std::string& generator) {
  if (normals.size() != mesh.positions.size()) {
    return invalidArgument("surface glTF: " + std::to_string(normals.size()) + " normals for " +
                           std::to_string(mesh.positions.size()) + " vertices");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!isFinite(mesh.positions[i]) || !isFinite(normals[i])) {
      return invalidArgument("surface glTF: vertex " + std::to_string(i) + " is not finite");
    }
  }
  ODESKIN_TRY(gltf::checkFloat32Positions(mesh.positions, "surface glTF"));
  const std::vector<std::uint32_t> triangles = gltf::fanTriangles(mesh.faces);
  tinygltf::Model m = gltf::newModel(generator);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.indices = gltf::appendTriangleIndices(m, triangles);
  primitive.attributes["POSITION"] = addVec3(m, mesh.positions, true);
  primitive.attributes["NORMAL"] = addVec3(m, normals, false);
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "odeskin surface";
  gltf_mesh.primitives.push_back(primitive);
  m.meshes.push_back(gltf_mesh);
  gltf::addSingleMeshScene(m, "odeskin surface");
  // The shortest turn from `up` to +y, (1 + up.y, up x y) normalised; half a turn about x for -y.
  if (up != Vec3(0.0, 1.0, 0.0)) {
    const Vec3 axis = glm::cross(up, Vec3(0.0, 1.0, 0.0));
    const double w = 1.0 + up.y;
    const double norm = std::sqrt(w * w + glm::dot(axis, axis));
    m.nodes[0].rotation = up.y < -0.5 ? std::vector<double>{1.0, 0.0, 0.0, 0.0}
                                      : std::vector<double>{axis.x / norm, axis.y / norm, axis.z / norm, w / norm};
  }
  return writeGlbAtomically(path, m);
}

}  // namespace odeskin

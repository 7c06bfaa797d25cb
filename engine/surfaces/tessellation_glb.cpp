// SPDX-License-Identifier: MIT
#include "tessellation_glb.hpp"

#include <cmath>
#include <limits>

#include <tiny_gltf.h>

#include "../io/gltf_baked_writer.hpp"

namespace odeskin {
namespace {

int addView(tinygltf::Model& m, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = m.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size() - 1);
}

int addVec3(tinygltf::Model& m, std::span<const Vec3> values, bool bounds) {
  std::vector<float> xyz;
  xyz.reserve(values.size() * 3);
  for (const Vec3& v : values) xyz.insert(xyz.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
  tinygltf::Accessor a;
  a.bufferView = addView(m, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = values.size();
  if (bounds) {
    a.minValues.assign(3, std::numeric_limits<double>::infinity());
    a.maxValues.assign(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      a.minValues[i % 3] = std::min(a.minValues[i % 3], static_cast<double>(xyz[i]));
      a.maxValues[i % 3] = std::max(a.maxValues[i % 3], static_cast<double>(xyz[i]));
    }
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

Status writeSurfaceGlb(const std::filesystem::path& path, const SurfaceMesh& mesh, std::span<const Vec3> normals,
                       const std::string& generator) {
  if (normals.size() != mesh.positions.size()) {
    return invalidArgument("surface glTF: " + std::to_string(normals.size()) + " normals for " +
                           std::to_string(mesh.positions.size()) + " vertices");
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!finite(mesh.positions[i]) || !finite(normals[i])) {
      return invalidArgument("surface glTF: vertex " + std::to_string(i) + " is not finite");
    }
  }
  std::vector<std::uint32_t> triangles;
  const FaceList& f = mesh.faces;
  triangles.reserve(f.faceCount() * 6);
  for (std::size_t face = 0; face < f.faceCount(); ++face) {
    const std::uint32_t begin = f.face_offsets[face];
    for (std::uint32_t k = begin + 1; k + 1 < f.face_offsets[face + 1]; ++k) {
      triangles.insert(triangles.end(), {f.indices[begin], f.indices[k], f.indices[k + 1]});
    }
  }
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = generator;
  m.buffers.emplace_back();
  tinygltf::Accessor indices;
  indices.bufferView =
      addView(m, triangles.data(), triangles.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.type = TINYGLTF_TYPE_SCALAR;
  indices.count = triangles.size();
  m.accessors.push_back(indices);
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.indices = 0;
  primitive.attributes["POSITION"] = addVec3(m, mesh.positions, true);
  primitive.attributes["NORMAL"] = addVec3(m, normals, false);
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "odeskin surface";
  gltf_mesh.primitives.push_back(primitive);
  m.meshes.push_back(gltf_mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "odeskin surface";
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return writeGlbAtomically(path, m);
}

}  // namespace odeskin

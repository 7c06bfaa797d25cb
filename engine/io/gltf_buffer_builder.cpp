// SPDX-License-Identifier: MIT
#include "gltf_buffer_builder.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "../core/float32_range.hpp"
#include "../offline/residual_fit.hpp"

namespace odeskin::gltf {

Status checkFloat32Positions(std::span<const Vec3> positions, const std::string& who) {
  constexpr double kSmallestSpan = 1e-30;
  if (const std::size_t i = firstBeyondFloat32(positions); i < positions.size()) {
    return invalidArgument(who + ": vertex " + std::to_string(i) +
                           " is outside glTF's float32 range (|coordinate| up to 1e+38); scale the mesh down");
  }
  const double side = longestBoxSide(positions);
  if (side > 0.0 && side < kSmallestSpan) {
    char span[32];
    std::snprintf(span, sizeof span, "%g", side);
    return invalidArgument(who + ": the mesh spans " + span +
                           ", too small for glTF's float32 positions (at least 1e-30); scale it up");
  }
  return okStatus();
}

tinygltf::Model newModel(const std::string& generator) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = generator;
  m.buffers.emplace_back();
  return m;
}

int appendView(tinygltf::Model& m, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = m.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  if (target != 0) view.target = target;
  const auto* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size() - 1);
}

int appendAccessor(tinygltf::Model& m, int view, int component_type, int type, std::size_t count) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component_type;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

void setBounds(tinygltf::Accessor& a, std::span<const float> values, int components, bool with_zero) {
  const auto n = static_cast<std::size_t>(components);
  a.minValues.assign(n, with_zero ? 0.0 : std::numeric_limits<double>::infinity());
  a.maxValues.assign(n, with_zero ? 0.0 : -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < values.size(); ++i) {
    a.minValues[i % n] = std::min(a.minValues[i % n], static_cast<double>(values[i]));
    a.maxValues[i % n] = std::max(a.maxValues[i % n], static_cast<double>(values[i]));
  }
}

int appendFloatAccessor(tinygltf::Model& m, const std::vector<float>& values, int type, int components, int target,
                        bool bounds) {
  const int index = appendAccessor(m, appendView(m, values, target), TINYGLTF_COMPONENT_TYPE_FLOAT, type,
                                   values.size() / static_cast<std::size_t>(components));
  if (bounds) setBounds(m.accessors[static_cast<std::size_t>(index)], values, components, false);
  return index;
}

int appendTexcoordAccessor(tinygltf::Model& m, std::span<const Vec2> uvs) {
  std::vector<float> values;
  values.reserve(2 * uvs.size());
  for (const Vec2& uv : uvs) values.insert(values.end(), {static_cast<float>(uv.x), static_cast<float>(uv.y)});
  return appendFloatAccessor(m, values, TINYGLTF_TYPE_VEC2, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
}

int appendTriangleIndices(tinygltf::Model& m, const std::vector<std::uint32_t>& triangles) {
  return appendAccessor(m, appendView(m, triangles, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                        TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, triangles.size());
}

void addSingleMeshScene(tinygltf::Model& m, const std::string& name) {
  tinygltf::Node node;
  node.mesh = 0;
  node.name = name;
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
}

std::vector<std::uint32_t> fanTriangles(const FaceList& faces) { return fanTriangles(faces, 0, faces.faceCount()); }

std::vector<std::uint32_t> fanTriangles(const FaceList& faces, std::size_t first_face, std::size_t end_face) {
  std::vector<std::uint32_t> triangles;
  triangles.reserve((end_face - first_face) * 6);
  for (std::size_t f = first_face; f < end_face; ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    for (std::uint32_t k = begin + 1; k + 1 < faces.face_offsets[f + 1]; ++k) {
      triangles.insert(triangles.end(), {faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
  return triangles;
}

}  // namespace odeskin::gltf

// SPDX-License-Identifier: MIT
#include "gltf_baked_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <tiny_gltf.h>

namespace odeskin {
namespace {

// Appends `bytes` to buffer 0 as a new buffer view (4-byte aligned); returns the view's index.
int addView(tinygltf::Model& m, const void* bytes, std::size_t size, int target) {
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

int addVec3Accessor(tinygltf::Model& m, const std::vector<float>& xyz) {
  tinygltf::Accessor a;
  a.bufferView = addView(m, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = xyz.size() / 3;
  a.minValues.assign(3, std::numeric_limits<double>::infinity());
  a.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    a.minValues[i % 3] = std::min(a.minValues[i % 3], static_cast<double>(xyz[i]));
    a.maxValues[i % 3] = std::max(a.maxValues[i % 3], static_cast<double>(xyz[i]));
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

int addScalarAccessor(tinygltf::Model& m, const std::vector<float>& values, bool bounds) {
  tinygltf::Accessor a;
  a.bufferView = addView(m, values.data(), values.size() * sizeof(float), 0);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = values.size();
  if (bounds) {
    a.minValues = {static_cast<double>(*std::min_element(values.begin(), values.end()))};
    a.maxValues = {static_cast<double>(*std::max_element(values.begin(), values.end()))};
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

Status checkInput(const FaceList& faces, const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds) {
  if (frames.empty()) return invalidArgument("baked glTF: no frames");
  if (seconds.size() != frames.size()) return invalidArgument("baked glTF: one time per frame is needed");
  const std::size_t v_count = frames[0].size();
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != v_count) return invalidArgument("baked glTF: frame " + std::to_string(f) + " has another vertex count");
    for (const Vec3& p : frames[f]) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        return invalidArgument("baked glTF: frame " + std::to_string(f) + " has a non-finite position");
      }
    }
    if (!std::isfinite(seconds[f]) || seconds[f] < 0.0 || (f > 0 && !(seconds[f] > seconds[f - 1]))) {
      return invalidArgument("baked glTF: frame times must be non-negative and increasing");
    }
  }
  for (std::uint32_t index : faces.indices) {
    if (index >= v_count) return invalidArgument("baked glTF: a face uses vertex " + std::to_string(index));
  }
  return okStatus();
}

}  // namespace

Status writeBakedGlb(const std::filesystem::path& path, const FaceList& faces,
                     const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds,
                     const BakedGlbOptions& options) {
  ODESKIN_TRY(checkInput(faces, frames, seconds));
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = options.generator;
  m.buffers.emplace_back();

  std::vector<std::uint32_t> triangles;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    for (std::uint32_t k = begin + 1; k + 1 < faces.face_offsets[f + 1]; ++k) {
      triangles.insert(triangles.end(), {faces.indices[begin], faces.indices[k], faces.indices[k + 1]});
    }
  }
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
  std::vector<float> xyz;
  auto flatten = [&](std::size_t frame) {
    xyz.clear();
    for (std::size_t i = 0; i < frames[frame].size(); ++i) {
      const Vec3 d = frame == 0 ? frames[0][i] : frames[frame][i] - frames[0][i];
      xyz.insert(xyz.end(), {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)});
    }
    return addVec3Accessor(m, xyz);
  };
  primitive.attributes["POSITION"] = flatten(0);
  for (std::size_t f = 1; f < frames.size(); ++f) primitive.targets.push_back({{"POSITION", flatten(f)}});
  tinygltf::Mesh mesh;
  mesh.name = "odeskin";
  mesh.primitives.push_back(primitive);
  mesh.weights.assign(frames.size() - 1, 0.0);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "odeskin";
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;

  if (frames.size() > 1) {
    // Key f weights target f-1 by 1 (frame 0: none); STEP holds it, LINEAR fades into the next.
    const std::size_t targets = frames.size() - 1;
    std::vector<float> times(seconds.begin(), seconds.end());
    std::vector<float> weights(frames.size() * targets, 0.0f);
    for (std::size_t f = 1; f < frames.size(); ++f) weights[f * targets + (f - 1)] = 1.0f;
    tinygltf::AnimationSampler sampler;
    sampler.input = addScalarAccessor(m, times, true);
    sampler.output = addScalarAccessor(m, weights, false);
    sampler.interpolation = options.linear ? "LINEAR" : "STEP";
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    tinygltf::Animation animation;
    animation.name = options.animation;
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    m.animations.push_back(animation);
  }
  m.buffers[0].data.resize((m.buffers[0].data.size() + 3) / 4 * 4, 0);

  return writeGlbAtomically(path, m);
}

Status writeGlbAtomically(const std::filesystem::path& path, const tinygltf::Model& model) {
  std::filesystem::path temp = path;
  temp += ".partial";
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, temp.string(), true, true, false, true)) {
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    return ioError(path.string() + ": cannot write the glTF file");
  }
  std::error_code ec;
  std::filesystem::rename(temp, path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    return ioError(path.string() + ": cannot move the written file into place");
  }
  return okStatus();
}

}  // namespace odeskin

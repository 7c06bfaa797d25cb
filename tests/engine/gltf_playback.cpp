// SPDX-License-Identifier: MIT
#include "gltf_playback.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

namespace odeskin::testing {
namespace {

std::size_t componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

double readComponent(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {  // KHR_mesh_quantization's normals
      std::int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {  // its positions and deltas
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: ADD_FAILURE() << "unexpected component type " << component_type; return 0.0;
  }
}

glm::dmat4 trs(const std::vector<double>& t, const std::vector<double>& r, const std::vector<double>& s) {
  glm::dmat4 m(1.0);
  if (!t.empty()) m = glm::translate(m, Vec3(t[0], t[1], t[2]));
  if (!r.empty()) m = m * glm::mat4_cast(glm::dquat(r[3], r[0], r[1], r[2]));
  if (!s.empty()) m = glm::scale(m, Vec3(s[0], s[1], s[2]));
  return m;
}

// One sampler at time `t` (spec 3.11 and appendix C): `n` components per element. `nlerp`: a LINEAR
// rotation as importers that keep quaternions as four curves play it (Blender): blended component
// by component, with no hemisphere check, then normalised.
std::vector<double> sample(const Channel& c, double t, std::size_t n, bool nlerp = false) {
  const bool cubic = c.interpolation == "CUBICSPLINE";
  const std::size_t per_key = cubic ? 3 * n : n;
  const std::size_t value_offset = cubic ? n : 0;
  auto value = [&](std::size_t k) {
    return std::vector<double>(c.output.begin() + static_cast<std::ptrdiff_t>(k * per_key + value_offset),
                               c.output.begin() + static_cast<std::ptrdiff_t>(k * per_key + value_offset + n));
  };
  const std::size_t keys = c.input.size();
  if (t <= c.input.front()) return value(0);
  if (t >= c.input.back()) return value(keys - 1);
  std::size_t k = 0;
  while (k + 2 < keys && c.input[k + 1] <= t) ++k;
  const double td = c.input[k + 1] - c.input[k];
  const double s = (t - c.input[k]) / td;
  std::vector<double> out(n);
  std::vector<double> v0 = value(k), v1 = value(k + 1);
  if (c.interpolation == "STEP") return v0;
  if (c.interpolation == "LINEAR") {
    if (c.path == "rotation" && nlerp) {
      const glm::dquat a(v0[3], v0[0], v0[1], v0[2]), b(v1[3], v1[0], v1[1], v1[2]);
      const glm::dquat q = glm::normalize((1.0 - s) * a + s * b);
      return {q.x, q.y, q.z, q.w};
    }
    if (c.path == "rotation") {
      glm::dquat a(v0[3], v0[0], v0[1], v0[2]), b(v1[3], v1[0], v1[1], v1[2]);
      double d = glm::dot(a, b);
      if (d < 0.0) b = -b, d = -d;
      const double angle = std::acos(std::min(d, 1.0));
      const glm::dquat q = angle < 1e-9 ? glm::normalize(a + s * (b - a))
                                        : (std::sin((1 - s) * angle) * a + std::sin(s * angle) * b) / std::sin(angle);
      return {q.x, q.y, q.z, q.w};
    }
    for (std::size_t i = 0; i < n; ++i) out[i] = (1.0 - s) * v0[i] + s * v1[i];
    return out;
  }
  const double s2 = s * s, s3 = s2 * s;
  for (std::size_t i = 0; i < n; ++i) {
    const double b0 = c.output[k * per_key + 2 * n + i];  // out-tangent of key k
    const double a1 = c.output[(k + 1) * per_key + i];    // in-tangent of key k+1
    out[i] = (2 * s3 - 3 * s2 + 1) * v0[i] + td * (s3 - 2 * s2 + s) * b0 + (-2 * s3 + 3 * s2) * v1[i] + td * (s3 - s2) * a1;
  }
  if (c.path == "rotation") {  // spec: re-normalise after interpolation
    const double len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
    for (double& x : out) x /= len;
  }
  return out;
}

}  // namespace

std::vector<double> readAccessor(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(index));
  const std::size_t n = componentCount(a.type);
  const std::size_t size = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  std::vector<double> out(a.count * n, 0.0);
  if (a.bufferView >= 0) {
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    const std::size_t stride = v.byteStride ? v.byteStride : n * size;
    const unsigned char* base = m.buffers.at(static_cast<std::size_t>(v.buffer)).data.data() + v.byteOffset + a.byteOffset;
    for (std::size_t e = 0; e < a.count; ++e) {
      for (std::size_t c = 0; c < n; ++c) out[e * n + c] = readComponent(base + e * stride + c * size, a.componentType, a.normalized);
    }
  }
  if (a.sparse.isSparse) {
    const tinygltf::BufferView& iv = m.bufferViews.at(static_cast<std::size_t>(a.sparse.indices.bufferView));
    const tinygltf::BufferView& vv = m.bufferViews.at(static_cast<std::size_t>(a.sparse.values.bufferView));
    const unsigned char* ip = m.buffers[0].data.data() + iv.byteOffset + static_cast<std::size_t>(a.sparse.indices.byteOffset);
    const unsigned char* vp = m.buffers[0].data.data() + vv.byteOffset + static_cast<std::size_t>(a.sparse.values.byteOffset);
    const std::size_t isize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.sparse.indices.componentType)));
    double previous = -1.0;
    for (int k = 0; k < a.sparse.count; ++k) {
      const double e = readComponent(ip + static_cast<std::size_t>(k) * isize, a.sparse.indices.componentType, false);
      EXPECT_GT(e, previous) << "sparse indices must increase";
      EXPECT_LT(e, static_cast<double>(a.count));
      previous = e;
      for (std::size_t c = 0; c < n; ++c) {
        out[static_cast<std::size_t>(e) * n + c] = readComponent(vp + (static_cast<std::size_t>(k) * n + c) * size, a.componentType, a.normalized);
      }
    }
  }
  return out;
}


GltfPlayback::GltfPlayback(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ok_ = loader.LoadBinaryFromFile(&model_, &err, &warn, path.string());
  EXPECT_TRUE(ok_) << err;
  if (!ok_) return;
  const tinygltf::Scene& scene = model_.scenes.at(static_cast<std::size_t>(std::max(model_.defaultScene, 0)));
  parents_.assign(model_.nodes.size(), -1);
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
    for (int child : model_.nodes[n].children) parents_[static_cast<std::size_t>(child)] = static_cast<int>(n);
  }
  for (int n : scene.nodes) {
    if (model_.nodes[static_cast<std::size_t>(n)].mesh >= 0) mesh_node_ = n;
  }
  EXPECT_GE(mesh_node_, 0) << "no mesh node at the scene root";
  if (mesh_node_ < 0) return;
  const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(mesh_node_)];
  const tinygltf::Primitive& p = model_.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
  base_ = readAccessor(model_, p.attributes.at("POSITION"));
  if (p.attributes.count("NORMAL") > 0) normals_ = readAccessor(model_, p.attributes.at("NORMAL"));
  for (const auto& target : p.targets) {
    targets_.push_back(readAccessor(model_, target.at("POSITION")));
    if (target.count("NORMAL") > 0) normal_targets_.push_back(readAccessor(model_, target.at("NORMAL")));
  }
  EXPECT_TRUE(normal_targets_.empty() || normal_targets_.size() == targets_.size()) << "NORMAL in some targets only";
  default_weights_ = node.weights.empty() ? model_.meshes[static_cast<std::size_t>(node.mesh)].weights : node.weights;
  default_weights_.resize(targets_.size(), 0.0);
  if (node.skin >= 0) {
    const tinygltf::Skin& skin = model_.skins.at(static_cast<std::size_t>(node.skin));
    joint_nodes_ = skin.joints;
    ibm_ = readAccessor(model_, skin.inverseBindMatrices);
    joints_ = readAccessor(model_, p.attributes.at("JOINTS_0"));
    weights_ = readAccessor(model_, p.attributes.at("WEIGHTS_0"));
  }
  for (const tinygltf::Animation& a : model_.animations) {
    for (const tinygltf::AnimationChannel& ch : a.channels) {
      const tinygltf::AnimationSampler& s = a.samplers.at(static_cast<std::size_t>(ch.sampler));
      channels_.push_back(Channel{ch.target_node, ch.target_path, s.interpolation, readAccessor(model_, s.input),
                                  readAccessor(model_, s.output)});
    }
  }
}

std::vector<Vec3> GltfPlayback::positionsAt(double seconds) const {
  const Pose pose = poseAt(seconds);
  std::vector<Vec3> out(vertexCount());
  for (std::size_t i = 0; i < out.size(); ++i) {
    Vec3 p = at(base_, i);  // morph targets first (spec 3.7.2.2)
    for (std::size_t k = 0; k < targets_.size(); ++k) p += pose.morph[k] * at(targets_[k], i);
    out[i] = Vec3(pose.skin(i) * glm::dvec4(p, 1.0));  // then skinning
  }
  return out;
}

std::vector<Vec3> GltfPlayback::bindNormalsAt(double seconds, bool morph_normals) const {
  const Pose pose = poseAt(seconds);
  std::vector<Vec3> out(vertexCount());
  for (std::size_t i = 0; i < out.size(); ++i) {
    Vec3 n = at(normals_, i);
    for (std::size_t k = 0; morph_normals && k < normal_targets_.size(); ++k) n += pose.morph[k] * at(normal_targets_[k], i);
    out[i] = glm::normalize(n);
  }
  return out;
}

std::vector<Vec3> GltfPlayback::normalsAt(double seconds, bool morph_normals) const {
  const Pose pose = poseAt(seconds);
  std::vector<Vec3> out = bindNormalsAt(seconds, morph_normals);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::normalize(glm::dmat3(pose.skin(i)) * out[i]);
  return out;
}

glm::dmat4 GltfPlayback::Pose::skin(std::size_t i) const {
  if (joint_matrices.empty()) return mesh_world;
  glm::dmat4 m(0.0);  // the skinned mesh node's own transform is ignored
  for (std::size_t k = 0; k < 4; ++k) {
    m += file->weights_[4 * i + k] * joint_matrices[static_cast<std::size_t>(file->joints_[4 * i + k])];
  }
  return m;
}

GltfPlayback::Pose GltfPlayback::poseAt(double seconds) const {
  Pose pose;
  pose.file = this;
  pose.morph = default_weights_;
  std::vector<std::vector<double>> t(model_.nodes.size()), r(model_.nodes.size()), s(model_.nodes.size());
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
    t[n] = model_.nodes[n].translation;
    r[n] = model_.nodes[n].rotation;
    s[n] = model_.nodes[n].scale;
  }
  for (const Channel& c : channels_) {
    const auto node = static_cast<std::size_t>(c.node);
    if (c.path == "weights") pose.morph = sample(c, seconds, targets_.size());
    if (c.path == "translation") t[node] = sample(c, seconds, 3);
    if (c.path == "rotation") r[node] = sample(c, seconds, 4, nlerp_rotations_);
    if (c.path == "scale") s[node] = sample(c, seconds, 3);
  }
  std::vector<glm::dmat4> world(model_.nodes.size());
  std::vector<bool> done(model_.nodes.size(), false);
  std::function<glm::dmat4(std::size_t)> worldOf = [&](std::size_t n) {
    if (done[n]) return world[n];
    const tinygltf::Node& node = model_.nodes[n];
    glm::dmat4 local = trs(t[n], r[n], s[n]);
    if (node.matrix.size() == 16) {
      for (int c = 0; c < 4; ++c) {
        for (int row = 0; row < 4; ++row) local[c][row] = node.matrix[4 * static_cast<std::size_t>(c) + static_cast<std::size_t>(row)];
      }
    }
    world[n] = parents_[n] < 0 ? local : worldOf(static_cast<std::size_t>(parents_[n])) * local;
    done[n] = true;
    return world[n];
  };
  for (std::size_t j = 0; j < joint_nodes_.size(); ++j) {
    glm::dmat4 ibm;
    for (int c = 0; c < 4; ++c) {
      for (int row = 0; row < 4; ++row) ibm[c][row] = ibm_[16 * j + static_cast<std::size_t>(4 * c + row)];
    }
    pose.joint_matrices.push_back(worldOf(static_cast<std::size_t>(joint_nodes_[j])) * ibm);
  }
  pose.mesh_world = worldOf(static_cast<std::size_t>(mesh_node_));
  return pose;
}

}  // namespace odeskin::testing

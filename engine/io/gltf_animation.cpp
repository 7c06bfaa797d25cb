// SPDX-License-Identifier: MIT
#include "gltf_animation.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "gltf_accessor.hpp"

namespace odeskin::gltf {
namespace {

constexpr std::array kTimeFormats{kFloat};
constexpr std::array kVectorFormats{kFloat};
// Rotations and weights may also be stored as normalized integers (spec 3.11, table of outputs).
constexpr std::array kNormalizedFormats{kFloat, kByteNorm, kUByteNorm, kShortNorm, kUShortNorm};

std::size_t morphTargetCount(const tinygltf::Model& model, const tinygltf::Node& node) {
  if (node.mesh < 0 || node.mesh >= static_cast<int>(model.meshes.size())) return 0;
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  return mesh.primitives.empty() ? 0 : mesh.primitives.front().targets.size();
}

// Spherical linear interpolation along the shorter arc (spec Appendix C), quaternions as x y z w.
std::array<double, 4> slerp(const double* a, const double* b, double u) {
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const double sign = d < 0.0 ? -1.0 : 1.0;
  d = std::abs(d);
  double wa = 1.0 - u;
  double wb = u;
  // Nearly parallel: the sine ratio loses precision, and lerp is then exact to rounding.
  if (d < 1.0 - 1e-12) {
    const double theta = std::acos(std::min(d, 1.0));
    const double s = std::sin(theta);
    wa = std::sin((1.0 - u) * theta) / s;
    wb = std::sin(u * theta) / s;
  }
  std::array<double, 4> q{};
  for (std::size_t c = 0; c < 4; ++c) q[c] = wa * a[c] + sign * wb * b[c];
  return q;
}

void normalize(std::vector<double>& q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (n > 0.0) {
    for (double& x : q) x /= n;
  }
}

}  // namespace

Result<Clip> loadClip(const tinygltf::Model& model, int index, DecodeBudget& budget) {
  const tinygltf::Animation& animation = model.animations[static_cast<std::size_t>(index)];
  Clip clip;
  clip.name = animation.name;
  for (std::size_t c = 0; c < animation.channels.size(); ++c) {
    const tinygltf::AnimationChannel& in = animation.channels[c];
    const std::string where = "animation " + std::to_string(index) + " channel " + std::to_string(c);
    if (in.target_node < 0) continue;
    Channel ch;
    if (in.target_path == "translation") {
      ch.path = ChannelPath::kTranslation;
    } else if (in.target_path == "rotation") {
      ch.path = ChannelPath::kRotation;
    } else if (in.target_path == "scale") {
      ch.path = ChannelPath::kScale;
    } else if (in.target_path == "weights") {
      ch.path = ChannelPath::kWeights;
    } else {
      continue;
    }
    if (in.target_node >= static_cast<int>(model.nodes.size())) {
      return parseError(where + ": target node " + std::to_string(in.target_node) + " does not exist");
    }
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(in.target_node)];
    ch.node = in.target_node;
    if (ch.path == ChannelPath::kWeights) {
      ch.width = morphTargetCount(model, node);
      if (ch.width == 0) {
        return parseError(where + ": animates the weights of node " + std::to_string(ch.node) +
                          ", which has no morph targets");
      }
    } else {
      if (!node.matrix.empty()) {
        return parseError(where + ": animates node " + std::to_string(ch.node) +
                          ", which has a matrix (only nodes with translation/rotation/scale may be animated)");
      }
      ch.width = ch.path == ChannelPath::kRotation ? 4 : 3;
    }
    if (in.sampler < 0 || in.sampler >= static_cast<int>(animation.samplers.size())) {
      return parseError(where + ": sampler " + std::to_string(in.sampler) + " does not exist");
    }
    const tinygltf::AnimationSampler& sampler = animation.samplers[static_cast<std::size_t>(in.sampler)];
    if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty()) {
      ch.interpolation = Interpolation::kLinear;
    } else if (sampler.interpolation == "STEP") {
      ch.interpolation = Interpolation::kStep;
    } else if (sampler.interpolation == "CUBICSPLINE") {
      ch.interpolation = Interpolation::kCubicSpline;
    } else {
      return parseError(where + ": unknown interpolation '" + sampler.interpolation + "'");
    }
    ODESKIN_ASSIGN_OR_RETURN(AccessorData input,
                             readAccessor(model, sampler.input, {where + " input", TINYGLTF_TYPE_SCALAR, kTimeFormats}, budget));
    for (std::size_t k = 1; k < input.count; ++k) {
      if (!(input.values[k] > input.values[k - 1])) {
        return parseError(where + ": keyframe times are not strictly increasing at keyframe " + std::to_string(k));
      }
    }
    const bool scalar = ch.path == ChannelPath::kWeights;
    const std::size_t per_key = (scalar ? ch.width : 1) * (ch.interpolation == Interpolation::kCubicSpline ? 3 : 1);
    AccessorRequest output{where + " output", TINYGLTF_TYPE_SCALAR, kNormalizedFormats, input.count * per_key};
    if (ch.path == ChannelPath::kRotation) output.type = TINYGLTF_TYPE_VEC4;
    if (ch.path == ChannelPath::kTranslation || ch.path == ChannelPath::kScale) {
      output.type = TINYGLTF_TYPE_VEC3;
      output.formats = kVectorFormats;
    }
    ODESKIN_ASSIGN_OR_RETURN(AccessorData values, readAccessor(model, sampler.output, output, budget));
    if (ch.path == ChannelPath::kRotation) {
      const std::size_t stride = ch.interpolation == Interpolation::kCubicSpline ? 3 : 1;
      const std::size_t first = stride == 3 ? 1 : 0;
      for (std::size_t k = 0; k < input.count; ++k) {
        const double* q = values.values.data() + 4 * (stride * k + first);
        if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] < 1e-24) {
          return parseError(where + ": keyframe " + std::to_string(k) + " is a zero quaternion");
        }
      }
    }
    ch.times_s = std::move(input.values);
    ch.values = std::move(values.values);
    clip.channels.push_back(std::move(ch));
  }
  return clip;
}

std::vector<double> sample(const Channel& channel, double time_s) {
  const std::vector<double>& t = channel.times_s;
  const std::size_t w = channel.width;
  const bool cubic = channel.interpolation == Interpolation::kCubicSpline;
  // Keyframe k's value; for CUBICSPLINE its in-tangent is at slot 0 and out-tangent at slot 2.
  auto slot = [&](std::size_t k, std::size_t s) { return channel.values.data() + (cubic ? 3 * k + s : k) * w; };
  auto value = [&](std::size_t k) { return slot(k, 1); };
  std::vector<double> out(w);
  if (t.size() == 1 || time_s <= t.front()) {
    std::copy_n(value(0), w, out.begin());
  } else if (time_s >= t.back()) {
    std::copy_n(value(t.size() - 1), w, out.begin());
  } else {
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), time_s) - t.begin()) - 1;
    const double td = t[k + 1] - t[k];
    const double u = (time_s - t[k]) / td;
    switch (channel.interpolation) {
      case Interpolation::kStep:
        std::copy_n(value(k), w, out.begin());
        break;
      case Interpolation::kLinear:
        if (channel.path == ChannelPath::kRotation) {
          const std::array<double, 4> q = slerp(value(k), value(k + 1), u);
          std::copy(q.begin(), q.end(), out.begin());
        } else {
          for (std::size_t c = 0; c < w; ++c) out[c] = (1.0 - u) * value(k)[c] + u * value(k + 1)[c];
        }
        break;
      case Interpolation::kCubicSpline: {
        // Appendix C: p(u) = (2u^3 - 3u^2 + 1) v_k + td (u^3 - 2u^2 + u) b_k + (-2u^3 + 3u^2) v_k+1
        //                    + td (u^3 - u^2) a_k+1.
        const double u2 = u * u;
        const double u3 = u2 * u;
        const double h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
        const double h10 = td * (u3 - 2.0 * u2 + u);
        const double h01 = -2.0 * u3 + 3.0 * u2;
        const double h11 = td * (u3 - u2);
        for (std::size_t c = 0; c < w; ++c) {
          out[c] = h00 * value(k)[c] + h10 * slot(k, 2)[c] + h01 * value(k + 1)[c] + h11 * slot(k + 1, 0)[c];
        }
        break;
      }
    }
  }
  if (channel.path == ChannelPath::kRotation) normalize(out);
  return out;
}

std::optional<std::pair<double, double>> keyframeSpan(const Clip& clip) {
  std::optional<std::pair<double, double>> span;
  for (const Channel& ch : clip.channels) {
    const double first = ch.times_s.front();
    const double last = ch.times_s.back();
    span = span ? std::pair{std::min(span->first, first), std::max(span->second, last)} : std::pair{first, last};
  }
  return span;
}

void applyClip(const Clip& clip, double time_s, std::span<NodeTransform> nodes, int weights_node,
               std::vector<double>& weights) {
  for (const Channel& ch : clip.channels) {
    const std::vector<double> v = sample(ch, time_s);
    NodeTransform& n = nodes[static_cast<std::size_t>(ch.node)];
    switch (ch.path) {
      case ChannelPath::kTranslation: n.translation = {v[0], v[1], v[2]}; break;
      case ChannelPath::kRotation: n.rotation = glm::dquat(v[3], v[0], v[1], v[2]); break;
      case ChannelPath::kScale: n.scale = {v[0], v[1], v[2]}; break;
      case ChannelPath::kWeights:
        if (ch.node == weights_node && weights.size() == v.size()) weights = v;
        break;
    }
  }
}

}  // namespace odeskin::gltf

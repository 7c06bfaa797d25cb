// SPDX-License-Identifier: MIT
// glTF animation sampling (internal to odeskin_gltf): channels on node translation, rotation, scale
// and morph weights; STEP, LINEAR (slerp for rotations) and CUBICSPLINE (Hermite with tangents
// scaled by the keyframe interval) per spec 3.11 and Appendix C; rotations re-normalised after
// interpolation. Before the first keyframe the first value holds, after the last the last.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "../core/result.hpp"
#include "gltf_accessor.hpp"
#include "gltf_nodes.hpp"

namespace odeskin::gltf {

enum class Interpolation { kStep, kLinear, kCubicSpline };
enum class ChannelPath { kTranslation, kRotation, kScale, kWeights };

struct Channel {
  int node = -1;
  ChannelPath path = ChannelPath::kTranslation;
  Interpolation interpolation = Interpolation::kLinear;
  std::vector<double> times_s;  // keyframe times, strictly increasing
  // Keyframe values, `width` each; CUBICSPLINE keyframes hold in-tangent, value, out-tangent.
  // Rotations are glTF quaternions (x, y, z, w).
  std::vector<double> values;
  std::size_t width = 0;  // 3 (translation, scale), 4 (rotation), morph target count (weights)
};

struct Clip {
  std::string name;
  std::vector<Channel> channels;
};

// Animation `index` with every sampler decoded and checked. kParseError naming the animation and
// channel: a sampler or node index out of range, an unknown interpolation, input times not strictly
// increasing, an output count that does not match the input count, a node that has a matrix but
// is animated (spec: only TRS nodes may be), a weights channel on a node without morph targets,
// samplers decoding to more values than `budget` has left (each channel decodes its sampler again).
// Channels with no target node or with a path other than the four core ones are skipped (they
// belong to extensions).
Result<Clip> loadClip(const tinygltf::Model& model, int index, DecodeBudget& budget);

// The span of the clip's keyframes: from its earliest first keyframe to its latest last one, or
// nullopt for a clip with no channels. Outside it every channel holds an end value.
std::optional<std::pair<double, double>> keyframeSpan(const Clip& clip);

// The channel's value at `time_s` (width numbers).
std::vector<double> sample(const Channel& channel, double time_s);

// Applies the clip at `time_s`: TRS channels overwrite `nodes`' translation, rotation and scale;
// a weights channel on node `weights_node` overwrites `weights` (its size must be the width).
void applyClip(const Clip& clip, double time_s, std::span<NodeTransform> nodes, int weights_node,
               std::vector<double>& weights);

}  // namespace odeskin::gltf

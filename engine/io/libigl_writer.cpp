// SPDX-License-Identifier: MIT
#include "libigl_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "../core/number_text.hpp"
#include "obj_io.hpp"

namespace odeskin {
namespace {

// Round-trips a double exactly, whatever the locale.
void appendNumber(std::string& text, double x) { odeskin::appendNumber(text, x, 17); }

}  // namespace

Status writeTgf(const std::filesystem::path& path, const Skeleton& s) {
  const std::size_t bones = s.boneCount();
  if (bones == 0) return invalidArgument(path.string() + ": the skeleton has no bones to write");
  if (s.tails.size() != bones || s.parents.size() != bones) {
    return invalidArgument(path.string() + ": the skeleton's heads, tails and parents are not one per bone");
  }
  double size = 0.0;
  for (std::size_t b = 0; b < bones; ++b) {
    if (!std::isfinite(glm::length(s.heads[b])) || !std::isfinite(glm::length(s.tails[b]))) {
      return invalidArgument(path.string() + ": bone " + std::to_string(b) + " has a non-finite joint");
    }
    size = std::max({size, glm::length(s.heads[b] - s.heads[0]), glm::length(s.tails[b] - s.heads[0])});
  }
  for (std::size_t b = 0; b < bones; ++b) {
    const std::int32_t p = s.parents[b];
    if (p >= static_cast<std::int32_t>(bones) || p < -1) {
      return invalidArgument(path.string() + ": bone " + std::to_string(b) + " has parent " + std::to_string(p) + " of " +
                             std::to_string(bones) + " bones");
    }
    std::int32_t q = p;
    for (std::size_t steps = 0; q >= 0; ++steps, q = s.parents[static_cast<std::size_t>(q)]) {
      if (steps > bones) return invalidArgument(path.string() + ": bone " + std::to_string(b) + " is on a cycle of parents");
    }
    if (p >= 0 && glm::length(s.heads[b] - s.tails[static_cast<std::size_t>(p)]) > 1e-9 * std::max(size, 1e-300)) {
      return invalidArgument(path.string() + ": bone " + std::to_string(b) + " does not start where its parent bone " +
                             std::to_string(p) + " ends (.tgf joins them at one joint)");
    }
  }
  // Joint 1.. : the distinct root heads, then one tail per bone.
  std::vector<Vec3> joints;
  std::vector<std::size_t> head_joint(bones);
  for (std::size_t b = 0; b < bones; ++b) {
    if (s.parents[b] >= 0) continue;
    const auto same = std::find(joints.begin(), joints.end(), s.heads[b]);
    head_joint[b] = static_cast<std::size_t>(same - joints.begin());
    if (same == joints.end()) joints.push_back(s.heads[b]);
  }
  const std::size_t first_tail = joints.size();
  for (std::size_t b = 0; b < bones; ++b) joints.push_back(s.tails[b]);
  for (std::size_t b = 0; b < bones; ++b) {
    if (s.parents[b] >= 0) head_joint[b] = first_tail + static_cast<std::size_t>(s.parents[b]);
  }
  std::string text;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    text += std::to_string(j + 1);
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      appendNumber(text, joints[j][k]);
    }
    text += '\n';
  }
  text += "#\n";
  for (std::size_t b = 0; b < bones; ++b) {
    text += std::to_string(head_joint[b] + 1) + ' ' + std::to_string(first_tail + b + 1) + '\n';
  }
  text += "#\n";
  return writeFileAtomically(path, text);
}

Status writeDmat(const std::filesystem::path& path, std::size_t rows, std::size_t cols, std::span<const double> values) {
  if (values.size() != rows * cols) {
    return invalidArgument(path.string() + ": " + std::to_string(values.size()) + " values for a " + std::to_string(rows) +
                           " x " + std::to_string(cols) + " matrix");
  }
  std::string text = std::to_string(cols) + ' ' + std::to_string(rows) + '\n';
  text.reserve(text.size() + 24 * values.size());
  for (std::size_t c = 0; c < cols; ++c) {
    for (std::size_t r = 0; r < rows; ++r) {
      const double x = values[r * cols + c];
      if (!std::isfinite(x)) {
        return invalidArgument(path.string() + ": value (" + std::to_string(r) + ", " + std::to_string(c) + ") is not finite");
      }
      appendNumber(text, x);
      text += '\n';
    }
  }
  return writeFileAtomically(path, text);
}

Status writeWeightsDmat(const std::filesystem::path& path, const Influences& influences, std::size_t bone_count) {
  const std::size_t vertices = influences.vertexCount();
  if (Status s = validateInfluences(influences, vertices, static_cast<std::uint32_t>(bone_count)); !s.ok()) {
    return invalidArgument(path.string() + ": " + s.message());
  }
  std::vector<double> dense(vertices * bone_count, 0.0);
  for (std::size_t v = 0; v < vertices; ++v) {
    for (std::uint32_t k = influences.offsets[v]; k < influences.offsets[v + 1]; ++k) {
      dense[v * bone_count + influences.bones[k]] += influences.weights[k];
    }
  }
  return writeDmat(path, vertices, bone_count, dense);
}

}  // namespace odeskin

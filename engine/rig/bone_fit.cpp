// SPDX-License-Identifier: MIT
#include "bone_fit.hpp"

#include <algorithm>

#include <Eigen/Dense>

namespace odeskin {
namespace {

Eigen::Vector3d toEigen(const Vec3& p) { return {p.x, p.y, p.z}; }

// Weighted Kabsch of rest positions onto target(e, i, w) (column entry e: vertex i, weight w) with
// weight weight_of(w) over bone b's vertices at or above its threshold (two passes about the
// centroids). `targets` keeps the first pass's targets for the second, beside the column.
template <typename Target, typename WeightOf>
Result<RigidTransform> alignBone(const BoneFitProblem& p, std::size_t b, Target target, WeightOf weight_of,
                                 std::vector<Vec3>& targets) {
  const std::uint32_t begin = p.column_offsets[b];
  targets.resize(p.column_offsets[b + 1] - begin);
  double weight_sum = 0.0;
  Vec3 from_sum(0.0);
  Vec3 to_sum(0.0);
  for (std::uint32_t e = begin; e < p.column_offsets[b + 1]; ++e) {
    const double w = p.column_weights[e];
    if (w < p.thresholds[b]) continue;
    const std::uint32_t i = p.column_vertices[e];
    const double a = weight_of(w);
    weight_sum += a;
    from_sum += a * p.rest[i];
    targets[e - begin] = target(e, i, w);
    to_sum += a * targets[e - begin];
  }
  if (!(weight_sum > 0.0)) return degenerate("bone has no weighted vertex");
  const Vec3 from_centroid = from_sum / weight_sum;
  const Vec3 to_centroid = to_sum / weight_sum;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::uint32_t e = begin; e < p.column_offsets[b + 1]; ++e) {
    const double w = p.column_weights[e];
    if (w < p.thresholds[b]) continue;
    const std::uint32_t i = p.column_vertices[e];
    h.noalias() += weight_of(w) * toEigen(p.rest[i] - from_centroid) * toEigen(targets[e - begin] - to_centroid).transpose();
  }
  return kabschFromCovariance(h, from_centroid, to_centroid);
}

RigidTransform inherit(const BoneFitProblem& p, std::size_t b, const std::vector<RigidTransform>& transforms) {
  return p.parents[b] >= 0 ? transforms[static_cast<std::size_t>(p.parents[b])] : RigidTransform{};
}

}  // namespace

BoneFitProblem makeBoneFitProblem(std::span<const Vec3> rest, const Influences& influences,
                                  std::span<const std::int32_t> parents) {
  const std::size_t bone_count = parents.size();
  BoneFitProblem p;
  p.rest = rest;
  p.influences = &influences;
  p.parents.assign(parents.begin(), parents.end());
  p.column_offsets.assign(bone_count + 1, 0);
  for (std::size_t e = 0; e < influences.bones.size(); ++e) {
    if (influences.weights[e] > 0.0) ++p.column_offsets[influences.bones[e] + 1];
  }
  for (std::size_t b = 0; b < bone_count; ++b) p.column_offsets[b + 1] += p.column_offsets[b];
  p.column_vertices.resize(p.column_offsets.back());
  p.column_weights.resize(p.column_offsets.back());
  p.thresholds.assign(bone_count, 0.0);
  std::vector<std::uint32_t> fill(p.column_offsets.begin(), p.column_offsets.end() - 1);
  for (std::size_t i = 0; i < influences.vertexCount(); ++i) {
    for (std::uint32_t e = influences.offsets[i]; e < influences.offsets[i + 1]; ++e) {
      const double w = influences.weights[e];
      if (!(w > 0.0)) continue;
      const std::uint32_t b = influences.bones[e];
      p.column_vertices[fill[b]] = static_cast<std::uint32_t>(i);
      p.column_weights[fill[b]++] = w;
      p.thresholds[b] = std::max(p.thresholds[b], w);
    }
  }
  for (double& t : p.thresholds) t *= kRelativeWeightThreshold;
  // Parents first: repeatedly take the bones whose parent is already placed (the graph is acyclic).
  std::vector<char> placed(bone_count, 0);
  while (p.order.size() < bone_count) {
    for (std::size_t b = 0; b < bone_count; ++b) {
      if (placed[b]) continue;
      const std::int32_t parent = p.parents[b];
      if (parent < 0 || placed[static_cast<std::size_t>(parent)]) {
        placed[b] = 1;
        p.order.push_back(static_cast<std::uint32_t>(b));
      }
    }
  }
  return p;
}

std::vector<RigidTransform> initialBoneTransforms(const BoneFitProblem& problem, std::span<const Vec3> pose,
                                                  std::vector<char>* inherited) {
  std::vector<RigidTransform> transforms(problem.parents.size());
  if (inherited != nullptr) inherited->assign(problem.parents.size(), 0);
  std::vector<Vec3> targets;
  for (const std::uint32_t b : problem.order) {
    Result<RigidTransform> fit = alignBone(
        problem, b, [&](std::uint32_t, std::uint32_t i, double) { return pose[i]; }, [](double w) { return w; }, targets);
    if (fit.ok()) {
      transforms[b] = fit.value();
    } else {
      transforms[b] = inherit(problem, b, transforms);
      if (inherited != nullptr) (*inherited)[b] = 1;
    }
  }
  return transforms;
}

double refineBoneTransforms(const BoneFitProblem& problem, std::span<const Vec3> pose,
                            std::vector<RigidTransform>& transforms, int max_sweeps) {
  const Influences& in = *problem.influences;
  const std::size_t vertex_count = in.vertexCount();
  std::vector<Vec3> skin(vertex_count);
  auto skinAll = [&] {
    double error = 0.0;
    for (std::size_t i = 0; i < vertex_count; ++i) {
      Vec3 s(0.0);
      for (std::uint32_t e = in.offsets[i]; e < in.offsets[i + 1]; ++e) {
        s += in.weights[e] * transforms[in.bones[e]].apply(problem.rest[i]);
      }
      skin[i] = s;
      const Vec3 d = pose[i] - s;
      error += glm::dot(d, d);
    }
    return error;
  };
  double error = skinAll();
  // Per entry of the bone's column: x_i under the bone's transform before the update (used by the
  // targets and by the update of skin), and the targets.
  std::vector<Vec3> moved, targets;
  for (int sweep = 0; sweep < max_sweeps && error > 0.0; ++sweep) {
    for (const std::uint32_t b : problem.order) {
      const RigidTransform old = transforms[b];
      const std::uint32_t begin = problem.column_offsets[b];
      moved.resize(problem.column_offsets[b + 1] - begin);
      for (std::uint32_t e = begin; e < problem.column_offsets[b + 1]; ++e) {
        moved[e - begin] = old.apply(problem.rest[problem.column_vertices[e]]);
      }
      // The point bone b alone should send x_i to, given the other bones: (p_i - others_i) / w_ib.
      auto target = [&](std::uint32_t e, std::uint32_t i, double w) {
        return (pose[i] - skin[i] + w * moved[e - begin]) / w;
      };
      Result<RigidTransform> fit = alignBone(problem, b, target, [](double w) { return w * w; }, targets);
      const RigidTransform next = fit.ok() ? fit.value() : inherit(problem, b, transforms);
      for (std::uint32_t e = begin; e < problem.column_offsets[b + 1]; ++e) {
        const std::uint32_t i = problem.column_vertices[e];
        skin[i] += problem.column_weights[e] * (next.apply(problem.rest[i]) - moved[e - begin]);
      }
      transforms[b] = next;
    }
    // Recomputed from scratch so the incremental updates above never drift.
    const double next_error = skinAll();
    const bool stalled = error - next_error <= kRefineRelativeGain * error;
    error = next_error;
    if (stalled) break;
  }
  return error;
}

}  // namespace odeskin

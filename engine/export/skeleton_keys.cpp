// SPDX-License-Identifier: MIT
#include "skeleton_keys.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <span>
#include <string>

#include "interval_bisection.hpp"

namespace odeskin {
namespace {

constexpr double kStep = 1e-4;     // finite-difference step in tau: truncation ~1e-8, rounding ~1e-12
constexpr int kRefineChecks = 7;
constexpr int kMeasureChecks = 16;

struct Frame {
  glm::dquat q{1.0, 0.0, 0.0, 0.0};
  Vec3 t{0.0};
};

// One bone's local transform at a key with one-sided derivatives d/dtau.
struct LocalKey {
  Frame value;
  glm::dquat dq_left{0.0, 0.0, 0.0, 0.0}, dq_right{0.0, 0.0, 0.0, 0.0};
  Vec3 dt_left{0.0}, dt_right{0.0};
};
using Key = std::vector<LocalKey>;

struct Sphere {
  Vec3 center{0.0};
  double radius = -1.0;  // < 0: the bone moves no vertex
};

glm::dquat aligned(const glm::dquat& q, const glm::dquat& reference) { return glm::dot(q, reference) < 0.0 ? -q : q; }

class SkeletonSampler {
 public:
  SkeletonSampler(const DeformAsset& asset, const DeformPlayer& player, std::vector<std::int32_t> parents)
      : asset_(asset), player_(player), parents_(std::move(parents)), bones_(asset.bone_count) {}

  // World frames G_b = T_b J_b: rotation of T_b, and T_b applied to the pivot.
  std::vector<Frame> worlds(std::uint32_t segment, double tau) {
    player_.bonesAt(asset_, segment, tau, bones_);
    std::vector<Frame> out(bones_.size());
    for (std::size_t b = 0; b < bones_.size(); ++b) {
      out[b].q = glm::normalize(glm::quat_cast(glm::dmat3(bones_[b])));
      out[b].t = bones_[b] * glm::dvec4(asset_.bone_pivots[b], 1.0);
    }
    return out;
  }

  std::vector<Frame> locals(std::uint32_t segment, double tau) {
    const std::vector<Frame> w = worlds(segment, tau);
    std::vector<Frame> out(w.size());
    for (std::size_t b = 0; b < w.size(); ++b) {
      const std::int32_t p = parents_[b];
      if (p < 0) {
        out[b] = w[b];
        continue;
      }
      const glm::dquat inv = glm::conjugate(w[static_cast<std::size_t>(p)].q);
      out[b].q = glm::normalize(inv * w[b].q);
      out[b].t = inv * (w[b].t - w[static_cast<std::size_t>(p)].t);
    }
    return out;
  }

  // Value and one-sided derivatives inside the segment (central where both sides fit, second-order
  // one-sided at the ends; the side outside the segment is left zero for the caller to fill).
  Key key(std::uint32_t segment, double tau) {
    const std::vector<Frame> f0 = locals(segment, tau);
    Key out(f0.size());
    for (std::size_t b = 0; b < f0.size(); ++b) out[b].value = f0[b];
    auto derivative = [&](double t1, double t2, double c0, double c1, double c2, double h, bool left, bool right) {
      const std::vector<Frame> f1 = locals(segment, t1), f2 = locals(segment, t2);
      for (std::size_t b = 0; b < f0.size(); ++b) {
        const glm::dquat q1 = aligned(f1[b].q, f0[b].q), q2 = aligned(f2[b].q, f0[b].q);
        const glm::dquat dq = (c0 * f0[b].q + c1 * q1 + c2 * q2) * (1.0 / h);
        const Vec3 dt = (c0 * f0[b].t + c1 * f1[b].t + c2 * f2[b].t) / h;
        if (left) out[b].dq_left = dq, out[b].dt_left = dt;
        if (right) out[b].dq_right = dq, out[b].dt_right = dt;
      }
    };
    if (tau - kStep >= 0.0 && tau + kStep <= 1.0) {
      derivative(tau - kStep, tau + kStep, 0.0, -0.5, 0.5, kStep, true, true);
    } else if (tau + kStep > 1.0) {
      derivative(tau - kStep, tau - 2.0 * kStep, 1.5, -2.0, 0.5, kStep, true, false);
    } else {
      derivative(tau + kStep, tau + 2.0 * kStep, -1.5, 2.0, -0.5, kStep, false, true);
    }
    return out;
  }

 private:
  const DeformAsset& asset_;
  const DeformPlayer& player_;
  std::vector<std::int32_t> parents_;
  std::vector<BoneTransform> bones_;
};

std::vector<Sphere> influenceSpheres(const DeformAsset& asset) {
  std::vector<Vec3> lo(asset.bone_count, Vec3(std::numeric_limits<double>::infinity()));
  std::vector<Vec3> hi(asset.bone_count, Vec3(-std::numeric_limits<double>::infinity()));
  const Influences& in = asset.influences;
  auto forEachPoint = [&](const std::function<void(std::uint32_t, const Vec3&)>& visit) {
    for (std::size_t i = 0; i < asset.vertexCount(); ++i) {
      for (std::uint32_t k = in.offsets[i]; k < in.offsets[i + 1]; ++k) {
        if (!(in.weights[k] > 0.0)) continue;
        for (const DeformSegment& seg : asset.segments) visit(in.bones[k], asset.rest_positions[i] + seg.base_residuals[i]);
      }
    }
  };
  forEachPoint([&](std::uint32_t b, const Vec3& x) {
    lo[b] = glm::min(lo[b], x);
    hi[b] = glm::max(hi[b], x);
  });
  std::vector<Sphere> spheres(asset.bone_count);
  for (std::uint32_t b = 0; b < asset.bone_count; ++b) {
    if (lo[b].x <= hi[b].x) spheres[b] = Sphere{0.5 * (lo[b] + hi[b]), 0.0};
  }
  forEachPoint([&](std::uint32_t b, const Vec3& x) {
    spheres[b].radius = std::max(spheres[b].radius, glm::length(x - spheres[b].center));
  });
  return spheres;
}

Key alignedTo(const Key& key, const Key& reference) {
  Key out = key;
  for (std::size_t b = 0; b < out.size(); ++b) {
    if (glm::dot(out[b].value.q, reference[b].value.q) >= 0.0) continue;
    out[b].value.q = -out[b].value.q;
    out[b].dq_left = -out[b].dq_left;
    out[b].dq_right = -out[b].dq_right;
  }
  return out;
}

Vec3 hermite3(const Vec3& v0, const Vec3& d0, const Vec3& v1, const Vec3& d1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * v0 + h * (s3 - 2.0 * s2 + s) * d0 + (-2.0 * s3 + 3.0 * s2) * v1 + h * (s3 - s2) * d1;
}

glm::dquat hermiteQ(const glm::dquat& v0, const glm::dquat& d0, const glm::dquat& v1, const glm::dquat& d1, double h,
                    double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2.0 * s3 - 3.0 * s2 + 1.0) * v0 + (h * (s3 - 2.0 * s2 + s)) * d0 + (-2.0 * s3 + 3.0 * s2) * v1 +
         (h * (s3 - s2)) * d1;
}

}  // namespace

Result<std::vector<std::uint32_t>> parentsFirst(std::span<const std::int32_t> parents) {
  const std::size_t count = parents.size();
  std::vector<std::size_t> depth(count, 0);
  for (std::size_t b = 0; b < count; ++b) {
    std::int32_t p = parents[b];
    while (p >= 0) {
      if (static_cast<std::size_t>(p) >= count) return invalidArgument("export: bone " + std::to_string(b) + " has parent " + std::to_string(p) + " out of range");
      if (++depth[b] > count) return invalidArgument("export: bone " + std::to_string(b) + " is on a cycle of bone parents");
      p = parents[static_cast<std::size_t>(p)];
    }
  }
  std::vector<std::uint32_t> order(count);
  for (std::size_t b = 0; b < count; ++b) order[b] = static_cast<std::uint32_t>(b);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });
  return order;
}

Result<SkeletonKeys> placeSkeletonKeys(const DeformAsset& asset, const DeformPlayer& player, const SkeletonKeyOptions& o) {
  if (!(o.position_tolerance > 0.0) || !(o.min_key_gap > 0.0) || o.min_key_gap > 0.25) {
    return invalidArgument("export: the skeleton tolerance and key gap must be positive");
  }
  SkeletonKeys out;
  out.interpolation = o.interpolation;
  out.parents = asset.bone_parents.empty() ? std::vector<std::int32_t>(asset.bone_count, -1) : asset.bone_parents;
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> order, parentsFirst(out.parents));
  SkeletonSampler sampler(asset, player, out.parents);
  const std::vector<Sphere> spheres = influenceSpheres(asset);
  const std::size_t bone_count = asset.bone_count;

  // The interpolated local frame between two keys (aligned quaternions). A LINEAR key's rotation is
  // glTF's slerp, or the normalized component-wise blend (`nlerp`) some importers play instead.
  enum class Rotation { kHermite, kSlerp, kNlerp };
  auto interpolate = [](const LocalKey& k0, const LocalKey& k1, double h, double s, Rotation rotation) {
    Frame local;
    switch (rotation) {
      case Rotation::kHermite:
        local.q = glm::normalize(hermiteQ(k0.value.q, k0.dq_right, k1.value.q, k1.dq_left, h, s));
        local.t = hermite3(k0.value.t, k0.dt_right, k1.value.t, k1.dt_left, h, s);
        return local;
      case Rotation::kSlerp: local.q = glm::normalize(glm::slerp(k0.value.q, k1.value.q, s)); break;
      case Rotation::kNlerp: local.q = glm::normalize((1.0 - s) * k0.value.q + s * k1.value.q); break;
    }
    local.t = (1.0 - s) * k0.value.t + s * k1.value.t;
    return local;
  };
  const bool linear = o.interpolation == KeyInterpolation::kLinear;
  const std::vector<Rotation> rotations =
      linear ? std::vector<Rotation>{Rotation::kSlerp, Rotation::kNlerp} : std::vector<Rotation>{Rotation::kHermite};

  // Worst vertex error of the interpolated skeleton at one time, relative to the tolerance.
  auto errorAt = [&](std::uint32_t segment, double a, const Key& ka, double b, const Key& kb, double s,
                     Rotation rotation) {
    std::vector<Frame> approx(bone_count);
    for (std::uint32_t bone : order) {
      const Frame local = interpolate(ka[bone], kb[bone], b - a, s, rotation);
      const std::int32_t p = out.parents[bone];
      if (p < 0) {
        approx[bone] = local;
      } else {
        const Frame& parent = approx[static_cast<std::size_t>(p)];
        approx[bone] = Frame{parent.q * local.q, parent.q * local.t + parent.t};
      }
    }
    const std::vector<Frame> exact = sampler.worlds(segment, a + s * (b - a));
    double worst = 0.0;
    for (std::size_t bone = 0; bone < bone_count; ++bone) {
      const Sphere& sphere = spheres[bone];
      if (sphere.radius < 0.0) continue;
      const Vec3 arm = sphere.center - asset.bone_pivots[bone];
      const Vec3 offset = (approx[bone].q * arm + approx[bone].t) - (exact[bone].q * arm + exact[bone].t);
      const glm::dquat d = approx[bone].q * glm::conjugate(exact[bone].q);
      const double rotation_norm = 2.0 * glm::length(Vec3(d.x, d.y, d.z));  // |R~ - R| = 2 sin(angle / 2)
      worst = std::max(worst, glm::length(offset) + rotation_norm * sphere.radius);
    }
    return worst;
  };
  auto intervalError = [&](std::uint32_t segment, double a, const Key& ka, double b, const Key& kb, int checks) {
    const Key kb_aligned = alignedTo(kb, ka);
    double worst = 0.0;
    for (const Rotation rotation : rotations) {
      for (int c = 1; c <= checks; ++c) {
        worst = std::max(worst, errorAt(segment, a, ka, b, kb_aligned, static_cast<double>(c) / (checks + 1), rotation));
      }
    }
    return worst;
  };

  struct SegmentKeys {
    std::vector<double> taus;
    std::vector<Key> keys;
  };
  std::vector<SegmentKeys> segments(asset.segments.size());
  for (std::uint32_t s = 0; s < segments.size(); ++s) {
    SegmentKeys& seg = segments[s];
    auto key_at = [&](double tau) { return sampler.key(s, tau); };
    auto too_coarse = [&](double a, const Key& ka, double b, const Key& kb) {
      return intervalError(s, a, ka, b, kb, kRefineChecks) > o.position_tolerance;
    };
    seg.taus.push_back(0.0);
    seg.keys.push_back(key_at(0.0));
    const Key start = seg.keys.back();
    bisectInterval(0.0, start, 1.0, key_at(1.0), o.min_key_gap, key_at, too_coarse, seg.taus, seg.keys);
    for (std::size_t k = 1; k < seg.taus.size(); ++k) {
      out.max_position_error = std::max(
          out.max_position_error, intervalError(s, seg.taus[k - 1], seg.keys[k - 1], seg.taus[k], seg.keys[k], kMeasureChecks));
    }
  }

  // Global keys; at a join the value and in-tangent come from the segment that ends, the out-tangent
  // from the one that starts. Quaternion signs follow the previous key.
  Key previous;
  auto emit = [&](double t, const Key& key, const Key* next_segment_start) {
    Key k = previous.empty() ? key : alignedTo(key, previous);
    if (next_segment_start) {
      const Key next = alignedTo(*next_segment_start, k);
      for (std::size_t b = 0; b < bone_count; ++b) {
        k[b].dq_right = next[b].dq_right;
        k[b].dt_right = next[b].dt_right;
      }
    }
    out.times.push_back(t);
    for (const LocalKey& bone : k) {
      out.translations.push_back(bone.value.t);
      out.translation_in.push_back(bone.dt_left);
      out.translation_out.push_back(bone.dt_right);
      out.rotations.push_back(bone.value.q);
      out.rotation_in.push_back(bone.dq_left);
      out.rotation_out.push_back(bone.dq_right);
    }
    previous = std::move(k);
  };
  emit(0.0, segments.front().keys.front(), nullptr);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const SegmentKeys& seg = segments[s];
    for (std::size_t k = 1; k < seg.taus.size(); ++k) {
      const bool join = k + 1 == seg.taus.size() && s + 1 < segments.size();
      emit(static_cast<double>(s) + seg.taus[k], seg.keys[k], join ? &segments[s + 1].keys.front() : nullptr);
    }
  }
  return out;
}

}  // namespace odeskin

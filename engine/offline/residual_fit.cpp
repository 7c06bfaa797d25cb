// SPDX-License-Identifier: MIT
#include "residual_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/SVD>

#include "../kernels/dual_quaternion.hpp"
#include "../kernels/fourier_deform_job.hpp"
#include "../kernels/lbs_job.hpp"
#include "deform_player.hpp"
#include "fourier_fit.hpp"
#include "time_basis.hpp"

namespace odeskin {
namespace {

// A blended linear part A whose smallest singular value is below this mixes nearly opposed
// rotations (PIPELINE.md 2): A^-1 would amplify the corrective more than fourfold (two equal
// weights on bones 150 degrees apart). Seen on cat-poses: one vertex's corrective reached 2.3x the box.
constexpr double kMinSingularValue = 0.25;

double smallestSingularValue(const glm::dmat3& a) {
  Eigen::MatrixXd m(3, 3);  // dynamic size: GCC 12 misreads the fixed-size SVD as uninitialised
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = a[c][r];
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues()(2);
}

// PIPELINE.md 2 falls back to a posed-space residual for such vertices; the deformer has one
// residual space per asset, so instead the vertex is bound rigidly to its dominant bone. A is then
// that bone's rotation, the bind-space residual stays exact, and the key poses are still hit.
Influences conditionedInfluences(const FitInput& in, const FitOptions& opt, std::size_t* rebound) {
  if (opt.skinning == SkinningMode::kDualQuaternion || opt.residual_space == ResidualSpace::kPosed) {
    return in.influences;  // a blended dual quaternion is always a rotation; posed residuals need no inverse
  }
  const InfluencesView view(in.influences);
  std::vector<std::vector<BoneTransform>> keys(in.key_poses.size(), std::vector<BoneTransform>(in.bone_count));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    for (std::uint32_t b = 0; b < in.bone_count; ++b) keys[k][b] = in.key_poses[k][b].matrix();
  }
  Influences out;
  for (std::size_t i = 0; i < in.rest_positions.size(); ++i) {
    const std::uint32_t begin = in.influences.offsets[i];
    const std::uint32_t end = in.influences.offsets[i + 1];
    bool singular = false;
    for (std::size_t k = 0; k < keys.size() && !singular && end - begin > 1; ++k) {
      singular = smallestSingularValue(blendedLinearPart(view, keys[k], i)) < kMinSingularValue;
    }
    if (!singular) {
      out.bones.insert(out.bones.end(), in.influences.bones.begin() + begin, in.influences.bones.begin() + end);
      out.weights.insert(out.weights.end(), in.influences.weights.begin() + begin, in.influences.weights.begin() + end);
    } else {
      std::uint32_t dominant = begin;
      for (std::uint32_t j = begin; j < end; ++j) {
        if (in.influences.weights[j] > in.influences.weights[dominant]) dominant = j;
      }
      out.bones.push_back(in.influences.bones[dominant]);
      out.weights.push_back(1.0);
      ++*rebound;
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

// The time-basis mode n that drives coefficient m of the 2N+2 layout (constant and trend: n = 0).
int modeOfCoefficient(std::size_t m, int modes) {
  if (m == 0 || m == coefficientsPerCurve(modes) - 1) return 0;
  return static_cast<int>((m + 1) / 2);
}

Status checkInput(const FitInput& in, const FitOptions& opt) {
  const std::size_t v_count = in.rest_positions.size();
  auto mismatch = [](const std::string& what, std::size_t got, std::size_t expected) {
    return invalidArgument("fit: " + what + " has " + std::to_string(got) + " entries, expected " +
                           std::to_string(expected));
  };
  if (v_count == 0) return invalidArgument("fit: the mesh has no vertices");
  if (in.poses.size() < 2) return invalidArgument("fit: needs at least 2 example poses, got " + std::to_string(in.poses.size()));
  if (in.key_poses.size() != in.poses.size()) return mismatch("key_poses", in.key_poses.size(), in.poses.size());
  for (std::size_t k = 0; k < in.poses.size(); ++k) {
    if (in.poses[k].size() != v_count) return mismatch("pose " + std::to_string(k), in.poses[k].size(), v_count);
    if (in.key_poses[k].size() != in.bone_count) {
      return mismatch("bone transforms of pose " + std::to_string(k), in.key_poses[k].size(), in.bone_count);
    }
    for (std::size_t i = 0; i < v_count; ++i) {
      const Vec3& p = in.poses[k][i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        return invalidArgument("fit: pose " + std::to_string(k) + " vertex " + std::to_string(i) + " is not finite");
      }
    }
  }
  if (in.bindings.size() != v_count) return mismatch("bindings", in.bindings.size(), v_count);
  if (in.bone_pivots.size() != in.bone_count) return mismatch("bone_pivots", in.bone_pivots.size(), in.bone_count);
  if (!opt.curve_materials.empty() && opt.curve_materials.size() != in.curves.size()) {
    return mismatch("curve_materials", opt.curve_materials.size(), in.curves.size());
  }
  if (!(opt.key_tolerance > 0.0)) return invalidArgument("fit: key tolerance must be positive");
  for (std::size_t c = 0; c < in.curves.size(); ++c) {
    const IsoCurve& curve = in.curves[c];
    if (curve.v.size() != curve.points.size()) {
      return invalidArgument("fit: curve " + std::to_string(c) + " has " + std::to_string(curve.points.size()) +
                             " points but " + std::to_string(curve.v.size()) + " parameters v");
    }
    for (const CurvePoint& p : curve.points) {
      if (p.a >= v_count || p.b >= v_count || !(p.t >= 0.0 && p.t <= 1.0)) {
        return invalidArgument("fit: curve " + std::to_string(c) + " has a point on edge (" + std::to_string(p.a) +
                               ", " + std::to_string(p.b) + ") at " + std::to_string(p.t) + ", off the mesh of " +
                               std::to_string(v_count) + " vertices");
      }
    }
  }
  return validateInfluences(in.influences, v_count, in.bone_count);
}

// r_i^k of PIPELINE.md 2 (bind space) or the posed-space residual of its section 6.
std::vector<Vec3> keyResiduals(const FitInput& in, const FitOptions& opt, const Influences& weights, std::size_t k) {
  std::vector<BoneTransform> bones(in.bone_count);
  for (std::uint32_t b = 0; b < in.bone_count; ++b) bones[b] = in.key_poses[k][b].matrix();
  const std::vector<DualQuaternion> dual = toDualQuaternions(bones);
  const InfluencesView influences(weights);
  std::vector<Vec3> residuals(in.rest_positions.size());
  for (std::size_t i = 0; i < residuals.size(); ++i) {
    const SkinTransform skin = skinTransform(opt.skinning, influences, bones, dual, i);
    const Vec3 posed = in.poses[k][i] - skin.apply(in.rest_positions[i]);
    // conditionedInfluences keeps every bind-space inverse well conditioned.
    residuals[i] = opt.residual_space == ResidualSpace::kPosed ? posed : glm::inverse(skin.linear) * posed;
  }
  return residuals;
}

// The fit of one curve with the most modes (<= N) its points determine; with none, the mean
// (closed) or the end-to-end trend (open).
Result<FourierFit> fitCurveAdaptive(std::span<const double> v, std::span<const Vec3> values, int modes, bool closed,
                                    bool adaptive) {
  // Least squares with more modes than the sampling resolves oscillates wildly in the gaps (cut
  // curves are unevenly sampled: snapped points, part seams). Mode n has period 1/n, so keep n at
  // most 1 / (2 x the widest gap in v), the sampling theorem's bound for uniform samples.
  if (adaptive && v.size() >= 2) {
    double gap = closed ? 1.0 - v.back() + v.front() : 0.0;
    for (std::size_t j = 1; j < v.size(); ++j) gap = std::max(gap, v[j] - v[j - 1]);
    if (gap > 0.0) modes = std::min(modes, static_cast<int>(std::floor(0.5 / gap)));
  }
  for (int n = modes; n >= 1; --n) {
    Result<FourierFit> fit = fitFourier(v, values, n, closed);
    if (fit.ok() || fit.status().code() != StatusCode::kIllPosed || !adaptive) return fit;
  }
  FourierFit constant;
  constant.closed = closed;
  constant.coefficients.assign(1, Vec3(0.0));
  if (closed) {
    for (const Vec3& x : values) constant.coefficients[0] += x / static_cast<double>(values.size());
  } else {
    constant.p0 = values.front();
    constant.slope = values.back() - values.front();
  }
  return constant;
}

Status fitSegmentCurves(const FitInput& in, const FitOptions& opt, const std::vector<Vec3>& delta, DeformSegment& seg,
                        std::size_t* reduced) {
  const std::size_t m_count = coefficientsPerCurve(opt.modes);
  std::vector<Vec3> values;
  for (std::size_t c = 0; c < in.curves.size(); ++c) {
    const IsoCurve& curve = in.curves[c];
    // A point on an edge moves with the same edge ratio in every pose (thesis Fig. 6.6).
    values.clear();
    for (const CurvePoint& p : curve.points) values.push_back((1.0 - p.t) * delta[p.a] + p.t * delta[p.b]);
    Result<FourierFit> fit = fitCurveAdaptive(curve.v, values, opt.modes, curve.closed, opt.adaptive_modes);
    if (!fit.ok()) {
      return Status(fit.status().code(), "curve " + std::to_string(c) + ": " + fit.status().message());
    }
    if (fit->modes < opt.modes) ++*reduced;
    Vec3* d = seg.coefficients.data() + c * m_count;
    for (std::size_t m = 0; m < fit->coefficients.size(); ++m) d[m] = fit->coefficients[m];
    // Open curves: the trend p0 + slope v joins the constant and the v term (gpu_layout.h).
    d[0] += fit->p0;
    d[m_count - 1] = fit->slope;
  }
  return okStatus();
}

}  // namespace

double longestBoxSide(std::span<const Vec3> positions) {
  if (positions.empty()) return 0.0;
  Vec3 lo(std::numeric_limits<double>::infinity());
  Vec3 hi(-std::numeric_limits<double>::infinity());
  for (const Vec3& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const Vec3 size = hi - lo;
  return std::max({size.x, size.y, size.z});
}

Status chainSegmentRates(DeformAsset& asset) {
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));
  const std::size_t m_count = coefficientsPerCurve(asset.modes);
  if (!asset.segments.empty()) asset.segments[0].rates.assign(asset.curveCount() * m_count, Vec3(0.0));
  // Rate continuity across keys (PIPELINE.md 3): the end rate of segment s-1 starts segment s.
  for (std::size_t s = 1; s < asset.segments.size(); ++s) {
    const DeformSegment& prev = asset.segments[s - 1];
    DeformSegment& seg = asset.segments[s];
    for (std::size_t c = 0; c < asset.curveCount(); ++c) {
      for (std::size_t m = 0; m < m_count; ++m) {
        const TimeBasisSample end = player.basis(asset.curve_materials[c], modeOfCoefficient(m, asset.modes)).at(1.0);
        const std::size_t k = c * m_count + m;
        seg.rates[k] = end.dgamma * prev.coefficients[k] + end.dpsi * prev.rates[k];
      }
    }
  }
  return okStatus();
}

Result<DeformAsset> fitDeformAsset(const FitInput& in, const FitOptions& opt, FitReport* report) {
  if (opt.modes < 1 || opt.modes > kMaxFourierModes) {
    return outOfRange("fit: modes N = " + std::to_string(opt.modes) + " outside 1.." + std::to_string(kMaxFourierModes));
  }
  ODESKIN_TRY(checkInput(in, opt));
  FitReport local;
  FitReport& rep = report ? *report : local;
  rep = FitReport{};

  DeformAsset asset;
  asset.modes = opt.modes;
  asset.residual_space = opt.residual_space;
  asset.skinning = opt.skinning;
  asset.rest_positions = in.rest_positions;
  asset.faces = in.faces;
  asset.bindings = in.bindings;
  asset.curves = in.curves;
  asset.materials = opt.materials.empty() ? std::vector<Material>{staticMaterial()} : opt.materials;
  asset.curve_materials = opt.curve_materials.empty() ? std::vector<std::uint32_t>(in.curves.size(), 0u)
                                                      : opt.curve_materials;
  asset.influences = conditionedInfluences(in, opt, &rep.ill_conditioned);
  asset.bone_count = in.bone_count;
  asset.bone_pivots = in.bone_pivots;
  asset.key_poses = in.key_poses;

  const std::size_t v_count = in.rest_positions.size();
  const std::size_t key_count = in.poses.size();
  const std::size_t m_count = coefficientsPerCurve(opt.modes);
  using Clock = std::chrono::steady_clock;
  auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  Clock::time_point stage = Clock::now();
  std::vector<std::vector<Vec3>> residuals(key_count);
  for (std::size_t k = 0; k < key_count; ++k) residuals[k] = keyResiduals(in, opt, asset.influences, k);
  rep.seconds_geometric = seconds_since(stage);
  stage = Clock::now();

  asset.segments.resize(key_count - 1);
  double sum_squares = 0.0;
  std::vector<Vec3> delta(v_count);
  for (std::size_t s = 0; s + 1 < key_count; ++s) {
    DeformSegment& seg = asset.segments[s];
    seg.base_residuals = residuals[s];
    seg.coefficients.assign(in.curves.size() * m_count, Vec3(0.0));
    seg.rates.assign(in.curves.size() * m_count, Vec3(0.0));
    seg.remainder_indices.assign(v_count, kNoRemainder);
    for (std::size_t i = 0; i < v_count; ++i) delta[i] = residuals[s + 1][i] - residuals[s][i];
    Status fitted = fitSegmentCurves(in, opt, delta, seg, &rep.reduced_curves);
    if (!fitted.ok()) return Status(fitted.code(), "segment " + std::to_string(s) + ": " + fitted.message());

    // Bind-space remainders bound the posed key error too: a convex blend of rotations has norm <= 1.
    const double box = longestBoxSide(in.poses[s + 1]);
    const double threshold = 0.5 * opt.key_tolerance * box;
    // At tau = 1 every gamma_n is 1 and every psi_n is 0, whatever the material.
    const std::vector<ModeBasisValue> at_key(static_cast<std::size_t>(opt.modes) + 1, ModeBasisValue{1.0, 0.0});
    for (std::size_t i = 0; i < v_count; ++i) {
      const CurveBinding& b = in.bindings[i];
      const Vec3 series = (1.0 - b.w) * curveSeries(seg.coefficients, {}, at_key, opt.modes, b.curve_a, b.v) +
                          b.w * curveSeries(seg.coefficients, {}, at_key, opt.modes, b.curve_b, b.v);
      const Vec3 eps = delta[i] - series;
      const double error = glm::length(eps);
      if (box > 0.0) {
        rep.max_series_error = std::max(rep.max_series_error, error / box);
        sum_squares += (error / box) * (error / box);
      }
      if (!opt.pure_fourier && error > threshold) {
        seg.remainder_indices[i] = static_cast<std::uint32_t>(seg.remainders.size());
        seg.remainders.push_back(eps);
      }
    }
    rep.remainder_count += seg.remainders.size();
  }

  rep.rms_series_error = std::sqrt(sum_squares / static_cast<double>(v_count * (key_count - 1)));
  rep.seconds_fourier = seconds_since(stage);
  stage = Clock::now();
  ODESKIN_TRY(chainSegmentRates(asset));
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));

  // Play every key back with the reference kernel: the error users will see, not an estimate.
  rep.key_error.assign(key_count, 0.0);
  std::vector<Vec3> played(v_count);
  for (std::size_t k = 0; k < key_count; ++k) {
    const double box = longestBoxSide(in.poses[k]);
    for (int side = 0; side < 2; ++side) {
      if ((side == 0 && k + 1 == key_count) || (side == 1 && k == 0)) continue;
      const auto segment = static_cast<std::uint32_t>(side == 0 ? k : k - 1);
      const double tau = side == 0 ? 0.0 : 1.0;
      ODESKIN_TRY(player.play(asset, segment, tau, played));
      double worst = 0.0;
      for (std::size_t i = 0; i < v_count; ++i) worst = std::max(worst, glm::length(played[i] - in.poses[k][i]));
      rep.key_error[k] = std::max(rep.key_error[k], box > 0.0 ? worst / box : worst);
    }
  }
  rep.seconds_solve = seconds_since(stage);
  return asset;
}

}  // namespace odeskin

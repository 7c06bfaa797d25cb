// SPDX-License-Identifier: MIT
#include "residual_fit.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/SVD>
#include <tbb/blocked_range.h>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"
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
// Vertices per task of the parallel per-vertex loops.
constexpr std::size_t kVertexGrain = 1024;
// The vertices' harmonics are kept from the remainders for the playback up to this size (3.7
// million vertices at N = 9, a third of what such a fit holds anyway), and computed twice above it.
constexpr std::size_t kHarmonicsTableBytes = std::size_t{512} << 20;

double smallestSingularValue(const glm::dmat3& a) {
  Eigen::MatrixXd m(3, 3);  // dynamic size: GCC 12 misreads the fixed-size SVD as uninitialised
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = a[c][r];
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues()(2);
}

// True when vertex i's blended linear part at some key has its smallest singular value below
// kMinSingularValue. Most vertices blend bones that turn alike, and a bound settles them without an
// SVD: sigma_max sigma_mid <= (sigma_max^2 + sigma_mid^2) / 2 <= |A|_F^2 / 2, so sigma_min =
// |det A| / (sigma_max sigma_mid) >= 2 |det A| / |A|_F^2. Only where that bound (less a margin far
// above the rounding of either computation) does not clear the threshold is the SVD taken, so the
// answer is the SVD's everywhere.
bool illConditioned(const InfluencesView& view, const std::vector<std::vector<BoneTransform>>& keys, std::size_t i) {
  if (view.offsets[i + 1] - view.offsets[i] <= 1) return false;
  for (const std::vector<BoneTransform>& bones : keys) {
    const glm::dmat3 a = blendedLinearPart(view, bones, i);
    double frobenius2 = 0.0;
    for (int c = 0; c < 3; ++c) frobenius2 += glm::dot(a[c], a[c]);
    const double bound = frobenius2 > 0.0 ? 2.0 * std::abs(glm::determinant(a)) / frobenius2 : 0.0;
    if (bound >= kMinSingularValue + 1e-9 * (1.0 + std::sqrt(frobenius2))) continue;
    if (smallestSingularValue(a) < kMinSingularValue) return true;
  }
  return false;
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
  const std::size_t v_count = in.rest_positions.size();
  std::vector<char> singular(v_count, 0);
  parallelFor(tbb::blocked_range<std::size_t>(0, v_count, kVertexGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) singular[i] = illConditioned(view, keys, i) ? 1 : 0;
  });
  Influences out;
  out.offsets.reserve(v_count + 1);
  out.bones.reserve(in.influences.bones.size());
  out.weights.reserve(in.influences.weights.size());
  for (std::size_t i = 0; i < v_count; ++i) {
    const std::uint32_t begin = in.influences.offsets[i];
    const std::uint32_t end = in.influences.offsets[i + 1];
    if (!singular[i]) {
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
    ODESKIN_TRY(checkedPositionBox(in.poses[k], "fit: pose " + std::to_string(k)).status());
  }
  ODESKIN_TRY(checkedPositionBox(in.rest_positions, "fit: the bind mesh").status());
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
                               ", " + std::to_string(p.b) + ") at " + messageNumber(p.t) + ", off the mesh of " +
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
  parallelFor(tbb::blocked_range<std::size_t>(0, residuals.size(), kVertexGrain),
              [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const SkinTransform skin = skinTransform(opt.skinning, influences, bones, dual, i);
      const Vec3 posed = in.poses[k][i] - skin.apply(in.rest_positions[i]);
      // conditionedInfluences keeps every bind-space inverse well conditioned.
      residuals[i] = opt.residual_space == ResidualSpace::kPosed ? posed : glm::inverse(skin.linear) * posed;
    }
  });
  return residuals;
}

// The fit of one curve with the most modes (<= N) its points determine; with none, the mean
// (closed) or the end-to-end trend (open). Whether N' modes are determined depends on the curve's
// parameters alone, so the choice and the factorised design are made once per curve and serve
// every segment.
class CurveFitPlan {
 public:
  CurveFitPlan(std::span<const double> v, int modes, bool closed, bool adaptive) : v_(v), closed_(closed), adaptive_(adaptive) {
    // Least squares with more modes than the sampling resolves oscillates wildly in the gaps (cut
    // curves are unevenly sampled: snapped points, part seams). Mode n has period 1/n, so keep n at
    // most 1 / (2 x the widest gap in v), the sampling theorem's bound for uniform samples.
    if (adaptive && v.size() >= 2) {
      double gap = closed ? 1.0 - v.back() + v.front() : 0.0;
      for (std::size_t j = 1; j < v.size(); ++j) gap = std::max(gap, v[j] - v[j - 1]);
      if (gap > 0.0) modes = std::min(modes, static_cast<int>(std::floor(0.5 / gap)));
    }
    modes_ = modes;
    for (int n = modes; n >= 1; --n) {
      Result<FourierFitter> fitter = FourierFitter::create(v, n, closed);
      if (fitter.ok()) {
        fitter_ = std::move(*fitter);
        return;
      }
      if (fitter.status().code() != StatusCode::kIllPosed || !adaptive) {
        status_ = fitter.status();
        return;
      }
    }
  }

  // What fitting `values` mode by mode with fitFourier would give.
  Result<FourierFit> fit(std::span<const Vec3> values) const {
    const bool finite = std::all_of(values.begin(), values.end(), [](const Vec3& x) { return isFinite(x); });
    if (!finite || values.size() != v_.size()) {
      // Not what the plan was made for: mode by mode, for the error fitFourier names.
      for (int n = modes_; n >= 1; --n) {
        Result<FourierFit> fit = fitFourier(v_, values, n, closed_);
        if (fit.ok() || fit.status().code() != StatusCode::kIllPosed || !adaptive_) return fit;
      }
    } else {
      if (!status_.ok()) return status_;
      if (fitter_) return fitter_->fit(values);
    }
    FourierFit constant;
    constant.closed = closed_;
    constant.coefficients.assign(1, Vec3(0.0));
    if (closed_) {
      for (const Vec3& x : values) constant.coefficients[0] += x / static_cast<double>(values.size());
    } else {
      constant.p0 = values.front();
      constant.slope = values.back() - values.front();
    }
    return constant;
  }

 private:
  std::span<const double> v_;
  bool closed_;
  bool adaptive_;
  int modes_ = 0;
  std::optional<FourierFitter> fitter_;
  Status status_ = okStatus();
};

// Every curve's series coefficients of one segment (curves in parallel; the first failing curve
// in index order is the error).
Status fitSegmentCurves(const FitInput& in, const FitOptions& opt, const std::vector<std::optional<CurveFitPlan>>& plans,
                        const std::vector<Vec3>& delta, DeformSegment& seg, std::size_t* reduced) {
  const std::size_t m_count = coefficientsPerCurve(opt.modes);
  const std::size_t c_count = in.curves.size();
  std::vector<Status> failed(c_count, okStatus());
  std::vector<char> reduced_curve(c_count, 0);
  parallelFor(tbb::blocked_range<std::size_t>(0, c_count, 4), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<Vec3> values;
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      const IsoCurve& curve = in.curves[c];
      // A point on an edge moves with the same edge ratio in every pose (thesis Fig. 6.6).
      values.clear();
      for (const CurvePoint& p : curve.points) values.push_back((1.0 - p.t) * delta[p.a] + p.t * delta[p.b]);
      Result<FourierFit> fit = plans[c]->fit(values);
      if (!fit.ok()) {
        failed[c] = Status(fit.status().code(), "curve " + std::to_string(c) + ": " + fit.status().message());
        continue;
      }
      reduced_curve[c] = fit->modes < opt.modes ? 1 : 0;
      Vec3* d = seg.coefficients.data() + c * m_count;
      for (std::size_t m = 0; m < fit->coefficients.size(); ++m) d[m] = fit->coefficients[m];
      // Open curves: the trend p0 + slope v joins the constant and the v term (gpu_layout.h).
      d[0] += fit->p0;
      d[m_count - 1] = fit->slope;
    }
  });
  for (std::size_t c = 0; c < c_count; ++c) {
    if (!failed[c].ok()) return failed[c];
    *reduced += reduced_curve[c];
  }
  return okStatus();
}

// cos(2 pi n v) into harmonics[n - 1] and sin(2 pi n v) into harmonics[N + n - 1], n = 1..N, by the
// reference kernel's expression (so the same values).
void harmonicsOf(double v, int modes, double* harmonics) {
  for (int n = 1; n <= modes; ++n) {
    const double angle = 2.0 * std::numbers::pi * n * v;
    harmonics[n - 1] = std::cos(angle);
    harmonics[modes + n - 1] = std::sin(angle);
  }
}

// S_c(v) at a key (every gamma_n = 1, psi_n = 0) from v's harmonics: curveSeries' arithmetic in
// its order, so the value is the same to the last bit, with the harmonics computed once per vertex
// instead of once per curve, segment and vertex.
Vec3 keySeries(const std::vector<Vec3>& coefficients, std::size_t m_count, int modes, std::uint32_t curve, double v,
               const double* harmonics) {

  const std::size_t base = curve * m_count;
  Vec3 sum = coefficients[base] + v * coefficients[base + m_count - 1];
  for (int n = 1; n <= modes; ++n) {
    const std::size_t mc = base + 2 * static_cast<std::size_t>(n) - 1;
    sum += harmonics[n - 1] * coefficients[mc] + harmonics[modes + n - 1] * coefficients[mc + 1];
  }
  return sum;
}

// One frame of playback: a segment at tau, its time basis and bones (reference kernel inputs).
struct KeyFrame {
  std::uint32_t segment = 0;
  std::vector<ModeBasisValue> basis;
  std::vector<BoneTransform> bones;
  std::vector<DualQuaternion> dual;  // kDualQuaternion only
};

// S_c(v) of one frame: curveSeries' arithmetic in its order (so the value is the reference
// kernel's to the last bit) with v's harmonics given (harmonicsOf).
Vec3 frameSeries(const DeformAsset& asset, const KeyFrame& frame, std::uint32_t curve, double v,
                 const double* harmonics) {
  const DeformSegment& seg = asset.segments[frame.segment];
  const std::size_t m_count = coefficientsPerCurve(asset.modes);
  const std::size_t per_material = static_cast<std::size_t>(asset.modes) + 1;
  const ModeBasisValue* mb = frame.basis.data() + asset.curve_materials[curve] * per_material;
  const std::size_t base = curve * m_count;
  const std::vector<Vec3>& coefficients = seg.coefficients;
  const std::vector<Vec3>& rates = seg.rates;
  const bool with_rates = !rates.empty();
  Vec3 sum = mb[0].gamma * (coefficients[base] + v * coefficients[base + m_count - 1]);
  if (with_rates) sum += mb[0].psi * (rates[base] + v * rates[base + m_count - 1]);
  for (int n = 1; n <= asset.modes; ++n) {
    const double c = harmonics[n - 1];
    const double s = harmonics[asset.modes + n - 1];
    const ModeBasisValue& bn = mb[n];
    const std::size_t mc = base + 2 * static_cast<std::size_t>(n) - 1;
    sum += bn.gamma * (c * coefficients[mc] + s * coefficients[mc + 1]);
    if (with_rates) sum += bn.psi * (c * rates[mc] + s * rates[mc + 1]);
  }
  return sum;
}

// Vertex i of one frame: FourierDeformJob::run's arithmetic, given the vertex's harmonics.
Vec3 framePosition(const DeformAsset& asset, const InfluencesView& influences, const KeyFrame& frame, std::size_t i,
                   const double* harmonics) {
  const DeformSegment& seg = asset.segments[frame.segment];
  const CurveBinding& b = asset.bindings[i];
  const Vec3 series_a = frameSeries(asset, frame, b.curve_a, b.v, harmonics);
  const Vec3 series_b = b.curve_b == b.curve_a ? series_a : frameSeries(asset, frame, b.curve_b, b.v, harmonics);
  Vec3 residual = (1.0 - b.w) * series_a + b.w * series_b;
  if (!seg.base_residuals.empty()) residual += seg.base_residuals[i];
  if (!seg.remainder_indices.empty() && seg.remainder_indices[i] != kNoRemainder) {
    residual += frame.basis.back().gamma * seg.remainders[seg.remainder_indices[i]];
  }
  auto skin = [&](const Vec3& x) {
    return asset.skinning == SkinningMode::kDualQuaternion
               ? skinTransform(asset.skinning, influences, frame.bones, frame.dual, i).apply(x)
               : skinPoint(influences, frame.bones, i, x);
  };
  const Vec3& rest = asset.rest_positions[i];
  return asset.residual_space == ResidualSpace::kBind ? skin(rest + residual) : skin(rest) + residual;
}

// Plays key k back (the end of segment k-1 and the start of segment k, where they exist) and
// returns the worst vertex distance from the example pose. Each frame's job is validated as the
// reference kernel validates it; every vertex then gets the kernel's position to the last bit (a
// test compares them), with its harmonics computed once for its two curves and both frames
// instead of once per curve and frame.
// `table`: every vertex's harmonics (2N each) when the caller kept them, else empty.
Result<double> playKey(const DeformAsset& asset, const DeformPlayer& player, std::span<const Vec3> pose, std::size_t k,
                       std::span<const double> table, std::vector<Vec3>& scratch) {
  const std::size_t key_count = asset.segments.size() + 1;
  std::vector<KeyFrame> frames;
  for (int side = 0; side < 2; ++side) {
    if ((side == 0 && k + 1 == key_count) || (side == 1 && k == 0)) continue;
    KeyFrame frame;
    frame.segment = static_cast<std::uint32_t>(side == 0 ? k : k - 1);
    const double tau = side == 0 ? 0.0 : 1.0;
    frame.basis.resize(player.basisSize());
    frame.bones.resize(asset.bone_count);
    player.basisAt(tau, frame.basis);
    player.bonesAt(asset, frame.segment, tau, frame.bones);
    ODESKIN_TRY(referenceJob(asset, frame.segment, frame.basis, frame.bones, scratch).validate());
    if (asset.skinning == SkinningMode::kDualQuaternion) frame.dual = toDualQuaternions(frame.bones);
    frames.push_back(std::move(frame));
  }
  const InfluencesView influences(asset.influences);
  const auto modes = static_cast<std::size_t>(asset.modes);
  return parallelReduce(
      tbb::blocked_range<std::size_t>(0, asset.vertexCount(), kVertexGrain), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double worst) {
        std::vector<double> computed(2 * modes);
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
          const double* harmonics = computed.data();
          if (table.empty()) harmonicsOf(asset.bindings[i].v, asset.modes, computed.data());
          else harmonics = table.data() + i * 2 * modes;
          for (const KeyFrame& frame : frames) {
            worst = std::max(worst, glm::length(framePosition(asset, influences, frame, i, harmonics) - pose[i]));
          }
        }
        return worst;
      },
      [](double x, double y) { return std::max(x, y); });
}

// PIPELINE.md 3's rate chaining with the time bases of `player` (made for `asset`).
void chainRates(DeformAsset& asset, const DeformPlayer& player) {
  const std::size_t m_count = coefficientsPerCurve(asset.modes);
  if (!asset.segments.empty()) asset.segments[0].rates.assign(asset.curveCount() * m_count, Vec3(0.0));
  // Each (material, mode)'s end values, once.
  std::vector<TimeBasisSample> ends(asset.materials.size() * static_cast<std::size_t>(asset.modes + 1));
  for (std::size_t m = 0; m < asset.materials.size(); ++m) {
    for (int n = 0; n <= asset.modes; ++n) {
      ends[m * static_cast<std::size_t>(asset.modes + 1) + static_cast<std::size_t>(n)] =
          player.basis(static_cast<std::uint32_t>(m), n).at(1.0);
    }
  }
  // Rate continuity across keys (PIPELINE.md 3): the end rate of segment s-1 starts segment s.
  for (std::size_t s = 1; s < asset.segments.size(); ++s) {
    const DeformSegment& prev = asset.segments[s - 1];
    DeformSegment& seg = asset.segments[s];
    for (std::size_t c = 0; c < asset.curveCount(); ++c) {
      const std::size_t material = asset.curve_materials[c];
      for (std::size_t m = 0; m < m_count; ++m) {
        const TimeBasisSample& end =
            ends[material * static_cast<std::size_t>(asset.modes + 1) + static_cast<std::size_t>(modeOfCoefficient(m, asset.modes))];
        const std::size_t k = c * m_count + m;
        seg.rates[k] = end.dgamma * prev.coefficients[k] + end.dpsi * prev.rates[k];
      }
    }
  }
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
  chainRates(asset, player);
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
  asset.bone_count = in.bone_count;
  asset.bone_pivots = in.bone_pivots;
  asset.key_poses = in.key_poses;

  const std::size_t v_count = in.rest_positions.size();
  const std::size_t key_count = in.poses.size();
  const std::size_t segment_count = key_count - 1;
  const std::size_t m_count = coefficientsPerCurve(opt.modes);
  using Clock = std::chrono::steady_clock;
  auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  // Geometric transform: the blended linear parts at every key (conditioning) and the residuals.
  Clock::time_point stage = Clock::now();
  asset.influences = conditionedInfluences(in, opt, &rep.ill_conditioned);
  std::vector<std::vector<Vec3>> residuals(key_count);
  for (std::size_t k = 0; k < key_count; ++k) residuals[k] = keyResiduals(in, opt, asset.influences, k);
  rep.seconds_geometric = seconds_since(stage);
  stage = Clock::now();

  std::vector<std::optional<CurveFitPlan>> plans(in.curves.size());
  parallelFor(tbb::blocked_range<std::size_t>(0, in.curves.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      plans[c].emplace(in.curves[c].v, opt.modes, in.curves[c].closed, opt.adaptive_modes);
    }
  });
  asset.segments.resize(segment_count);
  std::vector<Vec3> delta(v_count);
  for (std::size_t s = 0; s < segment_count; ++s) {
    DeformSegment& seg = asset.segments[s];
    seg.coefficients.assign(in.curves.size() * m_count, Vec3(0.0));
    seg.rates.assign(in.curves.size() * m_count, Vec3(0.0));
    for (std::size_t i = 0; i < v_count; ++i) delta[i] = residuals[s + 1][i] - residuals[s][i];
    Status fitted = fitSegmentCurves(in, opt, plans, delta, seg, &rep.reduced_curves);
    if (!fitted.ok()) return Status(fitted.code(), "segment " + std::to_string(s) + ": " + fitted.message());
  }

  // What the series leave of every Delta_i^s (vertices in parallel, each vertex's harmonics once
  // for both of its curves and every segment).
  std::vector<Vec3> eps(segment_count * v_count);
  const auto modes = static_cast<std::size_t>(opt.modes);
  // The harmonics serve the playback of the keys too, kept for it unless they take much memory.
  std::vector<double> table(v_count * 2 * modes * sizeof(double) <= kHarmonicsTableBytes ? v_count * 2 * modes : 0);
  parallelFor(tbb::blocked_range<std::size_t>(0, v_count, kVertexGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<double> computed(2 * modes);
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const CurveBinding& b = in.bindings[i];
      double* harmonics = table.empty() ? computed.data() : table.data() + i * 2 * modes;
      harmonicsOf(b.v, opt.modes, harmonics);
      for (std::size_t s = 0; s < segment_count; ++s) {
        const std::vector<Vec3>& coefficients = asset.segments[s].coefficients;
        const Vec3 series_a = keySeries(coefficients, m_count, opt.modes, b.curve_a, b.v, harmonics);
        const Vec3 series_b =
            b.curve_b == b.curve_a ? series_a : keySeries(coefficients, m_count, opt.modes, b.curve_b, b.v, harmonics);
        const Vec3 series = (1.0 - b.w) * series_a + b.w * series_b;
        eps[s * v_count + i] = (residuals[s + 1][i] - residuals[s][i]) - series;
      }
    }
  });
  double sum_squares = 0.0;
  for (std::size_t s = 0; s < segment_count; ++s) {
    DeformSegment& seg = asset.segments[s];
    seg.remainder_indices.assign(v_count, kNoRemainder);
    // Bind-space remainders bound the posed key error too: a convex blend of rotations has norm <= 1.
    const double box = longestBoxSide(in.poses[s + 1]);
    const double threshold = 0.5 * opt.key_tolerance * box;
    for (std::size_t i = 0; i < v_count; ++i) {
      const Vec3& e = eps[s * v_count + i];
      const double error = glm::length(e);
      if (box > 0.0) {
        rep.max_series_error = std::max(rep.max_series_error, error / box);
        sum_squares += (error / box) * (error / box);
      }
      if (!opt.pure_fourier && error > threshold) {
        seg.remainder_indices[i] = static_cast<std::uint32_t>(seg.remainders.size());
        seg.remainders.push_back(e);
      }
    }
    rep.remainder_count += seg.remainders.size();
    seg.base_residuals = std::move(residuals[s]);
  }

  rep.rms_series_error = std::sqrt(sum_squares / static_cast<double>(v_count * segment_count));
  rep.seconds_fourier = seconds_since(stage);
  stage = Clock::now();
  ODESKIN_ASSIGN_OR_RETURN(DeformPlayer player, DeformPlayer::create(asset));
  chainRates(asset, player);

  // Play every key back with the reference kernel's arithmetic: the error users will see, not an
  // estimate.
  rep.key_error.assign(key_count, 0.0);
  std::vector<Vec3> scratch(v_count);
  for (std::size_t k = 0; k < key_count; ++k) {
    const double box = longestBoxSide(in.poses[k]);
    ODESKIN_ASSIGN_OR_RETURN(const double worst, playKey(asset, player, in.poses[k], k, table, scratch));
    rep.key_error[k] = box > 0.0 ? worst / box : worst;
    // The remainders put every key within half the tolerance; a key played back farther off has
    // lost its digits to magnitudes double precision cannot hold beside the mesh's size.
    if (!std::isfinite(rep.key_error[k]) || (!opt.pure_fourier && rep.key_error[k] > opt.key_tolerance)) {
      return outOfRange("fit: the asset misses example pose " + std::to_string(k) + " by " + scientific(rep.key_error[k]) +
                        " of its box, above the key tolerance " + scientific(opt.key_tolerance) +
                        ": a position, joint or bone transform is too far out for double precision beside the "
                        "mesh's size");
    }
  }
  rep.seconds_solve = seconds_since(stage);
  return asset;
}

}  // namespace odeskin

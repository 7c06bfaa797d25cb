// SPDX-License-Identifier: MIT
#include "weight_keys.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "interval_bisection.hpp"

namespace odeskin {
namespace {

constexpr int kSamples = 2048;        // per segment, to find each curve's range and sign changes
constexpr int kRefineChecks = 7;      // interior points that decide whether an interval is halved
constexpr int kMeasureChecks = 32;    // interior points of the reported error
constexpr double kNegligible = 1e-9;  // a part below this fraction of max |g| is left out (and counted)

// One part max(sign * g, 0) at a key: its value and one-sided derivatives d/dtau. At a zero of g the
// side where the part is positive follows the slope, so a crossing key gets the kink exactly.
struct PartKey {
  double value = 0.0;
  double left = 0.0;
  double right = 0.0;
};

PartKey partAt(const WeightCurve& curve, int sign, double tau, double zero) {
  const WeightCurveSample s = curve.at(tau);
  const double g = sign * s.value;
  const double dg = sign * s.derivative;
  PartKey key{std::max(g, 0.0), 0.0, 0.0};
  if (g > zero) {
    key.left = key.right = dg;
  } else if (g >= -zero) {
    key.left = dg < 0.0 ? dg : 0.0;
    key.right = dg > 0.0 ? dg : 0.0;
  }
  return key;
}

struct Part {
  std::size_t source = 0;
  int sign = 1;
  double amplitude = 0.0;  // max |field|
  double zero = 0.0;       // |g| below this counts as a zero of g
  double scale = 0.0;
  double tolerance = 0.0;  // on the unscaled part
  double error = 0.0;      // measured, unscaled
};

struct SegmentKeys {
  std::vector<double> taus;
  std::vector<std::vector<PartKey>> keys;  // per tau, per part
  std::vector<Part> parts;
  double dropped_error = 0.0;  // position error of parts left out as negligible
};

double partValue(const WeightCurve& curve, int sign, double tau) { return std::max(sign * curve.at(tau).value, 0.0); }

// Sign changes of g on the sampling grid, each refined by bisection.
void addZeroCrossings(const WeightCurve& curve, const std::vector<double>& samples, double zero,
                      std::vector<double>& taus) {
  int last_sign = 0;
  double last_tau = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double tau = static_cast<double>(k) / kSamples;
    const int sign = samples[k] > zero ? 1 : (samples[k] < -zero ? -1 : 0);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) {
      double lo = last_tau, hi = tau;
      for (int it = 0; it < 80 && hi - lo > 1e-16; ++it) {
        const double mid = 0.5 * (lo + hi);
        (curve.at(mid).value * last_sign > 0.0 ? lo : hi) = mid;
      }
      taus.push_back(0.5 * (lo + hi));
    }
    last_sign = sign;
    last_tau = tau;
  }
}

Result<SegmentKeys> placeSegment(const ModeTargetSet& set, std::uint32_t segment, const WeightKeyOptions& o) {
  SegmentKeys seg;
  std::vector<double> taus{0.0, 1.0};
  std::vector<double> samples(kSamples + 1);
  for (std::size_t j = 0; j < set.targets.size(); ++j) {
    const ModeTarget& target = set.targets[j];
    if (target.segment != segment) continue;
    double g_max = 0.0, pos_max = 0.0, neg_max = 0.0;
    for (int k = 0; k <= kSamples; ++k) {
      const double g = target.curve.at(static_cast<double>(k) / kSamples).value;
      if (!std::isfinite(g)) return invalidArgument("export: the weight curve of target " + target.name + " is not finite");
      samples[static_cast<std::size_t>(k)] = g;
      g_max = std::max(g_max, std::abs(g));
      pos_max = std::max(pos_max, g);
      neg_max = std::max(neg_max, -g);
    }
    const double amplitude = target.field.maxLength();
    const double zero = 1e-12 * g_max;
    for (const int sign : {1, -1}) {
      const double part_max = sign > 0 ? pos_max : neg_max;
      if (part_max > kNegligible * g_max) {
        seg.parts.push_back(Part{j, sign, amplitude, zero, part_max, 0.0, 0.0});
      } else {
        seg.dropped_error += part_max * amplitude;
      }
    }
    addZeroCrossings(target.curve, samples, zero, taus);
  }
  const double tolerance_each = o.position_tolerance / static_cast<double>(std::max<std::size_t>(seg.parts.size(), 1));
  for (Part& p : seg.parts) {
    const double weight_tolerance = o.weight_tolerance * p.scale;  // on the unscaled part
    p.tolerance = p.amplitude > 0.0 ? std::min(tolerance_each / p.amplitude, weight_tolerance) : weight_tolerance;
  }

  std::sort(taus.begin(), taus.end());
  std::vector<double> start{0.0};
  for (double tau : taus) {
    if (tau - start.back() >= o.min_key_gap && 1.0 - tau >= o.min_key_gap) start.push_back(tau);
  }
  start.push_back(1.0);

  auto keyAt = [&](double tau) {
    std::vector<PartKey> keys;
    keys.reserve(seg.parts.size());
    for (const Part& p : seg.parts) keys.push_back(partAt(set.targets[p.source].curve, p.sign, tau, p.zero));
    return keys;
  };
  const bool linear = o.interpolation == KeyInterpolation::kLinear;
  // Worst |interpolated - exact| / tolerance over `checks` interior points; records errors when asked.
  auto intervalError = [&](double a, const std::vector<PartKey>& ka, double b, const std::vector<PartKey>& kb,
                           int checks, bool record) {
    double worst = 0.0;
    for (std::size_t p = 0; p < seg.parts.size(); ++p) {
      Part& part = seg.parts[p];
      const WeightCurve& curve = set.targets[part.source].curve;
      for (int c = 1; c <= checks; ++c) {
        const double s = static_cast<double>(c) / (checks + 1);
        const double exact = partValue(curve, part.sign, a + s * (b - a));
        const double keyed = linear ? (1.0 - s) * ka[p].value + s * kb[p].value
                                    : cubicHermite(ka[p].value, ka[p].right, kb[p].value, kb[p].left, b - a, s);
        const double error = std::abs(keyed - exact);
        worst = std::max(worst, error / part.tolerance);
        if (record) part.error = std::max(part.error, error);
      }
    }
    return worst;
  };

  auto too_coarse = [&](double a, const std::vector<PartKey>& ka, double b, const std::vector<PartKey>& kb) {
    return intervalError(a, ka, b, kb, kRefineChecks, false) > 1.0;
  };
  seg.taus.push_back(0.0);
  seg.keys.push_back(keyAt(0.0));
  for (std::size_t k = 1; k < start.size(); ++k) {
    const std::vector<PartKey> ka = seg.keys.back();
    bisectInterval(start[k - 1], ka, start[k], keyAt(start[k]), o.min_key_gap, keyAt, too_coarse, seg.taus, seg.keys);
  }
  for (std::size_t k = 1; k < seg.taus.size(); ++k) {
    intervalError(seg.taus[k - 1], seg.keys[k - 1], seg.taus[k], seg.keys[k], kMeasureChecks, true);
  }
  for (std::size_t p = 0; p < seg.parts.size(); ++p) {
    for (const std::vector<PartKey>& key : seg.keys) seg.parts[p].scale = std::max(seg.parts[p].scale, key[p].value);
  }
  return seg;
}

}  // namespace

Result<WeightKeys> placeWeightKeys(const ModeTargetSet& set, std::uint32_t segment_count, const WeightKeyOptions& o) {
  if (!(o.position_tolerance > 0.0) || !(o.weight_tolerance > 0.0) || !(o.min_key_gap > 0.0) || o.min_key_gap > 0.25) {
    return invalidArgument("export: the weight tolerances and key gap must be positive");
  }
  std::vector<SegmentKeys> segments;
  WeightKeys out;
  out.interpolation = o.interpolation;
  for (std::uint32_t s = 0; s < segment_count; ++s) {
    ODESKIN_ASSIGN_OR_RETURN(SegmentKeys seg, placeSegment(set, s, o));
    double position_error = seg.dropped_error;
    for (const Part& p : seg.parts) {
      out.targets.push_back(SplitTarget{p.source, p.sign, p.scale});
      out.max_weight_error = std::max(out.max_weight_error, p.error / p.scale);
      position_error += p.error * p.amplitude;
    }
    out.max_position_error = std::max(out.max_position_error, position_error);
    segments.push_back(std::move(seg));
  }

  // Global keys: segment s contributes its taus after 0 (its tau = 0 is segment s-1's tau = 1).
  struct Owner {
    std::uint32_t segment;
    std::size_t index;
  };
  std::vector<Owner> owners{{0, 0}};
  out.times.push_back(0.0);
  for (std::uint32_t s = 0; s < segment_count; ++s) {
    for (std::size_t k = 1; k < segments[s].taus.size(); ++k) {
      owners.push_back({s, k});
      out.times.push_back(static_cast<double>(s) + segments[s].taus[k]);
    }
  }
  const std::size_t key_count = out.times.size();
  const std::size_t target_count = out.targets.size();
  out.in_tangents.assign(key_count * target_count, 0.0);
  out.values.assign(key_count * target_count, 0.0);
  out.out_tangents.assign(key_count * target_count, 0.0);
  std::size_t column = 0;
  for (std::uint32_t s = 0; s < segment_count; ++s) {
    const SegmentKeys& seg = segments[s];
    for (std::size_t p = 0; p < seg.parts.size(); ++p, ++column) {
      const double scale = seg.parts[p].scale;
      bool started = false;
      for (std::size_t k = 0; k < key_count; ++k) {
        const std::size_t at = k * target_count + column;
        const Owner owner = owners[k];
        if (owner.segment == s && (owner.index > 0 || s == 0)) {
          const PartKey& key = seg.keys[owner.index][p];
          out.values[at] = key.value / scale;
          if (owner.index > 0) out.in_tangents[at] = key.left / scale;
          if (owner.index + 1 < seg.taus.size()) out.out_tangents[at] = key.right / scale;
          started = true;
        } else if (!started && owner.segment + 1 == s && owner.index + 1 == segments[owner.segment].taus.size()) {
          // The key where the segment starts (the previous segment's tau = 1).
          out.values[at] = seg.keys.front()[p].value / scale;
          out.out_tangents[at] = seg.keys.front()[p].right / scale;
          started = true;
        } else if (started) {
          out.values[at] = seg.keys.back()[p].value / scale;  // held after the segment
        }
      }
    }
  }
  return out;
}

}  // namespace odeskin

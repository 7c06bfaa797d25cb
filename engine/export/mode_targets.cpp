// SPDX-License-Identifier: MIT
#include "mode_targets.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace odeskin {
namespace {

using Member = std::pair<std::uint32_t, int>;  // (material, mode)

// Curves are merged only when they agree to rounding: a merged target must play exactly as its parts.
bool sameCurve(const WeightCurve& a, const WeightCurve& b) {
  constexpr int kSamples = 32;
  for (int k = 0; k <= kSamples; ++k) {
    const double tau = static_cast<double>(k) / kSamples;
    const WeightCurveSample sa = a.at(tau), sb = b.at(tau);
    if (std::abs(sa.value - sb.value) > 1e-12 * (1.0 + std::abs(sa.value)) ||
        std::abs(sa.derivative - sb.derivative) > 1e-12 * (1.0 + std::abs(sa.derivative))) {
      return false;
    }
  }
  return true;
}

SparseField addFields(const SparseField& a, const SparseField& b) {
  SparseField out;
  std::size_t i = 0, j = 0;
  while (i < a.vertices.size() || j < b.vertices.size()) {
    const bool take_a = j == b.vertices.size() || (i < a.vertices.size() && a.vertices[i] <= b.vertices[j]);
    const bool take_b = i == a.vertices.size() || (j < b.vertices.size() && b.vertices[j] <= a.vertices[i]);
    const std::uint32_t vertex = take_a ? a.vertices[i] : b.vertices[j];
    Vec3 value(0.0);
    if (take_a) value += a.values[i++];
    if (take_b) value += b.values[j++];
    if (value != Vec3(0.0)) {
      out.vertices.push_back(vertex);
      out.values.push_back(value);
    }
  }
  return out;
}

// "m0.n0-9" for consecutive modes of one material, joined by '+' across materials.
std::string describeMembers(std::vector<Member> members) {
  std::sort(members.begin(), members.end());
  std::string text;
  for (std::size_t k = 0; k < members.size();) {
    std::size_t end = k + 1;
    while (end < members.size() && members[end].first == members[k].first &&
           members[end].second == members[end - 1].second + 1) {
      ++end;
    }
    // Appended piece by piece: GCC 12's -Wrestrict misfires on "m" + std::to_string(...) here.
    if (!text.empty()) text.push_back('+');
    text.push_back('m');
    text.append(std::to_string(members[k].first)).append(".n").append(std::to_string(members[k].second));
    if (end - k > 1) text.append("-").append(std::to_string(members[end - 1].second));
    k = end;
  }
  return text;
}

std::string segmentName(std::uint32_t s) {
  std::string name(1, 's');
  return name.append(std::to_string(s));
}

// Vertices that take part of material m's series: through curve a (weight 1 - w) or curve b (w).
std::vector<std::uint32_t> materialVertices(const DeformAsset& asset, std::uint32_t m) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < asset.bindings.size(); ++i) {
    const CurveBinding& b = asset.bindings[i];
    if ((asset.curve_materials[b.curve_a] == m && b.w < 1.0) || (asset.curve_materials[b.curve_b] == m && b.w > 0.0)) {
      out.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return out;
}

struct Candidate {
  WeightCurve curve;
  SparseField field;
  std::vector<Member> members;
};

// Field of one (material, mode, kind) over `vertices`: the kernel's curveSeries with a unit basis
// (1 in this mode's gamma or psi, 0 elsewhere), blended as the kernel blends.
SparseField modeField(const DeformAsset& asset, const DeformSegment& seg, std::uint32_t m, int n, WeightCurveKind kind,
                      const std::vector<std::uint32_t>& vertices) {
  std::vector<ModeBasisValue> unit(static_cast<std::size_t>(asset.modes) + 1);
  unit[static_cast<std::size_t>(n)] = kind == WeightCurveKind::kGamma ? ModeBasisValue{1.0, 0.0} : ModeBasisValue{0.0, 1.0};
  const std::span<const Vec3> rates = kind == WeightCurveKind::kPsi ? std::span<const Vec3>(seg.rates) : std::span<const Vec3>();
  SparseField field;
  for (std::uint32_t i : vertices) {
    const CurveBinding& b = asset.bindings[i];
    Vec3 sum(0.0);
    if (asset.curve_materials[b.curve_a] == m && b.w < 1.0) {
      sum += (1.0 - b.w) * curveSeries(seg.coefficients, rates, unit, asset.modes, b.curve_a, b.v);
    }
    if (asset.curve_materials[b.curve_b] == m && b.w > 0.0) {
      sum += b.w * curveSeries(seg.coefficients, rates, unit, asset.modes, b.curve_b, b.v);
    }
    if (sum != Vec3(0.0)) {
      field.vertices.push_back(i);
      field.values.push_back(sum);
    }
  }
  return field;
}

bool anyNonZero(const std::vector<Vec3>& values) {
  return std::any_of(values.begin(), values.end(), [](const Vec3& v) { return v != Vec3(0.0); });
}

}  // namespace

WeightCurveSample WeightCurve::at(double tau) const {
  switch (kind) {
    case WeightCurveKind::kGamma: {
      const TimeBasisSample s = basis->at(tau);
      return {s.gamma, s.dgamma};
    }
    case WeightCurveKind::kPsi: {
      const TimeBasisSample s = basis->at(tau);
      return {s.psi, s.dpsi};
    }
    case WeightCurveKind::kRemainder:
      break;
  }
  return {remainderWeight(tau), 6.0 * tau * (1.0 - tau)};
}

double SparseField::maxLength() const {
  double out = 0.0;
  for (const Vec3& v : values) out = std::max(out, glm::length(v));
  return out;
}

Result<ModeTargetSet> buildModeTargets(const DeformAsset& asset, const DeformPlayer& player,
                                       const ModeTargetOptions& options) {
  if (asset.residual_space != ResidualSpace::kBind) {
    return invalidArgument("export: a posed-space residual is added after skinning; glTF morph targets come before it");
  }
  ModeTargetSet set;
  const std::size_t v_count = asset.vertexCount();
  const auto material_count = static_cast<std::uint32_t>(asset.materials.size());
  std::vector<std::vector<std::uint32_t>> material_vertices(material_count);
  for (std::uint32_t m = 0; m < material_count; ++m) material_vertices[m] = materialVertices(asset, m);
  const auto segment_count = static_cast<std::uint32_t>(asset.segments.size());
  std::vector<Vec3> played(v_count);

  for (std::uint32_t s = 0; s < segment_count; ++s) {
    const DeformSegment& seg = asset.segments[s];
    const bool has_rates = anyNonZero(seg.rates);
    for (const WeightCurveKind kind : {WeightCurveKind::kGamma, WeightCurveKind::kPsi}) {
      std::vector<Candidate> candidates;
      for (std::uint32_t m = 0; m < material_count; ++m) {
        if (material_vertices[m].empty()) continue;
        for (int n = 0; n <= asset.modes; ++n) {
          const ModeTimeBasis& basis = player.basis(m, n);
          // psi is identically zero where the rate is ignored (first-order and static modes).
          if (kind == WeightCurveKind::kPsi && (!has_rates || basis.rateIgnored())) continue;
          SparseField field = modeField(asset, seg, m, n, kind, material_vertices[m]);
          if (field.vertices.empty()) {
            ++set.zero_fields;
            continue;
          }
          WeightCurve curve{kind, basis};
          auto same = std::find_if(candidates.begin(), candidates.end(),
                                   [&](const Candidate& c) { return sameCurve(c.curve, curve); });
          if (same == candidates.end()) {
            candidates.push_back(Candidate{curve, std::move(field), {{m, n}}});
            continue;
          }
          same->field = addFields(same->field, field);
          same->members.emplace_back(m, n);
          ++set.merged_fields;
        }
      }
      for (Candidate& c : candidates) {
        if (c.field.vertices.empty()) continue;  // merged parts that cancelled exactly
        ModeTarget target;
        target.segment = s;
        target.name = segmentName(s);
        target.name.append(kind == WeightCurveKind::kGamma ? ".gamma." : ".psi.").append(describeMembers(c.members));
        target.curve = c.curve;
        target.field = std::move(c.field);
        set.targets.push_back(std::move(target));
      }
    }

    // The series at tau = 1 as the targets hold it after the segment.
    std::fill(played.begin(), played.end(), Vec3(0.0));
    for (const ModeTarget& t : set.targets) {
      if (t.segment != s) continue;
      const double held = t.curve.at(1.0).value;
      for (std::size_t k = 0; k < t.field.vertices.size(); ++k) played[t.field.vertices[k]] += held * t.field.values[k];
    }
    ModeTarget correction;
    correction.segment = s;
    correction.curve.kind = WeightCurveKind::kRemainder;
    const bool last = s + 1 == segment_count;
    correction.name = segmentName(s);
    correction.name.append(last ? ".remainder" : ".key");
    for (std::size_t i = 0; i < v_count; ++i) {
      const bool has_eps = !seg.remainder_indices.empty() && seg.remainder_indices[i] != kNoRemainder;
      const Vec3 eps = has_eps ? seg.remainders[seg.remainder_indices[i]] : Vec3(0.0);
      Vec3 value = eps;
      if (!last) {
        value = asset.segments[s + 1].base_residuals[i] - seg.base_residuals[i] - played[i];
        set.max_player_deviation = std::max(set.max_player_deviation, glm::length(value - eps));
      }
      if (value != Vec3(0.0)) {
        correction.field.vertices.push_back(static_cast<std::uint32_t>(i));
        correction.field.values.push_back(value);
      }
    }
    if (!correction.field.vertices.empty() || options.keep_zero_corrections) {
      set.targets.push_back(std::move(correction));
    } else {
      ++set.zero_fields;
    }
  }
  return set;
}

}  // namespace odeskin

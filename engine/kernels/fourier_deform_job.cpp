// SPDX-License-Identifier: MIT
#include "fourier_deform_job.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../core/number_text.hpp"
#include "dual_quaternion.hpp"
#include "lbs_job.hpp"

namespace odeskin {
namespace {

constexpr int kMaxModes = 64;

Vec3 jobSeries(const FourierDeformJob& job, std::uint32_t curve, double v) {
  const std::size_t per_material = static_cast<std::size_t>(job.modes) + 1;
  return curveSeries(job.coefficients, job.rates,
                     job.basis.subspan(job.curve_materials[curve] * per_material, per_material), job.modes, curve, v);
}

Status sizeError(const char* field, std::size_t got, std::size_t expected) {
  return invalidArgument(std::string("fourier deform: ") + field + " has " + std::to_string(got) +
                         " entries, expected " + std::to_string(expected));
}

}  // namespace

// Harmonics by direct cos/sin: the reference does not use the fast paths' recurrence, so it checks
// them independently.
Vec3 curveSeries(std::span<const Vec3> coefficients, std::span<const Vec3> rates,
                 std::span<const ModeBasisValue> material_basis, int modes, std::uint32_t curve, double v) {
  const std::size_t m_count = coefficientsPerCurve(modes);
  const std::size_t base = curve * m_count;
  const bool with_rates = !rates.empty();
  const ModeBasisValue& b0 = material_basis[0];
  Vec3 sum = b0.gamma * (coefficients[base] + v * coefficients[base + m_count - 1]);
  if (with_rates) sum += b0.psi * (rates[base] + v * rates[base + m_count - 1]);
  for (int n = 1; n <= modes; ++n) {
    const double angle = 2.0 * std::numbers::pi * n * v;
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const ModeBasisValue& bn = material_basis[static_cast<std::size_t>(n)];
    const std::size_t mc = base + 2 * static_cast<std::size_t>(n) - 1;
    sum += bn.gamma * (c * coefficients[mc] + s * coefficients[mc + 1]);
    if (with_rates) sum += bn.psi * (c * rates[mc] + s * rates[mc + 1]);
  }
  return sum;
}

Status FourierDeformJob::validate() const {
  if (modes < 1 || modes > kMaxModes) {
    return outOfRange("fourier deform: modes N = " + std::to_string(modes) + " outside 1.." +
                      std::to_string(kMaxModes));
  }
  if (skinning != SkinningMode::kLinear && skinning != SkinningMode::kDualQuaternion) {
    return invalidArgument("fourier deform: unknown skinning mode " +
                           std::to_string(static_cast<std::uint32_t>(skinning)));
  }
  const std::size_t vertex_count = rest_positions.size();
  const std::size_t curve_count = curve_materials.size();
  const std::size_t m_count = coefficientsPerCurve(modes);
  if (bindings.size() != vertex_count) return sizeError("bindings", bindings.size(), vertex_count);
  if (out_positions.size() != vertex_count) return sizeError("out_positions", out_positions.size(), vertex_count);
  if (!base_residuals.empty() && base_residuals.size() != vertex_count) {
    return sizeError("base_residuals", base_residuals.size(), vertex_count);
  }
  if (!remainder_indices.empty() && remainder_indices.size() != vertex_count) {
    return sizeError("remainder_indices", remainder_indices.size(), vertex_count);
  }
  if (coefficients.size() != curve_count * m_count) {
    return sizeError("coefficients", coefficients.size(), curve_count * m_count);
  }
  if (!rates.empty() && rates.size() != curve_count * m_count) return sizeError("rates", rates.size(), curve_count * m_count);
  const std::size_t per_material = static_cast<std::size_t>(modes) + 1;
  // material_count x (N+1) mode entries plus the remainder weight (gpu_layout.h).
  if (basis.size() < per_material + 1 || (basis.size() - 1) % per_material != 0) {
    return invalidArgument("fourier deform: basis has " + std::to_string(basis.size()) +
                           " entries, not a positive multiple of N+1 = " + std::to_string(per_material) +
                           " plus the remainder weight");
  }
  const std::size_t material_count = (basis.size() - 1) / per_material;
  for (const ModeBasisValue& b : basis) {
    if (!std::isfinite(b.gamma) || !std::isfinite(b.psi)) return invalidArgument("fourier deform: non-finite basis value");
  }
  for (std::size_t c = 0; c < curve_count; ++c) {
    if (curve_materials[c] >= material_count) {
      return invalidArgument("fourier deform: curve " + std::to_string(c) + " uses material " +
                             std::to_string(curve_materials[c]) + " of " + std::to_string(material_count));
    }
  }
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const CurveBinding& b = bindings[i];
    if (b.curve_a >= curve_count || b.curve_b >= curve_count) {
      return invalidArgument("fourier deform: vertex " + std::to_string(i) + " is bound to a curve beyond " +
                             std::to_string(curve_count));
    }
    if (!(b.w >= 0.0 && b.w <= 1.0) || !std::isfinite(b.v)) {
      return invalidArgument("fourier deform: vertex " + std::to_string(i) + " has blend weight " +
                             messageNumber(b.w) + " or parameter " + messageNumber(b.v) + " out of range");
    }
    if (!remainder_indices.empty() && remainder_indices[i] != kNoRemainder &&
        remainder_indices[i] >= remainders.size()) {
      return invalidArgument("fourier deform: vertex " + std::to_string(i) + " references remainder " +
                             std::to_string(remainder_indices[i]) + " of " + std::to_string(remainders.size()));
    }
  }
  ODESKIN_TRY(validateBones(bones, "fourier deform"));
  return validateInfluences(influences, vertex_count, static_cast<std::uint32_t>(bones.size()));
}

Status FourierDeformJob::run() const {
  ODESKIN_TRY(validate());
  const bool dual_quaternion = skinning == SkinningMode::kDualQuaternion;
  std::vector<DualQuaternion> dual_quaternions;
  if (dual_quaternion) dual_quaternions = toDualQuaternions(bones);
  // Linear blend skinning keeps its own sum (skinPoint), so kLinear output is unchanged bit for bit.
  auto skin = [&](std::size_t i, const Vec3& x) {
    return dual_quaternion ? skinTransform(skinning, influences, bones, dual_quaternions, i).apply(x)
                           : skinPoint(influences, bones, i, x);
  };
  for (std::size_t i = 0; i < rest_positions.size(); ++i) {
    const CurveBinding& b = bindings[i];
    const Vec3 series_a = jobSeries(*this, b.curve_a, b.v);
    const Vec3 series_b = b.curve_b == b.curve_a ? series_a : jobSeries(*this, b.curve_b, b.v);
    Vec3 residual = (1.0 - b.w) * series_a + b.w * series_b;
    if (!base_residuals.empty()) residual += base_residuals[i];
    if (!remainder_indices.empty() && remainder_indices[i] != kNoRemainder) {
      residual += basis.back().gamma * remainders[remainder_indices[i]];
    }
    out_positions[i] = residual_space == ResidualSpace::kBind ? skin(i, rest_positions[i] + residual)
                                                              : skin(i, rest_positions[i]) + residual;
  }
  return okStatus();
}

}  // namespace odeskin

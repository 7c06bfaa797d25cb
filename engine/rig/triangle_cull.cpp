// SPDX-License-Identifier: MIT
#include "triangle_cull.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// In units of the largest reach, the float tests are off by a few 1e-7 at most (inputs below 1, a
// handful of roundings): a margin of 1e-5 keeps every triangle met and adds few that are not.
constexpr float kMargin = 1e-5F;

}  // namespace

TriangleCull::TriangleCull(const std::vector<Vec3>& middles, const std::vector<double>& radii) : size_(middles.size()) {
  double reach = 0.0;
  for (std::size_t t = 0; t < size_; ++t) reach = std::max(reach, glm::length(middles[t]) + radii[t]);
  // A point with every triangle on it, or lengths past double range, leaves no unit: every
  // triangle then stays in every list.
  keep_all_ = !(reach > 0.0 && std::isfinite(reach));
  const std::size_t padded = (size_ + kBlock - 1) / kBlock * kBlock;
  x_.assign(padded, 0.0F);
  y_.assign(padded, 0.0F);
  z_.assign(padded, 0.0F);
  squared_length_.assign(padded, 0.0F);
  radius_.assign(padded, -1.0F);
  squared_radius_.assign(padded, -1.0F);
  const double inverse = keep_all_ ? 0.0 : 1.0 / reach;  // a rounding more is nothing to the margin
  for (std::size_t t = 0; t < size_; ++t) {
    if (keep_all_) {
      radius_[t] = squared_radius_[t] = 1.0F;
      continue;
    }
    const Vec3 m = middles[t] * inverse;
    const double r = radii[t] * inverse;
    x_[t] = static_cast<float>(m.x);
    y_[t] = static_cast<float>(m.y);
    z_[t] = static_cast<float>(m.z);
    squared_length_[t] = static_cast<float>(glm::dot(m, m));
    radius_[t] = static_cast<float>(r) + kMargin;
    squared_radius_[t] = static_cast<float>(r * r) + kMargin;
  }
}

void TriangleCull::nearPlane(const Vec3& normal, std::vector<std::uint32_t>& out) const {
  const auto nx = static_cast<float>(normal.x);
  const auto ny = static_cast<float>(normal.y);
  const auto nz = static_cast<float>(normal.z);
  collect(
      [&](std::size_t base, std::array<std::uint8_t, kBlock>& flags) {
        const float* x = x_.data() + base;
        const float* y = y_.data() + base;
        const float* z = z_.data() + base;
        const float* r = radius_.data() + base;
        std::uint8_t any = 0;
        for (std::size_t j = 0; j < kBlock; ++j) {
          const float d = nx * x[j] + ny * y[j] + nz * z[j];
          flags[j] = std::abs(d) <= r[j] ? 1 : 0;
          any = static_cast<std::uint8_t>(any | flags[j]);
        }
        return any != 0;
      },
      out);
}

void TriangleCull::nearLine(const Vec3& direction, std::vector<std::uint32_t>& out) const {
  const auto dx = static_cast<float>(direction.x);
  const auto dy = static_cast<float>(direction.y);
  const auto dz = static_cast<float>(direction.z);
  collect(
      [&](std::size_t base, std::array<std::uint8_t, kBlock>& flags) {
        const float* x = x_.data() + base;
        const float* y = y_.data() + base;
        const float* z = z_.data() + base;
        const float* m2 = squared_length_.data() + base;
        const float* r2 = squared_radius_.data() + base;
        std::uint8_t any = 0;
        for (std::size_t j = 0; j < kBlock; ++j) {
          const float along = dx * x[j] + dy * y[j] + dz * z[j];
          flags[j] = m2[j] - along * along <= r2[j] ? 1 : 0;
          any = static_cast<std::uint8_t>(any | flags[j]);
        }
        return any != 0;
      },
      out);
}

}  // namespace odeskin

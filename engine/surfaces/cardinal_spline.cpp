// SPDX-License-Identifier: MIT
#include "cardinal_spline.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace odeskin {

Result<ClampedCubicSpline> ClampedCubicSpline::fit(std::span<const double> values, double slope_begin,
                                                   double slope_end) {
  if (values.size() < 2) return invalidArgument("clamped spline: need at least two knot values");
  for (std::size_t j = 0; j < values.size(); ++j) {
    if (!std::isfinite(values[j])) return invalidArgument("clamped spline: knot value " + std::to_string(j) + " is not finite");
  }
  if (!std::isfinite(slope_begin) || !std::isfinite(slope_end)) {
    return invalidArgument("clamped spline: an end slope is not finite");
  }
  const std::size_t n = values.size() - 1;
  const double h = 1.0 / static_cast<double>(n);
  ClampedCubicSpline s;
  s.values_.assign(values.begin(), values.end());
  s.slopes_.assign(n + 1, 0.0);
  s.slopes_[0] = slope_begin;
  s.slopes_[n] = slope_end;
  if (n >= 2) {
    // Thomas algorithm on the (n-1) x (n-1) system with diagonal 4 and off-diagonals 1; the known
    // end slopes move to the right-hand side of the first and last rows.
    const std::size_t m = n - 1;
    std::vector<double> c(m, 0.0);  // modified super-diagonal
    std::vector<double> d(m, 0.0);  // modified right-hand side
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = i + 1;
      double rhs = 3.0 * (values[j + 1] - values[j - 1]) / h;
      if (j == 1) rhs -= slope_begin;
      if (j == n - 1) rhs -= slope_end;
      const double denom = 4.0 - (i > 0 ? c[i - 1] : 0.0);
      c[i] = 1.0 / denom;
      d[i] = (rhs - (i > 0 ? d[i - 1] : 0.0)) / denom;
    }
    for (std::size_t i = m; i-- > 0;) {
      s.slopes_[i + 1] = d[i] - (i + 1 < m ? c[i] * s.slopes_[i + 2] : 0.0);
    }
  }
  return s;
}

namespace {

struct Piece {
  std::size_t j;  // cppcheck-suppress unusedStructMember ; read through structured bindings
  double s;       // cppcheck-suppress unusedStructMember ; as above
};

Piece locate(double u, std::size_t n) {
  const double x = u * static_cast<double>(n);
  const double j = std::clamp(std::floor(x), 0.0, static_cast<double>(n - 1));
  return {static_cast<std::size_t>(j), x - j};
}

}  // namespace

double ClampedCubicSpline::at(double u) const {
  const std::size_t n = pieces();
  const double h = 1.0 / static_cast<double>(n);
  const auto [j, s] = locate(u, n);
  const double h00 = (1.0 - s) * (1.0 - s) * (1.0 + 2.0 * s);
  const double h10 = s * (1.0 - s) * (1.0 - s);
  const double h01 = s * s * (3.0 - 2.0 * s);
  const double h11 = -s * s * (1.0 - s);
  return values_[j] * h00 + h * slopes_[j] * h10 + values_[j + 1] * h01 + h * slopes_[j + 1] * h11;
}

double ClampedCubicSpline::derivative(double u) const {
  const std::size_t n = pieces();
  const double h = 1.0 / static_cast<double>(n);
  const auto [j, s] = locate(u, n);
  // d/du = (1/h) d/ds of the Hermite form.
  const double d00 = -6.0 * s * (1.0 - s);
  const double d10 = (1.0 - s) * (1.0 - 3.0 * s);
  const double d01 = 6.0 * s * (1.0 - s);
  const double d11 = s * (3.0 * s - 2.0);
  return (values_[j] * d00 + values_[j + 1] * d01) / h + slopes_[j] * d10 + slopes_[j + 1] * d11;
}

std::array<double, 4> ClampedCubicSpline::pieceCoefficients(std::size_t j) const {
  const double h = 1.0 / static_cast<double>(pieces());
  const double f0 = values_[j], f1 = values_[j + 1];
  const double m0 = h * slopes_[j], m1 = h * slopes_[j + 1];
  return {f0, m0, 3.0 * (f1 - f0) - 2.0 * m0 - m1, 2.0 * (f0 - f1) + m0 + m1};
}

Result<CardinalSpline> CardinalSpline::fit(const Ode4Cardinal& cardinal, int pieces) {
  if (pieces < 1 || pieces > 100000) {
    return outOfRange("cardinal spline: " + std::to_string(pieces) + " pieces, expected 1 to 100000");
  }
  const auto n = static_cast<std::size_t>(pieces);
  std::array<std::vector<double>, 4> values;
  for (auto& v : values) v.resize(n + 1);
  CardinalSample first, last;
  for (std::size_t j = 0; j <= n; ++j) {
    const CardinalSample s = cardinal.at(static_cast<double>(j) / static_cast<double>(n));
    for (std::size_t k = 0; k < 4; ++k) values[k][j] = s.r[k];
    if (j == 0) first = s;
    if (j == n) last = s;
  }
  CardinalSpline out;
  out.pieces_ = pieces;
  for (std::size_t k = 0; k < 4; ++k) {
    ODESKIN_ASSIGN_OR_RETURN(ClampedCubicSpline spline, ClampedCubicSpline::fit(values[k], first.dr[k], last.dr[k]));
    out.splines_.push_back(std::move(spline));
  }
  return out;
}

CardinalSample CardinalSpline::at(double u) const {
  CardinalSample s;
  for (std::size_t k = 0; k < 4; ++k) {
    s.r[k] = splines_[k].at(u);
    s.dr[k] = splines_[k].derivative(u);
  }
  return s;
}

}  // namespace odeskin

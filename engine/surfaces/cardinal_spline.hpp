// SPDX-License-Identifier: MIT
// Clamped cubic spline approximation of the cardinal functions (thesis Sec. 3.7, MATH.md 2.11),
// the form a CAD system takes: each r_k becomes n cubic pieces on u_j = j/n that interpolate
// r_k(u_j), match r_k' at u = 0 and u = 1 and are C2 at the interior knots, so the approximate
// surface S ~ sum_k f_k(u) B_k(v) still meets all four position and tangent constraints exactly.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "ode4_cardinal.hpp"

namespace odeskin {

// One clamped cubic spline on n uniform pieces of [0, 1]: knot values f_j, end slopes m_0, m_n,
// interior slopes from m_{j-1} + 4 m_j + m_{j+1} = 3 (f_{j+1} - f_{j-1}) / h (Thomas algorithm).
class ClampedCubicSpline {
 public:
  // `values` holds f_0..f_n (n + 1 >= 2 entries). kInvalidArgument for fewer than two values or a
  // non-finite value or slope.
  static Result<ClampedCubicSpline> fit(std::span<const double> values, double slope_begin, double slope_end);

  double at(double u) const;          // f(u); u outside [0, 1] extends the end pieces
  double derivative(double u) const;  // f'(u)
  std::size_t pieces() const { return values_.size() - 1; }
  const std::vector<double>& knotSlopes() const { return slopes_; }  // m_0..m_n (per unit u)
  // Power-basis coefficients (c0, c1, c2, c3) of piece j in its local s = (u - u_j)/h in [0, 1]:
  // f = c0 + c1 s + c2 s^2 + c3 s^3 (what a CAD file stores). Precondition: j < pieces().
  std::array<double, 4> pieceCoefficients(std::size_t j) const;

 private:
  ClampedCubicSpline() = default;
  std::vector<double> values_;  // f_0..f_n
  std::vector<double> slopes_;  // m_0..m_n
};

// The four cardinal functions of one Ode4Cardinal, each approximated by a ClampedCubicSpline.
class CardinalSpline {
 public:
  // kOutOfRange unless 1 <= pieces <= 100000.
  static Result<CardinalSpline> fit(const Ode4Cardinal& cardinal, int pieces);

  CardinalSample at(double u) const;
  const ClampedCubicSpline& component(int k) const { return splines_[static_cast<std::size_t>(k)]; }  // k = 0..3
  int pieces() const { return pieces_; }

 private:
  CardinalSpline() = default;
  std::vector<ClampedCubicSpline> splines_;
  int pieces_ = 0;
};

}  // namespace odeskin

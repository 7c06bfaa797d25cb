// SPDX-License-Identifier: MIT
// Patch networks for the surfaces tests: iso-curves of a known swept surface T(xi, theta), where
// xi = row + u runs across boundaries and theta around (closed) or along (open) the curves. The
// boundaries cycle through every way of giving derivatives: coefficients, control curves after,
// derivative curves measured on T, control curves before.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "engine/surfaces/network.hpp"

namespace odeskin::testing {

struct SweptSurface {
  bool closed_u = false;  // a torus (the last row returns to boundary 0) instead of a tube or sheet
  bool closed_v = true;   // curves around (tube, torus) or along (sheet)
  std::uint32_t rows = 3;
  std::uint32_t columns = 4;
  std::uint32_t points = 16;  // per curve

  Vec3 at(double xi, double theta) const {
    if (closed_u) {
      const double phi = 2.0 * M_PI * xi / rows;
      const double r = 0.5 + 0.08 * std::cos(3.0 * theta + phi);
      const Vec3 radial(std::cos(phi), std::sin(phi), 0.0);
      return 2.0 * radial + r * (std::cos(theta) * radial + std::sin(theta) * Vec3(0.0, 0.0, 1.0));
    }
    if (closed_v) {
      const double r = 1.0 + 0.2 * std::sin(xi) + 0.1 * std::cos(3.0 * theta + xi);
      return {r * std::cos(theta), r * std::sin(theta), -0.8 * xi};
    }
    return {3.0 * theta, 0.9 * xi, 0.3 * std::sin(2.0 * theta) * std::cos(xi)};
  }
  // The curve's parameter at point k.
  double theta(std::uint32_t k) const {
    return closed_v ? 2.0 * M_PI * k / points : static_cast<double>(k) / (points - 1);
  }
  std::vector<Vec3> curve(double xi) const {
    std::vector<Vec3> p;
    for (std::uint32_t k = 0; k < points; ++k) p.push_back(at(xi, theta(k)));
    return p;
  }
  std::vector<Vec3> derivative(double xi, int order) const {
    const double h = 1e-3;
    std::vector<Vec3> p;
    for (std::uint32_t k = 0; k < points; ++k) {
      const double t = theta(k);
      p.push_back(order == 1 ? (at(xi + h, t) - at(xi - h, t)) / (2.0 * h)
                             : (at(xi + h, t) - 2.0 * at(xi, t) + at(xi - h, t)) / (h * h));
    }
    return p;
  }
};

inline std::uint32_t addCurve(NetworkDescription& d, const std::string& name, std::vector<Vec3> points, bool closed) {
  d.curve_names.push_back(name);
  d.curve_points.push_back(std::move(points));
  d.curve_closed.push_back(closed);
  return static_cast<std::uint32_t>(d.curve_names.size() - 1);
}

inline NetworkDescription sweptNetwork(const SweptSurface& s, const std::vector<Ode6Shape>& row_shapes) {
  NetworkDescription d;
  d.columns = s.columns;
  d.closed_u = s.closed_u;
  const std::uint32_t boundaries = s.closed_u ? s.rows : s.rows + 1;
  for (std::uint32_t b = 0; b < boundaries; ++b) {
    // Appended piecewise: GCC 12's -Wrestrict misfires on chained std::string operator+ here.
    std::string name = "b";
    name += std::to_string(b);
    auto named = [&](const char* suffix) { return std::string(name).append(suffix); };
    NetworkBoundary x;
    x.name = name;
    x.position = addCurve(d, name, s.curve(b), s.closed_v);
    const bool has_after = s.closed_u || b < s.rows;
    const bool has_before = s.closed_u || b > 0;
    const std::uint32_t kind = b % 4;
    if (kind == 0) {
      x.source = DerivativeSource::kCoefficients;
      x.w_first = 0.3;
      x.w_second = -0.2;
    } else if (kind == 2) {
      x.source = DerivativeSource::kCurves;
      x.first_curve = addCurve(d, named("_d1"), s.derivative(b, 1), s.closed_v);
      x.second_curve = addCurve(d, named("_d2"), s.derivative(b, 2), s.closed_v);
    } else {
      x.source = DerivativeSource::kControlCurves;
      x.side = (kind == 1 && has_after) || !has_before ? ControlSide::kAfter : ControlSide::kBefore;
      x.slopes = kind == 1 ? SlopeRule::kOneSided : SlopeRule::kThreePoint;
      const double base = x.side == ControlSide::kAfter ? b : b - 1.0;
      x.u_lower = x.side == ControlSide::kAfter ? 0.2 : 0.6;
      x.u_upper = x.side == ControlSide::kAfter ? 0.4 : 0.8;
      x.control_lower = addCurve(d, named("_lo"), s.curve(base + x.u_lower), s.closed_v);
      x.control_upper = addCurve(d, named("_hi"), s.curve(base + x.u_upper), s.closed_v);
    }
    d.boundaries.push_back(x);
  }
  for (std::uint32_t r = 0; r < s.rows; ++r) {
    for (std::uint32_t c = 0; c < s.columns; ++c) d.shapes.push_back(row_shapes[r % row_shapes.size()]);
  }
  return d;
}

// One shape per row from four regimes: B (the thesis's), A, F (quintic Hermite), I.
inline std::vector<Ode6Shape> mixedRowShapes() { return {{1, 3, 1}, {1, -5, 4}, {1, 0, 0}, {1, 1, 1}}; }

// The three layouts every network test covers: a 3 x 4 tube closed in v, an open 3 x 3 sheet and a
// 4 x 3 torus closed in u.
inline std::vector<SweptSurface> sweptLayouts() {
  SweptSurface tube;  // cppcheck-suppress unassignedVariable ; the defaults are the tube
  SweptSurface sheet;
  sheet.closed_v = false;
  sheet.columns = 3;
  sheet.points = 9;
  SweptSurface torus;
  torus.closed_u = true;
  torus.rows = 4;
  torus.columns = 3;
  return {tube, sheet, torus};
}

}  // namespace odeskin::testing

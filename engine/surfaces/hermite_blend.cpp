// SPDX-License-Identifier: MIT
#include "hermite_blend.hpp"

namespace odeskin {

std::array<double, 4> hermiteBasis(double u) {
  const double w = 1.0 - u;
  return {w * w * (1.0 + 2.0 * u), u * w * w, -u * u * w, u * u * (3.0 - 2.0 * u)};
}

CardinalSample hermiteCardinals(double u) {
  const std::array<double, 4> h = hermiteBasis(u);
  const double w = 1.0 - u;
  CardinalSample s;
  s.r = {h[0], h[1], h[3], h[2]};
  // H0' = -6u(1-u), H1' = (1-u)(1-3u), H3' = 6u(1-u), H2' = u(3u-2).
  s.dr = {-6.0 * u * w, w * (1.0 - 3.0 * u), 6.0 * u * w, u * (3.0 * u - 2.0)};
  return s;
}

}  // namespace odeskin

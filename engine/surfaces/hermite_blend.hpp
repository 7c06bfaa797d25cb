// SPDX-License-Identifier: MIT
// The cubic Hermite blend the thesis compares with (Eqs 3.19-3.21, MATH.md 2.9):
//   B_i^3(u) = 3!/(i!(3-i)!) u^i (1-u)^(3-i),
//   H0 = B0 + B1 = (1-u)^2 (1+2u),  H1 = B1/3 = u (1-u)^2,
//   H2 = -B2/3 = -u^2 (1-u),        H3 = B2 + B3 = u^2 (3-2u),
//   S = H0 C0 + H1 C0bar + H2 C1bar + H3 C1.
// These are exactly the ODE cardinal functions (r1, r2, r4, r3) for beta = gamma = 0 (any alpha),
// and the limit of the ODE blend as alpha dominates beta and gamma.
#pragma once

#include <array>

#include "ode4_cardinal.hpp"

namespace odeskin {

// (H0, H1, H2, H3)(u) in the thesis's order.
std::array<double, 4> hermiteBasis(double u);

// The same functions in cardinal order (r1..r4 = H0, H1, H3, H2) with their u-derivatives, so a
// Hermite blend is a BlendingSurface like any other.
CardinalSample hermiteCardinals(double u);

}  // namespace odeskin

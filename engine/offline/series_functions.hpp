// SPDX-License-Identifier: MIT
// Entire scalar functions shared by the closed-form time bases (MATH.md 1.3, 5.3, 5.5). Each is
// evaluated without removable singularities: a power series near the singular point of its textbook
// form, the textbook form elsewhere.
#pragma once

namespace odeskin {

struct ChSh {
  double ch = 1.0;  // Ch(X, t)
  double sh = 0.0;  // Sh(X, t)
};

// Ch(X,t) = sum X^k t^2k/(2k)!, Sh(X,t) = sum X^k t^(2k+1)/(2k+1)! (MATH.md 1.3): cosh/sinh for
// X > 0, cos/sin for X < 0, (1, t) at X = 0, continuous in X. Unscaled: overflows for
// sqrt(X) |t| > ~710.
ChSh chSh(double x, double t);

// phi1(x) = (e^x - 1)/x, phi1(0) = 1 (MATH.md 5.3).
double phi1(double x);
// phi2(x) = (e^x - 1 - x)/x^2, phi2(0) = 1/2 (MATH.md 5.3).
double phi2(double x);

}  // namespace odeskin

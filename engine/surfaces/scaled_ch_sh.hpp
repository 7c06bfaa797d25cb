// SPDX-License-Identifier: MIT
// Ch(X,t) and Sh(X,t) divided by N(X) = cosh(sqrt(X)/2) (N = 1 for X <= 0), MATH.md 1.3-1.4: the
// fundamental solutions of y'' = X y, scaled so that they stay within about 1 on |t| <= 1/2 for any
// X, however large. Dividing a basis function by a constant leaves the span it builds unchanged,
// which is why the cardinal functions can be assembled from these without ever overflowing.
#pragma once

namespace odeskin {

struct ScaledChSh {
  double ch = 1.0;  // Ch(X, t) / N(X)
  double sh = 0.0;  // Sh(X, t) / N(X)
};

// Ch/N and Sh/N at t. Derivatives follow from Ch' = X Sh and Sh' = Ch (same N): d(Ch/N)/dt = X sh,
// d(Sh/N)/dt = ch. Ch = cosh(sqrt(X) t), Sh = sinh(sqrt(X) t)/sqrt(X) for X > 0; cos and
// sin(sqrt(-X) t)/sqrt(-X) for X < 0; 1 and t at X = 0, continuous in X.
// Precondition: X and t finite. For |t| <= 1/2 both values are bounded by about max(1, 1/sqrt(X)).
ScaledChSh scaledChSh(double x, double t);

}  // namespace odeskin

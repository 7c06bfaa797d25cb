// SPDX-License-Identifier: MIT
// The six cardinal functions of the C2 surface patch ODE (thesis ch. 4, Eq 4.2; MATH.md 3):
//   rho S^(6) + eta S^(4) + lambda S'' = 0 on u in [0, 1],
//   S(u, v) = g1(u) c1(v) + g2(u) c2(v) + g3(u) c3(v) + g4(u) c4(v) + g5(u) c5(v) + g6(u) c6(v),
// with c1, c2, c3 = S, S_u, S_uu at u = 0 and c4, c5, c6 the same at u = 1. Each g_k solves the ODE;
// its value, slope and curvature are 0 at both ends except the one matching c_k, which is 1.
//
// Computed as MATH.md 3.3-3.5 prescribe, not from the thesis's closed forms (Eqs 4.20-4.22 need the
// fixes F1, F2 and lose every digit near xi2 = pi, F3): the problem splits into an even and an odd
// 3x3 block in t = u - 1/2, each block uses a basis that stays well conditioned in float64 (a power
// series for small parameters, deflated and overflow-free scaled hyperbolic/trigonometric functions
// otherwise), and a Hadamard ratio below 1e-10 reports a resonance instead of a surface.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "../core/result.hpp"

namespace odeskin {

// Shape parameters of one patch. Only b = eta/rho and c = lambda/rho matter: (k rho, k eta,
// k lambda) gives the same cardinal functions for every k != 0.
struct Ode6Shape {
  double rho = 1.0;
  double eta = 0.0;
  double lambda = 0.0;
};

// Root regimes of the quartic factor rho r^4 + eta r^2 + lambda (MATH.md 2.3 and 3.2; r = 0 is
// always a further double root). D = b^2 - 4c.
enum class Ode6Regime : std::uint32_t {
  kA,  // D > 0, c > 0, b < 0: two real pairs +-p1, +-p2
  kB,  // D > 0, c > 0, b > 0: two imaginary pairs (the only regime the thesis treats, Eqs 4.14-4.18)
  kC,  // D > 0, c < 0: a real and an imaginary pair
  kD,  // c = 0, b < 0: r = 0 quadruple plus a real pair
  kE,  // c = 0, b > 0: r = 0 quadruple plus an imaginary pair
  kF,  // b = c = 0: S^(6) = 0, quintic Hermite
  kG,  // D = 0, b < 0: a double real pair
  kH,  // D = 0, b > 0: a double imaginary pair
  kI,  // D < 0: complex quadruple +-a +- iw
};

// "A" .. "I" followed by the condition, e.g. "B (D > 0, c > 0, b > 0: two imaginary pairs)".
const char* ode6RegimeName(Ode6Regime regime);

// Which well-conditioned basis evaluates the blocks (MATH.md 3.4); values match the GPU layout.
enum class Ode6Branch : std::uint32_t {
  kSeries = 0,  // omega <= 3: canonical power series of order 6
  kReal = 1,    // D >= omega^4/4: {1, Ct(s1), Ct(s2)} and {t, St(s1), St(s2)}, scaled
  kPq = 2,      // otherwise: products Ch(X1)Ch(X2), Sh(X1)Sh(X2) (even), Sh Ch, Ch Sh (odd)
};

inline constexpr int kOde6MaxDerivative = 6;
// Largest accepted frequency scale omega = max(sqrt|b|, |c|^(1/4)): boundary layers of width
// 1/omega; beyond this they are thinner than 1e-6 of the patch and no tessellation resolves them.
inline constexpr double kOde6MaxFrequency = 1e6;
// Hadamard ratio |det B| / prod ||columns of B|| below which a block counts as singular (MATH.md 3.5).
inline constexpr double kOde6ResonanceRatio = 1e-10;
// Terms of the power series in the kSeries branch (omega <= 3, |t| <= 1/2: the 40th term is below
// 1e-30 of the first). The shader sums the same number of terms.
inline constexpr int kOde6SeriesTerms = 40;

// g_1 .. g_6 (index k - 1) or one of their derivatives at one u.
using Ode6Values = std::array<double, 6>;

// What evaluates the blocks, in the form the compute shader reads it (tessellation_layout.h): the
// basis functions of each block and the 3x3 matrix turning them into block-cardinal functions
// E_i (even) and O_i (odd) with E_i^(j)(1/2) = delta_ij: E_i(t) = sum_l e_l(t) even[l][i].
struct Ode6Basis {
  Ode6Branch branch = Ode6Branch::kSeries;
  double b = 0.0;   // eta / rho
  double c = 0.0;   // lambda / rho
  double x1 = 0.0;  // kReal: s1 (larger |root| of s^2 + b s + c); kPq: X1 = (sqrt(c) - b/2)/2
  double x2 = 0.0;  // kReal: s2 = c / s1;                           kPq: X2 = -(sqrt(c) + b/2)/2
  double w = 1.0;   // row scale W = max(1, omega)
  std::array<std::array<double, 3>, 3> even{};
  std::array<std::array<double, 3>, 3> odd{};
};

class Ode6Cardinal {
 public:
  // Errors: kInvalidArgument for a parameter that is not finite; kDegenerate for rho = 0 (a
  // fourth-order ODE cannot meet six conditions); kOutOfRange when eta/rho or lambda/rho overflow
  // or omega exceeds kOde6MaxFrequency; kIllPosed when the boundary-value problem is resonant (no
  // unique solution, MATH.md 3.5) - every message names the parameters.
  static Result<Ode6Cardinal> create(const Ode6Shape& shape);

  // g_k^(order)(u) for k = 1..6. Preconditions: u in [0, 1], order in [0, kOde6MaxDerivative].
  Ode6Values evaluate(double u, int order = 0) const;
  // Orders 0 .. out.size() - 1 at once (out.size() <= kOde6MaxDerivative + 1).
  void evaluate(double u, std::span<Ode6Values> out) const;

  const Ode6Shape& shape() const { return shape_; }
  const Ode6Basis& basis() const { return basis_; }
  Ode6Regime regime() const { return regime_; }
  // Smaller Hadamard ratio of the two row-scaled blocks (1 = orthogonal columns, 0 = singular).
  double hadamardRatio() const { return hadamard_ratio_; }

 private:
  Ode6Cardinal() = default;

  Ode6Shape shape_;
  Ode6Basis basis_;
  Ode6Regime regime_ = Ode6Regime::kF;
  double hadamard_ratio_ = 1.0;
  // kSeries: Taylor coefficients a_n (n < kOde6SeriesTerms + 7) of Y_0 .. Y_5 at t = 0, where
  // Y_k^(j)(0) = delta_jk; Y_0 = 1 and Y_1 = t, so only Y_2 .. Y_5 are stored (index k - 2).
  std::array<std::array<double, kOde6SeriesTerms + kOde6MaxDerivative + 1>, 4> series_{};
};

// Classifies (b, c) by exact comparisons (MATH.md 2.3).
Ode6Regime classifyOde6(double b, double c);

}  // namespace odeskin

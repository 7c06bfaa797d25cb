// SPDX-License-Identifier: MIT
// The four cardinal functions of the fourth-order blending ODE (thesis ch. 3, Eqs 3.1-3.43, as
// corrected and generalised by MATH.md 2.1-2.8):
//   alpha G'''' + beta G'' + gamma G = 0 on u in [0, 1],
//   S(u, v) = r1(u) C0(v) + r2(u) C0bar(v) + r3(u) C1(v) + r4(u) C1bar(v)        (Eq 3.43, C10)
// where r_k solves the ODE with one unit condition among r(0), r'(0), r(1), r'(1) (MATH.md 2.1).
// Built from even/odd 2x2 blocks on well-conditioned bases (MATH.md 2.5-2.6), so every regime,
// the double-root lines, tiny and very large shape parameters evaluate in float64 without overflow.
#pragma once

#include <algorithm>
#include <array>

#include "../core/result.hpp"

namespace odeskin {

// Root structure of r^4 + b r^2 + c = 0 with b = beta/alpha, c = gamma/alpha, D = b^2 - 4c
// (MATH.md 2.3; the letters are that table's ids).
enum class Ode4Regime {
  kTwoRealPairs,          // A: D > 0, c > 0, b < 0: +-p1, +-p2
  kTwoImaginaryPairs,     // B: D > 0, c > 0, b > 0: +-i q1, +-i q2 (thesis Eqs 3.31-3.36)
  kRealAndImaginary,      // C: D > 0, c < 0: +-p, +-i q
  kZeroAndRealPair,       // D: c = 0, b < 0: 0 (double), +-p
  kZeroAndImaginaryPair,  // E: c = 0, b > 0: 0 (double), +-i q
  kQuadrupleZero,         // F: b = c = 0: the cubic Hermite blend (MATH.md 2.9)
  kRealDoublePair,        // G: D = 0, b < 0: +-p double (thesis Eqs 3.5-3.13)
  kImaginaryDoublePair,   // H: D = 0, b > 0: +-i q double (thesis Eqs 3.26-3.30)
  kComplexQuadruple,      // I: D < 0: +-a +- i w (thesis Eqs 3.37-3.42)
};

// "A: two real pairs (D > 0, c > 0, b < 0)" and so on.
const char* ode4RegimeName(Ode4Regime regime);

// Which well-conditioned fundamental system evaluates the cardinal functions (MATH.md 2.6).
enum class Ode4Basis {
  kSeries,  // omega <= 1: power series, entire in (b, c)
  kReal,    // D >= omega^4 / 4: Ch/Sh of the two real roots s1, s2 of s^2 + b s + c; also in
            // regime A below that threshold wherever its block ratios beat the pq basis's
  kPq,      // otherwise (c > 0): products Ch(X1) Ch(X2) etc., continuous across D = 0
};

// Classifies (alpha, beta, gamma). The sign of D is decided from beta^2 - 4 alpha gamma with
// exact products (fma), so parameters on a double-root line classify as G or H exactly.
// Errors: kInvalidArgument naming the parameter that is NaN or infinite, or when |beta/alpha|
// exceeds 1e150 (b^2 would overflow) or |gamma/alpha| exceeds 1e12 (beyond it the end slopes lose
// the accuracy a blend's constraints need, measured in ode4_cardinal.cpp); kDegenerate for alpha = 0
// (second-order ODE, cannot meet four conditions; MATH.md 2.8), including alpha = beta = gamma = 0.
Result<Ode4Regime> classifyOde4(double alpha, double beta, double gamma);

// Values and u-derivatives of the four cardinal functions at one u (index k-1 holds r_k).
struct CardinalSample {
  std::array<double, 4> r{};   // r1..r4
  std::array<double, 4> dr{};  // r1'..r4'
};

// Hadamard ratio below which a block is reported resonant (MATH.md 2.7).
inline constexpr double kOde4ResonanceThreshold = 1e-10;

// The cardinal functions for one parameter set, set up once (classification, basis, the two 2x2
// block inverses) and then evaluated at any u. Cheap to copy.
class Ode4Cardinal {
 public:
  // Errors: those of classifyOde4, and kIllPosed when the boundary-value problem is singular or
  // numerically so (a block's Hadamard ratio |det B| / (|col1| |col2|) < 1e-10 after row scaling,
  // MATH.md 2.7): resonant parameters, e.g. gamma = 0, beta = 4 pi^2 alpha. The message names the
  // parameters and the block (even: symmetric mode, odd: antisymmetric mode).
  static Result<Ode4Cardinal> create(double alpha, double beta, double gamma);

  // r_k(u) and r_k'(u). Accurate to ~1e-12 (1 + |r|) for u in [0, 1]; outside [0, 1] values grow
  // like the fundamental solutions and may overflow to +-inf. Precondition: u finite.
  CardinalSample at(double u) const;

  double alpha() const { return alpha_; }
  double beta() const { return beta_; }
  double gamma() const { return gamma_; }
  double b() const { return b_; }  // beta / alpha
  double c() const { return c_; }  // gamma / alpha
  Ode4Regime regime() const { return regime_; }
  Ode4Basis basis() const { return basis_; }
  // The smaller of the two blocks' Hadamard ratios (1 for perfectly conditioned blocks).
  double hadamardRatio() const { return hadamard_ratio_; }

 private:
  struct Pair {  // two basis functions of one parity and their t-derivatives at one t
    double f = 0.0, df = 0.0, g = 0.0, dg = 0.0;
  };
  struct BlockInverse {  // value- and slope-cardinal functions as combinations of (f, g)
    double v_f = 0.0, v_g = 0.0, d_f = 0.0, d_g = 0.0;
  };
  struct BlockRatios {  // Hadamard ratios of the two row-scaled blocks (MATH.md 2.7)
    double even = 0.0, odd = 0.0;
    double smaller() const { return std::min(even, odd); }
  };
  Ode4Cardinal() = default;
  // Picks the basis of MATH.md 2.6 for (b_, c_) and sets its constants; returns the slope-row
  // scale W = max(1, omega) of MATH.md 2.5.
  double chooseBasis();
  // Sets the kReal basis from D = b^2 - 4c > 0.
  void useRealRoots(double d);
  // Sets even_ and odd_ for the current basis and returns their ratios.
  BlockRatios invertBlocks(double w);
  // invertBlocks, after switching regime A from the pq to the real basis where that conditions
  // the blocks better.
  BlockRatios setUpBlocks(double w);
  Pair evenPair(double t) const;
  Pair oddPair(double t) const;
  Pair seriesPair(int first, double t) const;

  double alpha_ = 1.0, beta_ = 0.0, gamma_ = 0.0;
  double b_ = 0.0, c_ = 0.0;
  Ode4Regime regime_ = Ode4Regime::kQuadrupleZero;
  Ode4Basis basis_ = Ode4Basis::kSeries;
  double x1_ = 0.0, x2_ = 0.0;  // kReal: s1, s2; kPq: X1, X2
  static constexpr int kSeriesTerms = 48;
  // kSeries: Taylor coefficients a_n = Y_k^(n)(0) of Y0..Y3 (MATH.md 2.6, branch 1).
  std::array<std::array<double, kSeriesTerms + 1>, 4> series_{};
  BlockInverse even_, odd_;
  double hadamard_ratio_ = 1.0;
};

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// Time basis of one Fourier mode (MATH.md 5.2-5.5; thesis Eqs 6.17-6.29, corrected by G2-G7):
//   rho a'' + eta a' + h_n a = t e,  a(0) = 0, a'(0) = rate, a(1) = d
//   a(t) = gamma_n(t) d + psi_n(t) rate,  gamma = P/P(1),  psi = H - H(1) gamma.
#pragma once

#include "../core/result.hpp"
#include "material.hpp"

namespace odeskin {

// Which form of the mode equation applies (MATH.md 5.3).
enum class ModeKind {
  kSecondOrder,  // rho != 0
  kFirstOrder,   // rho = 0, eta != 0: rate cannot be imposed, psi = 0
  kStatic,       // rho = eta = 0, h != 0: gamma = t
};

struct TimeBasisSample {
  double gamma = 0.0;   // gamma_n(t)
  double dgamma = 0.0;  // d gamma_n / dt
  double psi = 0.0;     // psi_n(t)
  double dpsi = 0.0;    // d psi_n / dt
};

// Closed-form time basis of one mode, set up once (validation, P(1), H(1)) and then evaluated at
// any t in float64. Cheap to copy.
class ModeTimeBasis {
 public:
  // Builds the basis for mass rho, damping eta and mode stiffness h.
  // Errors (message names the parameters and `mode` for the user):
  //   kInvalidArgument  a parameter is NaN or infinite;
  //   kDegenerate       rho = eta = h = 0 (the equation carries no information);
  //   kIllPosed         resonance, P(1) = 0 up to 1e-9 of max|P| (only possible for eta/rho < -2),
  //                     or growth so fast that P(1) or H(1) overflows float64.
  static Result<ModeTimeBasis> create(double rho, double eta, double h, int mode = 0);
  // Same for mode n of a material (h = modeStiffness(material, n)).
  static Result<ModeTimeBasis> create(const Material& material, int n);

  // gamma, gamma', psi, psi' at t (any finite t; the segment is t in [0, 1]). Never NaN for finite t:
  // a value that overflows float64 (|t| far outside [0, 1] for growing modes) comes back as +-inf.
  TimeBasisSample at(double t) const;

  ModeKind kind() const { return kind_; }
  // True when the prescribed initial rate is ignored (first-order and static modes, MATH.md 5.3).
  bool rateIgnored() const { return kind_ != ModeKind::kSecondOrder; }
  // |H(1)|: large values flag exponential growth modes (h < 0 or eta < 0), where psi loses accuracy.
  double impulseResponseAtOne() const;
  // eta/rho < 0 (negative damping, non-physical but accepted), or h < 0 (growth mode).
  bool negativeDamping() const;
  bool growthMode() const;

 private:
  ModeTimeBasis() = default;
  TimeBasisSample atSecondOrder(double t) const;
  TimeBasisSample atFirstOrder(double t) const;

  // Implementation-defined normalised constants; see time_basis.cpp.
  ModeKind kind_ = ModeKind::kStatic;
  double rho_ = 0.0, eta_ = 0.0, h_ = 0.0;
  double kappa_ = 0.0, k_ = 0.0, x_ = 0.0;  // second order: eta/(2 rho), h/rho, kappa^2 - k
  double q1_ = 1.0, h1_ = 0.0;              // second order: Q(1), H(1)
  double c_ = 0.0, norm_ = 1.0;             // first order: -h/eta and the normaliser of gamma
};

}  // namespace odeskin

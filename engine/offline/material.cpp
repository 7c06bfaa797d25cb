// SPDX-License-Identifier: MIT
#include "material.hpp"

#include <cstdio>
#include <numbers>

namespace odeskin {

double modeStiffness(const Material& material, int n) {
  // The v-derivative of a Fourier mode of index n on unit v gives d2/dv2 -> -(2 pi n)^2 (MATH.md 5.1).
  const double nd = static_cast<double>(n);
  const double bending = 4.0 * nd * nd * std::numbers::pi * std::numbers::pi * material.xi;
  return material.bending == BendingSign::kThesis ? material.zeta - bending : material.zeta + bending;
}

Material staticMaterial() { return Material{}; }

Material skinMaterial() {
  // Thesis 6.5.1 quotes E = 150, mu = 0.3, rho = 1050, eta = 0.619; thickness 2 mm and zeta = 1e4
  // are our assumptions (MATH.md 5.7).
  constexpr double kYoung = 150.0;
  constexpr double kPoisson = 0.3;
  constexpr double kThickness = 0.002;
  Material m;
  m.rho = 1050.0;
  m.eta = 0.619;
  m.zeta = 1.0e4;
  m.xi = kYoung * kThickness * kThickness * kThickness / (12.0 * (1.0 - kPoisson * kPoisson));
  return m;
}

std::string describe(const Material& material) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "rho=%g eta=%g zeta=%g xi=%.5g%s", material.rho, material.eta,
                material.zeta, material.xi,
                material.bending == BendingSign::kStiffening ? " (stiffening bending sign)" : "");
  return buffer;
}

}  // namespace odeskin

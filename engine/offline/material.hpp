// SPDX-License-Identifier: MIT
// Per-curve material of the dynamic deformation model (MATH.md 5.1, 5.7; thesis 6.4.1, 6.5.1).
#pragma once

#include <string>

namespace odeskin {

// Sign of the lowered bending term in h_n (MATH.md 5.1, erratum G12). The thesis lowers
// "+xi d2/dv2", so h_n = zeta - 4 n^2 pi^2 xi decreases with n; a physical stiffness would add it.
enum class BendingSign { kThesis, kStiffening };

struct Material {
  double rho = 0.0;   // mass density (>= 0 physically)
  double eta = 0.0;   // damping (>= 0 physically; negative accepted with a warning)
  double zeta = 0.0;  // restoring coefficient (the thesis's varsigma / zeta, erratum G11)
  double xi = 0.0;    // flexural rigidity, E h^3 / (12 (1 - mu^2))
  BendingSign bending = BendingSign::kThesis;
};

// h_n = zeta -/+ 4 n^2 pi^2 xi (MATH.md 5.1), n >= 0.
double modeStiffness(const Material& material, int n);

// rho = eta = 0, zeta = 1, xi = 0: gamma_n(t) = t for every mode, the thesis's static deformation
// (Fig. 6.12).
Material staticMaterial();
// The thesis's skin values (rho = 1050, eta = 0.619) with our assumed zeta = 1e4 and 2 mm thickness
// (xi = E h^3 / (12 (1 - mu^2)) with E = 150, mu = 0.3), MATH.md 5.7.
Material skinMaterial();

std::string describe(const Material& material);

}  // namespace odeskin

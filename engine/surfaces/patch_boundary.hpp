// SPDX-License-Identifier: MIT
// The boundary data of a C2 patch (thesis sec. 4.2; MATH.md 3.7): the position curves c1(v) at u = 0
// and c4(v) at u = 1 come with first and second u-derivatives c2, c3 and c5, c6, built in one of two
// ways:
//  (A) coefficients (thesis Eqs 4.24-4.25): c2 = w1 c1, c3 = w2 c1, c5 = w3 c4, c6 = w4 c4;
//  (B) control curves (thesis Eqs 4.3-4.7, corrected): cb2, cb3 at 0 < u2 < u3 inside the patch
//      near u = 0 and cb5, cb6 at u5 < u6 < 1 near u = 1 (0 < u2 < u3 <= u5 < u6 < 1, erratum F7).
//      Slopes are the thesis's first-order one-sided differences by default, or three-point slopes
//      exact for quadratics; second derivatives are true second divided differences (errata F5, F6:
//      the printed ones divide a slope difference by u2, resp. 1 - u6, and are exact for quadratics
//      only when u3 = 2 u2, resp. 1 - u5 = 2 (1 - u6)).
// Either way every derivative curve is a fixed linear combination of the boundary curve and its
// control curves; the weights below are that combination, shared by patches and networks.
#pragma once

#include <array>
#include <functional>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

// A curve of v in the patch's parameter range [0, 1]: its value (order 0) or v-derivative (1, 2).
using PatchCurve = std::function<Vec3(double v, int order)>;

// The six boundary curves c1 .. c6 (index k - 1): S, S_u, S_uu at u = 0, then at u = 1.
using PatchCurves = std::array<PatchCurve, 6>;

enum class SlopeRule {
  kOneSided,    // c2 = (cb2 - c1)/u2, c5 = (c4 - cb6)/(1 - u6): the thesis's Eqs 4.3, 4.5 (default)
  kThreePoint,  // through the boundary and both control curves: exact for quadratics
};

// A derivative curve as  boundary * c_boundary + near * cb_near + far * cb_far, where "near" is the
// control curve closer to the boundary (cb2 at u2, resp. cb6 at u6) and "far" the other one.
struct DerivativeWeights {
  double boundary = 0.0;
  double near = 0.0;
  double far = 0.0;
};

struct ControlWeights {
  DerivativeWeights first;   // c2 (start) or c5 (end)
  DerivativeWeights second;  // c3 (start) or c6 (end)
};

// At u = 0 from control curves at u2 (near) and u3 (far). kInvalidArgument unless 0 < u2 < u3 < 1.
Result<ControlWeights> startControlWeights(double u2, double u3, SlopeRule slopes);
// At u = 1 from control curves at u6 (near) and u5 (far). kInvalidArgument unless 0 < u5 < u6 < 1.
Result<ControlWeights> endControlWeights(double u5, double u6, SlopeRule slopes);

// The second derivatives as the thesis prints them (Eqs 4.4, 4.6; errata F5, F6), kept only to
// show the erratum: c3 = [(cb3 - cb2)/(u3 - u2) - (cb2 - c1)/u2] / u2, and the mirror image at u = 1.
DerivativeWeights thesisStartSecondWeights(double u2, double u3);
DerivativeWeights thesisEndSecondWeights(double u5, double u6);

// Way (A): c2 = w[0] c1, c3 = w[1] c1, c5 = w[2] c4, c6 = w[3] c4. kInvalidArgument for empty
// curves or weights that are not finite.
Result<PatchCurves> coefficientBoundary(const PatchCurve& c1, const PatchCurve& c4, const std::array<double, 4>& w);

// Positions of the control curves of way (B) inside one patch.
struct ControlPositions {
  double u2 = 0.25;
  double u3 = 0.5;
  double u5 = 0.5;
  double u6 = 0.75;
};

// Way (B): c1, c4 are the boundary curves; cb2, cb3, cb5, cb6 the control curves at `at`.
// kInvalidArgument for empty curves or unless 0 < u2 < u3 <= u5 < u6 < 1.
Result<PatchCurves> controlCurveBoundary(const PatchCurve& c1, const PatchCurve& cb2, const PatchCurve& cb3,
                                         const PatchCurve& cb5, const PatchCurve& cb6, const PatchCurve& c4,
                                         const ControlPositions& at, SlopeRule slopes = SlopeRule::kOneSided);

}  // namespace odeskin

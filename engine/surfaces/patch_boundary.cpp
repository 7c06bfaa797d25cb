// SPDX-License-Identifier: MIT
#include "patch_boundary.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace odeskin {
namespace {

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// A combination of three curves as one curve.
PatchCurve combine(DerivativeWeights w, PatchCurve boundary, PatchCurve near, PatchCurve far) {
  return [w, boundary = std::move(boundary), near = std::move(near), far = std::move(far)](double v, int order) {
    return w.boundary * boundary(v, order) + w.near * near(v, order) + w.far * far(v, order);
  };
}

PatchCurve scaled(double w, PatchCurve c) {
  return [w, c = std::move(c)](double v, int order) { return w * c(v, order); };
}

}  // namespace

Result<ControlWeights> startControlWeights(double u2, double u3, SlopeRule slopes) {
  if (!(u2 > 0.0 && u2 < u3 && u3 < 1.0)) {
    return invalidArgument("patch boundary: control curves at u2 = " + number(u2) + ", u3 = " + number(u3) +
                           " need 0 < u2 < u3 < 1");
  }
  ControlWeights w;
  if (slopes == SlopeRule::kOneSided) {
    w.first = {-1.0 / u2, 1.0 / u2, 0.0};
  } else {
    w.first = {-(u2 + u3) / (u2 * u3), u3 / (u2 * (u3 - u2)), -u2 / (u3 * (u3 - u2))};
  }
  // c3 = 2 [u2 cb3 - u3 cb2 + (u3 - u2) c1] / [u2 u3 (u3 - u2)] (erratum F5).
  const double d = u2 * u3 * (u3 - u2);
  w.second = {2.0 * (u3 - u2) / d, -2.0 * u3 / d, 2.0 * u2 / d};
  return w;
}

Result<ControlWeights> endControlWeights(double u5, double u6, SlopeRule slopes) {
  if (!(u5 > 0.0 && u5 < u6 && u6 < 1.0)) {
    return invalidArgument("patch boundary: control curves at u5 = " + number(u5) + ", u6 = " + number(u6) +
                           " need 0 < u5 < u6 < 1");
  }
  ControlWeights w;
  const double a = 1.0 - u6;  // distance of the near control curve from the boundary
  const double b = 1.0 - u5;  // distance of the far one
  if (slopes == SlopeRule::kOneSided) {
    w.first = {1.0 / a, -1.0 / a, 0.0};
  } else {
    w.first = {(a + b) / (a * b), -b / ((b - a) * a), a / ((b - a) * b)};
  }
  // c6 = 2 [(u6 - u5) c4 + (1 - u6) cb5 - (1 - u5) cb6] / [(1 - u6)(u6 - u5)(1 - u5)] (erratum F6).
  const double d = a * (b - a) * b;
  w.second = {2.0 * (b - a) / d, -2.0 * b / d, 2.0 * a / d};
  return w;
}

DerivativeWeights thesisStartSecondWeights(double u2, double u3) {
  // [(cb3 - cb2)/(u3 - u2) - (cb2 - c1)/u2] / u2
  const double s = 1.0 / (u3 - u2);
  return {1.0 / (u2 * u2), (-s - 1.0 / u2) / u2, s / u2};
}

DerivativeWeights thesisEndSecondWeights(double u5, double u6) {
  // [(c4 - cb6)/(1 - u6) - (cb6 - cb5)/(u6 - u5)] / (1 - u6)
  const double a = 1.0 - u6;
  const double s = 1.0 / (u6 - u5);
  return {1.0 / (a * a), (-1.0 / a - s) / a, s / a};
}

Result<PatchCurves> coefficientBoundary(const PatchCurve& c1, const PatchCurve& c4, const std::array<double, 4>& w) {
  if (!c1 || !c4) return invalidArgument("patch boundary: c1 and c4 are required");
  for (double x : w) {
    if (!std::isfinite(x)) return invalidArgument("patch boundary: coefficient w = " + number(x) + " is not finite");
  }
  return PatchCurves{c1, scaled(w[0], c1), scaled(w[1], c1), c4, scaled(w[2], c4), scaled(w[3], c4)};
  // NOLINTNEXTLINE(clang-analyzer-cplusplus.NewDeleteLeaks): false positive, the analyzer loses std::function's heap functor once it is moved into the returned array
}

Result<PatchCurves> controlCurveBoundary(const PatchCurve& c1, const PatchCurve& cb2, const PatchCurve& cb3,
                                         const PatchCurve& cb5, const PatchCurve& cb6, const PatchCurve& c4,
                                         const ControlPositions& at, SlopeRule slopes) {
  if (!c1 || !cb2 || !cb3 || !cb5 || !cb6 || !c4) {
    return invalidArgument("patch boundary: c1, cb2, cb3, cb5, cb6 and c4 are required");
  }
  if (!(at.u3 <= at.u5)) {
    return invalidArgument("patch boundary: control curves need u3 <= u5, got u3 = " + number(at.u3) +
                           ", u5 = " + number(at.u5));
  }
  ODESKIN_ASSIGN_OR_RETURN(const ControlWeights start, startControlWeights(at.u2, at.u3, slopes));
  ODESKIN_ASSIGN_OR_RETURN(const ControlWeights end, endControlWeights(at.u5, at.u6, slopes));
  return PatchCurves{c1,
                     combine(start.first, c1, cb2, cb3),
                     combine(start.second, c1, cb2, cb3),
                     c4,
                     combine(end.first, c4, cb6, cb5),
                     combine(end.second, c4, cb6, cb5)};
}

}  // namespace odeskin

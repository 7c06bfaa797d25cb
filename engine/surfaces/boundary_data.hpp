// SPDX-License-Identifier: MIT
// The boundary data of a blending surface (thesis Sec. 3.1, MATH.md 2.1): two trimlines, each a
// curve C(v) and the cross-boundary tangent Cbar(v) = S_u there,
//   S(0, v) = C0(v), S_u(0, v) = C0bar(v), S(1, v) = C1(v), S_u(1, v) = C1bar(v).
// A trimline comes from callables, from sampled polylines (interpolated by a C2 cubic spline,
// periodic for closed trimlines), or from an iso-line of a primary parametric surface and its
// u-derivative.
#pragma once

#include <functional>
#include <numbers>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

using CurveFunction = std::function<Vec3(double v)>;
using SurfaceFunction = std::function<Vec3(double u, double v)>;

// The v-interval of the trimlines. Periodic (closed trimlines, e.g. v in [0, 2 pi)): the grid
// wraps, sample j of V is at v_begin + (v_end - v_begin) j / V. Open (e.g. the plane blends of
// thesis Eqs 3.22-3.24 on [0, 1]): sample j of V is at v_begin + (v_end - v_begin) j / (V - 1).
struct VDomain {
  double v_begin = 0.0;
  double v_end = 2.0 * std::numbers::pi;
  bool periodic = true;
};

// One trimline: its position curve and its u-tangent curve, both functions of v.
struct Trimline {
  CurveFunction curve;    // C(v)
  CurveFunction tangent;  // Cbar(v) = S_u on this trimline
};

// Both trimlines at one v: C0, C0bar, C1, C1bar.
struct TrimlineSample {
  Vec3 c0{0.0}, c0bar{0.0}, c1{0.0}, c1bar{0.0};
};

// kInvalidArgument when `curve` or `tangent` is empty.
Result<Trimline> trimlineFromFunctions(CurveFunction curve, CurveFunction tangent);

// Samples of C and Cbar at uniform v over `domain` (periodic: n samples at v_j = v_begin + j dv,
// dv = (v_end - v_begin)/n, the curve closes from the last sample back to the first; open: n
// samples with the last at v_end), interpolated per coordinate by a C2 cubic spline (periodic,
// or natural at the ends). Both polylines need the same count: at least 3 when periodic, 2 when
// open. Evaluating outside the domain wraps (periodic) or clamps (open) v.
// Errors: kInvalidArgument for mismatched or too few samples, a non-finite coordinate (named by
// polyline and index) or an invalid domain.
Result<Trimline> trimlineFromPolylines(std::vector<Vec3> curve, std::vector<Vec3> tangent, const VDomain& domain);

// The iso-line u = u_iso of a primary surface P(u, v): C(v) = P(u_iso, v) and
// Cbar(v) = tangent_scale * P_u(u_iso, v). When `u_derivative` is empty P_u is taken by a
// five-point central difference with step 1e-3 (error ~1e-13 |P^(5)|); pass it when known.
// tangent_scale sets magnitude and direction (negative: the blend leaves against increasing u).
// Errors: kInvalidArgument for an empty surface or a non-finite u_iso or tangent_scale.
Result<Trimline> trimlineFromSurface(SurfaceFunction surface, SurfaceFunction u_derivative, double u_iso,
                                     double tangent_scale = 1.0);

// The two trimlines over one v-domain.
class BoundaryData {
 public:
  // Errors: kInvalidArgument for an empty function in either trimline, or a domain whose ends are
  // not finite or not increasing.
  static Result<BoundaryData> create(Trimline start, Trimline end, const VDomain& domain = {});

  TrimlineSample at(double v) const;
  const Trimline& start() const { return start_; }
  const Trimline& end() const { return end_; }
  const VDomain& domain() const { return domain_; }

 private:
  BoundaryData() = default;
  Trimline start_, end_;
  VDomain domain_;
};

// kInvalidArgument unless v_begin and v_end are finite with v_begin < v_end.
Status validateDomain(const VDomain& domain);

}  // namespace odeskin

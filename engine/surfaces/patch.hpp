// SPDX-License-Identifier: MIT
// One C2 surface patch (thesis ch. 4, Eqs 4.2 and 4.8; MATH.md 3.1):
//   S(u, v) = sum_k g_k(u) c_k(v),  (u, v) in [0, 1]^2,
// with the cardinal functions g_k of Ode6Cardinal and the boundary curves c1 .. c6 of
// patch_boundary.hpp. S, S_u, S_uu equal c1, c2, c3 at u = 0 and c4, c5, c6 at u = 1 exactly (up to
// rounding) for every shape; v-derivatives are those of the curves, weighted by the same g_k.
#pragma once

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "ode6_cardinal.hpp"
#include "patch_boundary.hpp"

namespace odeskin {

// S and its partial derivatives at one (u, v).
struct PatchPoint {
  Vec3 s{0.0};
  Vec3 s_u{0.0};
  Vec3 s_uu{0.0};
  Vec3 s_v{0.0};
  Vec3 s_vv{0.0};
  Vec3 s_uv{0.0};
};

class Patch {
 public:
  // Errors of Ode6Cardinal::create for the shape; kInvalidArgument when a curve is empty.
  static Result<Patch> create(const Ode6Shape& shape, PatchCurves curves);
  // A patch over curves whose cardinal functions were already computed (shared by a chain of
  // v-adjacent patches, MATH.md 3.9).
  static Result<Patch> create(const Ode6Cardinal& cardinal, PatchCurves curves);

  // Preconditions: u, v in [0, 1].
  Vec3 position(double u, double v) const;
  PatchPoint evaluate(double u, double v) const;

  const Ode6Cardinal& cardinal() const { return cardinal_; }
  const PatchCurves& curves() const { return curves_; }

 private:
  Patch(const Ode6Cardinal& cardinal, PatchCurves curves) : cardinal_(cardinal), curves_(std::move(curves)) {}

  Ode6Cardinal cardinal_;
  PatchCurves curves_;
};

}  // namespace odeskin

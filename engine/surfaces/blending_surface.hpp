// SPDX-License-Identifier: MIT
// A blending surface between two trimlines (thesis Eq 3.43 as corrected by C10, MATH.md 2.1):
//   S(u, v) = r1(u) C0(v) + r2(u) C0bar(v) + r3(u) C1(v) + r4(u) C1bar(v),   u in [0, 1],
// with r_k the ODE cardinal functions (Ode4Cardinal), the cubic Hermite functions (hermite_blend),
// or their spline approximation (cardinal_spline), and its grid tessellation into a mesh.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "boundary_data.hpp"
#include "ode4_cardinal.hpp"

namespace odeskin {

// r_k(u) and r_k'(u) for u in [0, 1].
using CardinalFunction = std::function<CardinalSample(double u)>;

class BlendingSurface {
 public:
  // The ODE blend alpha G'''' + beta G'' + gamma G = 0. Errors: those of Ode4Cardinal::create
  // (kInvalidArgument for NaN or infinite parameters, kDegenerate for alpha = 0, kIllPosed for
  // resonant parameters).
  static Result<BlendingSurface> create(BoundaryData boundary, double alpha, double beta, double gamma);
  // Any set of cardinal functions (Hermite, spline approximation). kInvalidArgument when empty.
  static Result<BlendingSurface> create(BoundaryData boundary, CardinalFunction cardinals);

  Vec3 at(double u, double v) const;            // S(u, v)
  Vec3 derivativeU(double u, double v) const;   // S_u(u, v)
  // S at one u for boundary data already sampled at v (what the grid tessellation uses).
  static Vec3 combine(const std::array<double, 4>& r, const TrimlineSample& b) {
    return r[0] * b.c0 + r[1] * b.c0bar + r[2] * b.c1 + r[3] * b.c1bar;
  }

  const BoundaryData& boundary() const { return boundary_; }
  const CardinalFunction& cardinals() const { return cardinals_; }

 private:
  BlendingSurface(BoundaryData boundary, CardinalFunction cardinals)
      : boundary_(std::move(boundary)), cardinals_(std::move(cardinals)) {}
  BoundaryData boundary_;
  CardinalFunction cardinals_;
};

// A grid of S(u_i, v_j): vertex i * v_count + j, u_i = i / (u_count - 1); v_j = v_begin + dv j
// with dv = span / v_count when the domain is periodic (the grid wraps: no duplicate seam) and
// span / (v_count - 1) when it is open.
struct BlendGrid {
  std::vector<Vec3> positions;  // u_count * v_count
  FaceList faces;               // quads (i, j), (i+1, j), (i+1, j+1), (i, j+1); j+1 wraps when periodic
  std::uint32_t u_count = 0;
  std::uint32_t v_count = 0;
  bool wraps_v = false;
};

// Largest u_count * v_count accepted (vertex indices stay far inside uint32).
inline constexpr std::uint64_t kMaxBlendGridVertices = 50'000'000;

// The v of grid column j (as tessellateBlend places it).
double blendGridV(const VDomain& domain, std::uint32_t v_count, std::uint32_t j);

// Samples the surface on the grid, evaluating the cardinal functions once per row and the boundary
// data once per column (MATH.md 2.14). Errors: kOutOfRange for u_count < 2, v_count < 3
// (periodic) or < 2 (open), or more than kMaxBlendGridVertices vertices; kInvalidArgument naming
// (u, v) when the surface is not finite there (boundary data that are not finite).
Result<BlendGrid> tessellateBlend(const BlendingSurface& surface, std::uint32_t u_count, std::uint32_t v_count);

}  // namespace odeskin

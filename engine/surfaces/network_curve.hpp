// SPDX-License-Identifier: MIT
// A curve of a patch network: a C2 cubic spline through given points, parameterised uniformly over
// v in [0, span] (span = the network's patch columns, so patch column j sees v in [j, j + 1]).
// Stored as a uniform cubic B-spline whose control points are solved for: periodic when closed,
// not-a-knot ends when open with 4 or more points, natural ends (zero curvature) for 2 or 3.
// Because every curve is C2 over its whole range and v-adjacent patches read the same curve on
// either side of their shared edge, c_k^(i)(1) = chat_k^(i)(0) for i = 0, 1, 2 holds by construction
// (the curve half of MATH.md 3.8's condition for C2 across a v-interface).
#pragma once

#include <span>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

class NetworkCurve {
 public:
  // points: at v_i = i span / (n - 1) (open, n >= 2) or i span / n (closed, n >= 3). kInvalidArgument
  // for too few or non-finite points or span <= 0.
  static Result<NetworkCurve> interpolate(std::span<const Vec3> points, bool closed, double span);

  // The value (order 0) or v-derivative (order 1..3) at v in [0, span]; a closed curve wraps any v.
  // At a knot the spline's pieces meet C2: `left_limit` evaluates the piece that ends there (what
  // a patch whose v-range ends at the knot sees) instead of the one that starts there.
  Vec3 evaluate(double v, int order = 0, bool left_limit = false) const;

  bool closed() const { return closed_; }
  double span() const { return span_; }
  const std::vector<Vec3>& points() const { return points_; }

 private:
  NetworkCurve() = default;

  std::vector<Vec3> points_;
  std::vector<Vec3> control_;  // open: P_-1 .. P_n (n + 2); closed: P_0 .. P_(n-1), periodic
  std::size_t spans_ = 0;
  double span_ = 1.0;
  bool closed_ = false;
};

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "network_curve.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Sparse>

#include "../core/finite_vector.hpp"

namespace odeskin {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Uniform cubic B-spline basis (and its derivatives) on one span, local x in [0, 1].
std::array<double, 4> basis(double x, int order) {
  const double y = 1.0 - x;
  switch (order) {
    case 0: return {y * y * y / 6.0, (3.0 * x * x * x - 6.0 * x * x + 4.0) / 6.0,
                    (-3.0 * x * x * x + 3.0 * x * x + 3.0 * x + 1.0) / 6.0, x * x * x / 6.0};
    case 1: return {-0.5 * y * y, 0.5 * (3.0 * x * x - 4.0 * x), 0.5 * (-3.0 * x * x + 2.0 * x + 1.0), 0.5 * x * x};
    case 2: return {y, 3.0 * x - 2.0, 1.0 - 3.0 * x, x};
    default: return {-1.0, 3.0, -3.0, 1.0};
  }
}

}  // namespace

Result<NetworkCurve> NetworkCurve::interpolate(std::span<const Vec3> points, bool closed, double span) {
  const std::size_t n = points.size();
  if (n < (closed ? 3u : 2u)) {
    return invalidArgument("network curve: " + std::to_string(n) + " points; a " + (closed ? "closed" : "open") +
                           " curve needs at least " + (closed ? "3" : "2"));
  }
  if (!(std::isfinite(span) && span > 0.0)) return invalidArgument("network curve: the parameter span must be > 0");
  for (std::size_t i = 0; i < n; ++i) {
    if (!isFinite(points[i])) {
      return invalidArgument("network curve: point " + std::to_string(i) + " is not finite");
    }
  }
  NetworkCurve curve;
  curve.points_.assign(points.begin(), points.end());
  curve.closed_ = closed;
  curve.span_ = span;
  curve.spans_ = closed ? n : n - 1;

  // Unknowns: closed P_0..P_(n-1); open P_-1..P_n stored at index i + 1. Rows i < n interpolate
  // point i: (P_(i-1) + 4 P_i + P_(i+1)) / 6 = Q_i; open curves add two end conditions.
  const std::size_t unknowns = closed ? n : n + 2;
  Triplets t;
  auto col = [&](long i) {
    return static_cast<int>(closed ? static_cast<std::size_t>((i + static_cast<long>(n)) % static_cast<long>(n))
                                   : static_cast<std::size_t>(i + 1));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const long k = static_cast<long>(i);
    t.emplace_back(static_cast<int>(i), col(k - 1), 1.0 / 6.0);
    t.emplace_back(static_cast<int>(i), col(k), 4.0 / 6.0);
    t.emplace_back(static_cast<int>(i), col(k + 1), 1.0 / 6.0);
  }
  if (!closed) {
    const long last = static_cast<long>(n) - 1;
    if (n >= 4) {
      // Not-a-knot: the third derivative is continuous at knots 1 and n - 2.
      const double w[5] = {-1.0, 4.0, -6.0, 4.0, -1.0};
      for (int j = 0; j < 5; ++j) {
        t.emplace_back(static_cast<int>(n), col(j - 1), w[j]);
        t.emplace_back(static_cast<int>(n + 1), col(last - 3 + j), w[j]);
      }
    } else {
      // Natural: zero second derivative at both ends.
      const double w[3] = {1.0, -2.0, 1.0};
      for (int j = 0; j < 3; ++j) {
        t.emplace_back(static_cast<int>(n), col(j - 1), w[j]);
        t.emplace_back(static_cast<int>(n + 1), col(last - 1 + j), w[j]);
      }
    }
  }
  Eigen::SparseMatrix<double> a(static_cast<int>(unknowns), static_cast<int>(unknowns));
  a.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  if (lu.info() != Eigen::Success) return internalError("network curve: the spline system is singular");
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<int>(unknowns), 3);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) rhs(static_cast<int>(i), d) = points[i][d];
  }
  const Eigen::MatrixXd p = lu.solve(rhs);
  curve.control_.resize(unknowns);
  for (std::size_t i = 0; i < unknowns; ++i) {
    curve.control_[i] = Vec3(p(static_cast<int>(i), 0), p(static_cast<int>(i), 1), p(static_cast<int>(i), 2));
  }
  return curve;
}

Vec3 NetworkCurve::evaluate(double v, int order, bool left_limit) const {
  const double per_v = static_cast<double>(spans_) / span_;  // spline parameter per unit of v
  double s = v * per_v;
  if (closed_) {
    s = std::fmod(s, static_cast<double>(spans_));
    if (s < 0.0) s += static_cast<double>(spans_);
  }
  const double last = static_cast<double>(spans_ - 1);
  double k = std::floor(s);
  if (left_limit && k == s) k -= 1.0;  // the piece that ends at this knot (wraps below 0 when closed)
  if (closed_ && k < 0.0) {
    k += static_cast<double>(spans_);
    s += static_cast<double>(spans_);
  }
  k = std::clamp(k, 0.0, last);
  const double x = s - k;
  const auto span = static_cast<std::size_t>(k);
  const std::array<double, 4> b = basis(x, order);
  Vec3 out(0.0);
  for (std::size_t i = 0; i < 4; ++i) {
    // Span k uses P_(k-1) .. P_(k+2): open storage is shifted by one, closed wraps.
    const std::size_t index = closed_ ? (span + spans_ - 1 + i) % spans_ : span + i;
    out += b[i] * control_[index];
  }
  return out * std::pow(per_v, order);
}

}  // namespace odeskin

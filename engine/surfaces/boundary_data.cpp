// SPDX-License-Identifier: MIT
#include "boundary_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include <Eigen/Sparse>

#include "../core/finite_vector.hpp"

namespace odeskin {
namespace {

std::string num(double x) {
  char text[40];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// A vector-valued C2 cubic spline through uniformly spaced samples, periodic or natural: slopes
// (per sample spacing) from m_{j-1} + 4 m_j + m_{j+1} = 3 (P_{j+1} - P_{j-1}), with 2 m_0 + m_1
// and m_{n-2} + 2 m_{n-1} at the ends of an open curve; cubic Hermite pieces between samples.
class UniformSpline {
 public:
  UniformSpline(std::vector<Vec3> points, const VDomain& domain) : points_(std::move(points)), domain_(domain) {
    const auto n = static_cast<Eigen::Index>(points_.size());
    Eigen::SparseMatrix<double> a(n, n);
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs(n, 3);
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::Index prev = j - 1;
      Eigen::Index next = j + 1;
      double diagonal = 4.0;
      if (domain.periodic) {
        prev = (j + n - 1) % n;
        next = (j + 1) % n;
      } else if (j == 0 || j == n - 1) {
        diagonal = 2.0;
      }
      entries.emplace_back(j, j, diagonal);
      const Vec3 hi = points_[static_cast<std::size_t>(next < n ? next : j)];
      const Vec3 lo = points_[static_cast<std::size_t>(prev >= 0 ? prev : j)];
      if (prev >= 0) entries.emplace_back(j, prev, 1.0);
      if (next < n) entries.emplace_back(j, next, 1.0);
      for (int c = 0; c < 3; ++c) rhs(j, c) = 3.0 * (hi[c] - lo[c]);
    }
    a.setFromTriplets(entries.begin(), entries.end());
    // Symmetric and strictly diagonally dominant: LDL^T needs no pivoting.
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
    const Eigen::MatrixXd m = solver.solve(rhs);
    slopes_.resize(points_.size());
    for (Eigen::Index j = 0; j < n; ++j) slopes_[static_cast<std::size_t>(j)] = Vec3(m(j, 0), m(j, 1), m(j, 2));
  }

  Vec3 operator()(double v) const {
    const std::size_t n = points_.size();
    const double span = domain_.v_end - domain_.v_begin;
    const std::size_t pieces = domain_.periodic ? n : n - 1;
    double x = (v - domain_.v_begin) / span * static_cast<double>(pieces);
    if (domain_.periodic) {
      x = std::fmod(x, static_cast<double>(n));
      if (x < 0.0) x += static_cast<double>(n);
    } else {
      x = std::clamp(x, 0.0, static_cast<double>(pieces));
    }
    std::size_t j = std::min(static_cast<std::size_t>(x), pieces - 1);
    const double s = x - static_cast<double>(j);
    const std::size_t k = domain_.periodic ? (j + 1) % n : j + 1;
    const double h00 = (1.0 - s) * (1.0 - s) * (1.0 + 2.0 * s);
    const double h10 = s * (1.0 - s) * (1.0 - s);
    const double h01 = s * s * (3.0 - 2.0 * s);
    const double h11 = -s * s * (1.0 - s);
    return h00 * points_[j] + h10 * slopes_[j] + h01 * points_[k] + h11 * slopes_[k];
  }

 private:
  std::vector<Vec3> points_;
  std::vector<Vec3> slopes_;  // dP/dj (per sample spacing)
  VDomain domain_;
};

Status checkPolyline(const std::vector<Vec3>& points, const char* name) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!isFinite(p)) {
      return invalidArgument(std::string("trimline polyline: ") + name + " sample " + std::to_string(i) +
                             " is not finite");
    }
  }
  return okStatus();
}

}  // namespace

Status validateDomain(const VDomain& domain) {
  if (!std::isfinite(domain.v_begin) || !std::isfinite(domain.v_end) || !(domain.v_begin < domain.v_end)) {
    return invalidArgument("trimline v-domain [" + num(domain.v_begin) + ", " + num(domain.v_end) +
                           "] must be finite and increasing");
  }
  return okStatus();
}

Result<Trimline> trimlineFromFunctions(CurveFunction curve, CurveFunction tangent) {
  if (!curve) return invalidArgument("trimline: the curve function is empty");
  if (!tangent) return invalidArgument("trimline: the tangent function is empty");
  return Trimline{std::move(curve), std::move(tangent)};
}

Result<Trimline> trimlineFromPolylines(std::vector<Vec3> curve, std::vector<Vec3> tangent, const VDomain& domain) {
  ODESKIN_TRY(validateDomain(domain));
  if (curve.size() != tangent.size()) {
    return invalidArgument("trimline polyline: " + std::to_string(curve.size()) + " curve samples but " +
                           std::to_string(tangent.size()) + " tangent samples");
  }
  const std::size_t minimum = domain.periodic ? 3 : 2;
  if (curve.size() < minimum) {
    return invalidArgument("trimline polyline: " + std::to_string(curve.size()) + " samples, need at least " +
                           std::to_string(minimum) + (domain.periodic ? " for a closed curve" : ""));
  }
  ODESKIN_TRY(checkPolyline(curve, "curve"));
  ODESKIN_TRY(checkPolyline(tangent, "tangent"));
  auto c = std::make_shared<const UniformSpline>(std::move(curve), domain);
  auto t = std::make_shared<const UniformSpline>(std::move(tangent), domain);
  return Trimline{[c](double v) { return (*c)(v); }, [t](double v) { return (*t)(v); }};
}

Result<Trimline> trimlineFromSurface(SurfaceFunction surface, SurfaceFunction u_derivative, double u_iso,
                                     double tangent_scale) {
  if (!surface) return invalidArgument("trimline from surface: the surface function is empty");
  if (!std::isfinite(u_iso)) return invalidArgument("trimline from surface: u_iso is not finite");
  if (!std::isfinite(tangent_scale)) return invalidArgument("trimline from surface: tangent_scale is not finite");
  CurveFunction curve = [surface, u_iso](double v) { return surface(u_iso, v); };
  CurveFunction tangent;
  if (u_derivative) {
    tangent = [d = std::move(u_derivative), u_iso, tangent_scale](double v) { return tangent_scale * d(u_iso, v); };
  } else {
    // (-f(u+2h) + 8 f(u+h) - 8 f(u-h) + f(u-2h)) / 12h: fourth order, so h = 1e-3 balances the
    // truncation (h^4/30 |P^(5)|) against rounding (~1e-16/h).
    constexpr double h = 1e-3;
    tangent = [surface = std::move(surface), u_iso, tangent_scale](double v) {
      const Vec3 d = (-surface(u_iso + 2 * h, v) + 8.0 * surface(u_iso + h, v) - 8.0 * surface(u_iso - h, v) +
                      surface(u_iso - 2 * h, v)) /
                     (12.0 * h);
      return tangent_scale * d;
    };
  }
  return Trimline{std::move(curve), std::move(tangent)};
}

Result<BoundaryData> BoundaryData::create(Trimline start, Trimline end, const VDomain& domain) {
  ODESKIN_TRY(validateDomain(domain));
  if (!start.curve || !start.tangent) return invalidArgument("boundary data: the u = 0 trimline has an empty function");
  if (!end.curve || !end.tangent) return invalidArgument("boundary data: the u = 1 trimline has an empty function");
  BoundaryData out;
  out.start_ = std::move(start);
  out.end_ = std::move(end);
  out.domain_ = domain;
  return out;
}

TrimlineSample BoundaryData::at(double v) const {
  return {start_.curve(v), start_.tangent(v), end_.curve(v), end_.tangent(v)};
}

}  // namespace odeskin

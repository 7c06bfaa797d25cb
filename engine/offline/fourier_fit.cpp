// SPDX-License-Identifier: MIT
// Least-squares Fourier fit of iso-parametric curves (MATH.md 4.1-4.3; thesis Eqs 6.2-6.6, open
// curves per erratum G9): C(v) = [p0 + slope v] + sum_m c_m phi_m(v), c = argmin |A c - P|, A = QR.
#include "fourier_fit.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"

namespace odeskin {
namespace {

// MATH.md 4.2: full column rank requires min|R_ii| > 1e-10 max|R_ii|.
constexpr double kRankTolerance = 1e-10;

// Least squares by column-pivoted Householder QR. Pivoting makes |R_ii| non-increasing, so the
// MATH.md 4.2 test min|R_ii| > 1e-10 max|R_ii| reads off the diagonal and is rank revealing; with
// unpivoted QR a dependent column can hide behind a moderately small R_ii instead of a near-zero one.
// `what` describes the problem for the error message.
Status checkRank(const Eigen::ColPivHouseholderQR<Eigen::MatrixXd>& qr, const std::string& what) {
  const Eigen::VectorXd diag = qr.matrixR().diagonal().cwiseAbs();
  const double max_r = diag.maxCoeff();
  const double min_r = diag.minCoeff();
  if (!(min_r > kRankTolerance * max_r)) {
    return illPosed(what + ": rank deficient (min|R_ii| = " + messageNumber(min_r) +
                    ", max|R_ii| = " + messageNumber(max_r) + ")");
  }
  return okStatus();
}

// The checks on N, the parameters and the sample count (`samples` values).
Status validateParameters(std::span<const double> v, std::size_t samples, int modes, bool closed) {
  if (modes < 1 || modes > kMaxFourierModes) {
    return outOfRange("Fourier mode count N = " + std::to_string(modes) + " outside [1, " +
                      std::to_string(kMaxFourierModes) + "]");
  }
  if (v.size() != samples) {
    return invalidArgument("parameter count " + std::to_string(v.size()) +
                           " differs from sample count " + std::to_string(samples));
  }
  const std::size_t min_samples = closed ? 1 : 2;  // open curves need both end points
  if (samples < min_samples) {
    return invalidArgument(std::string(closed ? "closed" : "open") + " curve with " +
                           std::to_string(samples) + " samples: need at least " +
                           std::to_string(min_samples));
  }
  return okStatus();
}

Status validateFitInput(std::span<const double> v, std::span<const glm::dvec3> values, int modes,
                        bool closed) {
  ODESKIN_TRY(validateParameters(v, values.size(), modes, closed));
  for (std::size_t j = 0; j < values.size(); ++j) {
    if (!std::isfinite(v[j]) || !isFinite(values[j])) {
      return invalidArgument("non-finite parameter or sample at index " + std::to_string(j));
    }
  }
  // The trend p0 + slope v interpolates the end points only at v = 0 and v = 1 (MATH.md 4.3);
  // arcLengthParameters returns exactly these values.
  if (!closed && (v.front() != 0.0 || v.back() != 1.0)) {
    return invalidArgument("open curve parameters must start at 0 and end at 1 (got " +
                           messageNumber(v.front()) + " and " + messageNumber(v.back()) + ")");
  }
  return okStatus();
}

// Squared Frobenius norm of the residual A x - b: the fit's rss over all samples and coordinates.
double residualSumOfSquares(const Eigen::MatrixXd& a, const Eigen::MatrixXd& x, const Eigen::MatrixXd& b) {
  return (a * x - b).squaredNorm();
}

}  // namespace

// MATH.md 4.2: closed curves fit all samples with the full 2N+1 basis. MATH.md 4.3 (erratum G9),
// open curves: C(v) = P_0 + (P_J - P_0) v + sum_n [a_n (cos 2 pi n v - 1) + b_n sin 2 pi n v]; every
// correction term vanishes at v = 0 and v = 1, so the ends are exact, and a_n, b_n (2N unknowns)
// come from least squares over the interior samples j = 1..J-1.
struct FourierFitter::Design {
  Eigen::MatrixXd a;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr;
};

Result<FourierFitter> FourierFitter::create(std::span<const double> v, int modes, bool closed) {
  ODESKIN_TRY(validateParameters(v, v.size(), modes, closed));
  for (std::size_t j = 0; j < v.size(); ++j) {
    if (!std::isfinite(v[j])) return invalidArgument("non-finite parameter or sample at index " + std::to_string(j));
  }
  if (!closed && (v.front() != 0.0 || v.back() != 1.0)) {
    return invalidArgument("open curve parameters must start at 0 and end at 1 (got " +
                           messageNumber(v.front()) + " and " + messageNumber(v.back()) + ")");
  }
  const Eigen::Index rows = closed ? static_cast<Eigen::Index>(v.size()) : static_cast<Eigen::Index>(v.size()) - 2;
  const Eigen::Index cols = closed ? 2 * modes + 1 : 2 * modes;
  const std::string what =
      closed ? "closed curve with " + std::to_string(rows) + " samples cannot determine " + std::to_string(cols) +
                   " coefficients (N=" + std::to_string(modes) + ")"
             : "open curve with " + std::to_string(rows) + " interior samples cannot determine " +
                   std::to_string(cols) + " coefficients (N=" + std::to_string(modes) + ")";
  // Too few samples is rank deficient by counting; say so before QR (which also wants rows >= cols).
  if (rows < cols) return illPosed(what + ": rank deficient (too few samples)");
  auto design = std::make_shared<Design>();
  design->a.resize(rows, cols);
  std::vector<double> phi(static_cast<std::size_t>(2 * modes + 1));
  for (Eigen::Index r = 0; r < rows; ++r) {
    const auto j = static_cast<std::size_t>(r) + (closed ? 0 : 1);
    fourierBasis(v[j], modes, phi);
    if (closed) {
      for (Eigen::Index m = 0; m < cols; ++m) design->a(r, m) = phi[static_cast<std::size_t>(m)];
    } else {
      for (int n = 1; n <= modes; ++n) {
        design->a(r, 2 * n - 2) = phi[static_cast<std::size_t>(2 * n - 1)] - 1.0;
        design->a(r, 2 * n - 1) = phi[2 * static_cast<std::size_t>(n)];
      }
    }
  }
  design->qr.compute(design->a);
  ODESKIN_TRY(checkRank(design->qr, what));
  FourierFitter fitter;
  fitter.v_.assign(v.begin(), v.end());
  fitter.modes_ = modes;
  fitter.closed_ = closed;
  fitter.design_ = std::move(design);
  return fitter;
}

Result<FourierFit> FourierFitter::fit(std::span<const glm::dvec3> values) const {
  ODESKIN_TRY(validateFitInput(v_, values, modes_, closed_));
  const Eigen::MatrixXd& a = design_->a;
  const Eigen::Index rows = a.rows();
  const Eigen::Index cols = a.cols();
  FourierFit fit;
  fit.modes = modes_;
  fit.closed = closed_;
  Eigen::MatrixXd b(rows, 3);
  if (closed_) {
    for (Eigen::Index j = 0; j < rows; ++j) {
      for (int k = 0; k < 3; ++k) b(j, k) = values[static_cast<std::size_t>(j)][k];
    }
  } else {
    fit.p0 = values.front();
    fit.slope = values.back() - fit.p0;
    for (Eigen::Index r = 0; r < rows; ++r) {
      const auto j = static_cast<std::size_t>(r) + 1;
      const glm::dvec3 detrended = values[j] - (fit.p0 + fit.slope * v_[j]);
      for (int k = 0; k < 3; ++k) b(r, k) = detrended[k];
    }
  }
  const Eigen::MatrixXd c(design_->qr.solve(b));
  if (closed_) {
    fit.coefficients.resize(static_cast<std::size_t>(cols));
    for (Eigen::Index m = 0; m < cols; ++m) {
      fit.coefficients[static_cast<std::size_t>(m)] = glm::dvec3(c(m, 0), c(m, 1), c(m, 2));
    }
  } else {
    // Layout of MATH.md 4.3: c_{2n-1} = a_n, c_{2n} = b_n, c_0 = -sum_n a_n.
    fit.coefficients.assign(static_cast<std::size_t>(cols) + 1, glm::dvec3(0.0));
    for (Eigen::Index m = 0; m < cols; ++m) {
      const glm::dvec3 cm(c(m, 0), c(m, 1), c(m, 2));
      fit.coefficients[static_cast<std::size_t>(m) + 1] = cm;
      if (m % 2 == 0) fit.coefficients[0] -= cm;
    }
  }
  fit.rss = residualSumOfSquares(a, c, b);
  return fit;
}

Result<std::vector<double>> arcLengthParameters(std::span<const glm::dvec3> points, bool closed) {
  if (points.size() < 2) {
    return invalidArgument("arc-length parameters need at least 2 points, got " +
                           std::to_string(points.size()));
  }
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (!isFinite(points[j])) return invalidArgument("non-finite point at index " + std::to_string(j));
  }
  // Cumulative lengths l_1 + ... + l_j (MATH.md 4.1); closed curves add the segment P_{J-1} -> P_0.
  std::vector<double> v(points.size());
  double length = 0.0;
  v[0] = 0.0;
  for (std::size_t j = 1; j < points.size(); ++j) {
    length += glm::length(points[j] - points[j - 1]);
    v[j] = length;
  }
  if (closed) length += glm::length(points.front() - points.back());
  if (!(length > 0.0)) {
    return degenerate(std::string(closed ? "closed" : "open") + " curve of " +
                      std::to_string(points.size()) + " points has zero total length");
  }
  for (double& vj : v) vj /= length;
  // Open curves end at exactly 1 (rounding of the division could leave 1 - ulp), which the end
  // interpolation of MATH.md 4.3 relies on; closed curves keep v_{J-1} < 1 as computed.
  if (!closed) v.back() = 1.0;
  return v;
}

void fourierBasis(double v, int modes, std::span<double> out) {
  assert(modes >= 0 && out.size() >= static_cast<std::size_t>(2 * modes + 1));
  // Direct cos/sin per mode rather than the angle-addition recurrence: the fit is offline, and
  // the direct form keeps every entry within an ulp or two for all N <= 64.
  out[0] = 1.0;
  for (int n = 1; n <= modes; ++n) {
    const double angle = 2.0 * std::numbers::pi * n * v;
    out[static_cast<std::size_t>(2 * n - 1)] = std::cos(angle);
    out[2 * static_cast<std::size_t>(n)] = std::sin(angle);
  }
}

glm::dvec3 FourierFit::evaluate(double v) const {
  // Open curves add the trend of MATH.md 4.3; for closed curves p0 = slope = 0 by construction,
  // but skip them anyway so a closed fit never depends on those fields.
  glm::dvec3 c = closed ? glm::dvec3(0.0) : p0 + slope * v;
  if (coefficients.empty()) return c;
  c += coefficients[0];
  // Guard against a hand-edited fit whose modes and coefficient count disagree.
  const int usable_modes = std::min(modes, static_cast<int>((coefficients.size() - 1) / 2));
  for (int n = 1; n <= usable_modes; ++n) {
    const double angle = 2.0 * std::numbers::pi * n * v;
    c += coefficients[static_cast<std::size_t>(2 * n - 1)] * std::cos(angle) +
         coefficients[2 * static_cast<std::size_t>(n)] * std::sin(angle);
  }
  return c;
}

Result<FourierFit> fitFourier(std::span<const double> v, std::span<const glm::dvec3> values, int modes,
                              bool closed) {
  ODESKIN_TRY(validateFitInput(v, values, modes, closed));
  ODESKIN_ASSIGN_OR_RETURN(const FourierFitter fitter, FourierFitter::create(v, modes, closed));
  return fitter.fit(values);
}

}  // namespace odeskin

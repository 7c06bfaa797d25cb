// SPDX-License-Identifier: MIT
#include "mesh_network.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/parallel.hpp"
#include "../core/position_box.hpp"
#include "mesh_network_deviation.hpp"

namespace odeskin {
namespace {

Status checkOptions(const MeshNetworkOptions& o) {
  const auto range = [](const char* name, std::uint32_t value, std::uint32_t lo, std::uint32_t hi) {
    if (value >= lo && value <= hi) return okStatus();
    return invalidArgument(std::string(name) + " = " + std::to_string(value) + " is outside [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "]");
  };
  ODESKIN_TRY(range("rows", o.rows, 1, kMaxMeshNetworkPatches));
  ODESKIN_TRY(range("columns", o.columns, 1, kMaxMeshNetworkPatches));
  ODESKIN_TRY(range("points per column", o.points_per_column, 1, kMaxMeshNetworkCurvePoints));
  if (std::uint64_t{o.columns} * o.points_per_column + 1 > kMaxMeshNetworkCurvePoints) {
    return invalidArgument("columns x points per column + 1 = " +
                           std::to_string(std::uint64_t{o.columns} * o.points_per_column + 1) + " curve points exceed " +
                           std::to_string(kMaxMeshNetworkCurvePoints));
  }
  ODESKIN_TRY(range("derivative degree", o.derivative_degree, 2, 8));
  ODESKIN_TRY(range("derivative points", o.derivative_points, o.derivative_degree, 1000));
  if (!(o.derivative_window > 0.0 && o.derivative_window <= 1.0)) {
    return invalidArgument("derivative window = " + messageNumber(o.derivative_window) + " is outside (0, 1] row heights");
  }
  if (meshNetworkSampleCount(o) > kMaxMeshNetworkSamples) {
    return outOfRange(std::to_string(o.rows) + " x " + std::to_string(o.columns) + " patches with " +
                      std::to_string(o.points_per_column) + " points per column read " +
                      std::to_string(meshNetworkSampleCount(o)) + " mesh samples, more than " +
                      std::to_string(kMaxMeshNetworkSamples));
  }
  return okStatus();
}

std::vector<double> sideOffsets(double window, std::uint32_t points, double sign) {
  std::vector<double> t;
  for (std::uint32_t k = 1; k <= points; ++k) t.push_back(sign * window * k / points);
  return t;
}

}  // namespace

std::uint64_t meshNetworkSampleCount(const MeshNetworkOptions& o) {
  const std::uint64_t points = std::uint64_t{o.columns} * o.points_per_column + 1, side = o.derivative_points;
  const std::uint64_t ends = o.rows >= 1 ? 2 : 0, inner = o.rows >= 1 ? o.rows - 1 : 0;
  return points * (ends * (1 + side) + inner * (1 + 2 * side));
}

Result<DerivativeStencil> derivativeStencil(std::vector<double> offsets, std::uint32_t degree) {
  const std::size_t n = offsets.size();
  if (degree < 1 || n < degree) {
    return invalidArgument("derivative stencil: " + std::to_string(n) + " samples cannot fix a polynomial of degree " +
                           std::to_string(degree));
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(offsets[k]) || offsets[k] == 0.0) {
      return invalidArgument("derivative stencil: offset " + std::to_string(k) + " must be finite and nonzero");
    }
    for (std::size_t l = 0; l < k; ++l) {
      if (offsets[l] == offsets[k]) return invalidArgument("derivative stencil: offsets " + std::to_string(l) + " and " + std::to_string(k) + " coincide");
    }
  }
  // S(t) - S(0) = sum_{p=1..degree} a_p t^p, scaled so the columns are of one size.
  const double scale = *std::max_element(offsets.begin(), offsets.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  const double h = std::abs(scale);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(degree));
  for (std::size_t k = 0; k < n; ++k) {
    for (std::uint32_t p = 1; p <= degree; ++p) a(static_cast<Eigen::Index>(k), p - 1) = std::pow(offsets[k] / h, p);
  }
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> decomposition(a);
  if (decomposition.rank() < static_cast<Eigen::Index>(degree)) {
    return invalidArgument("derivative stencil: the samples do not fix a polynomial of degree " + std::to_string(degree));
  }
  const Eigen::MatrixXd pseudo_inverse = decomposition.pseudoInverse();
  DerivativeStencil s;
  s.offsets = std::move(offsets);
  for (std::size_t k = 0; k < n; ++k) {
    s.first.push_back(pseudo_inverse(0, static_cast<Eigen::Index>(k)) / h);
    s.second.push_back(degree >= 2 ? 2.0 * pseudo_inverse(1, static_cast<Eigen::Index>(k)) / (h * h) : 0.0);
  }
  return s;
}

Result<MeshNetwork> MeshNetwork::extract(std::span<const Vec3> positions, const FaceList& faces,
                                         const MeshNetworkOptions& options) {
  ODESKIN_TRY(checkOptions(options));
  MeshNetwork m;
  m.options_ = options;
  ODESKIN_ASSIGN_OR_RETURN(m.disk_, parameteriseDisk(positions, faces));
  m.vertex_uv_.assign(m.disk_.uv.begin(), m.disk_.uv.begin() + static_cast<std::ptrdiff_t>(m.disk_.vertex_count));

  const double window = options.derivative_window;
  const std::uint32_t k = options.derivative_points;
  std::vector<double> inner = sideOffsets(window, k, -1.0);
  const std::vector<double> after = sideOffsets(window, k, 1.0);
  inner.insert(inner.end(), after.begin(), after.end());
  for (std::vector<double> offsets : {after, inner, sideOffsets(window, k, -1.0)}) {
    ODESKIN_ASSIGN_OR_RETURN(DerivativeStencil s, derivativeStencil(std::move(offsets), options.derivative_degree));
    m.stencils_.push_back(std::move(s));
  }

  const DiskLocator locator(m.disk_);
  const std::uint32_t rows = options.rows, n = m.curvePoints();
  m.boundary_offsets_.push_back(0);
  for (std::uint32_t b = 0; b <= rows; ++b) {
    const DerivativeStencil& s = m.stencils_[b == 0 ? 0 : b == rows ? 2 : 1];
    m.boundary_offsets_.push_back(m.boundary_offsets_.back() + std::size_t{n} * (1 + s.offsets.size()));
  }
  m.points_.resize(m.boundary_offsets_.back());
  parallelFor(std::uint32_t{0}, rows + 1, [&](std::uint32_t b) {
    const DerivativeStencil& s = m.stencils_[b == 0 ? 0 : b == rows ? 2 : 1];
    const double u = static_cast<double>(b) / rows;
    std::size_t at = m.boundary_offsets_[b];
    for (std::uint32_t j = 0; j < n; ++j) {
      const double v = static_cast<double>(j) / (n - 1);
      m.points_[at++] = locator.locate({u, v});
      for (double t : s.offsets) m.points_[at++] = locator.locate({u + t / rows, v});
    }
  });
  return m;
}

Result<NetworkDescription> MeshNetwork::describe(std::span<const Vec3> positions) const {
  if (positions.size() != disk_.vertex_count) {
    return invalidArgument("the pose has " + std::to_string(positions.size()) + " vertices, the network's mesh " +
                           std::to_string(disk_.vertex_count));
  }
  ODESKIN_TRY(checkedPositionBox(positions, "the pose", 1).status());
  const std::vector<Vec3> x = diskPositions(disk_, positions);
  const std::uint32_t rows = options_.rows, n = curvePoints();
  NetworkDescription d;
  d.columns = options_.columns;
  d.closed_u = false;
  d.shapes.assign(std::size_t{rows} * options_.columns, options_.shape);
  for (std::uint32_t b = 0; b <= rows; ++b) {
    const DerivativeStencil& s = stencils_[b == 0 ? 0 : b == rows ? 2 : 1];
    std::vector<Vec3> c(n), c_u(n), c_uu(n);
    std::size_t at = boundary_offsets_[b];
    for (std::uint32_t j = 0; j < n; ++j) {
      c[j] = pointPosition(points_[at++], x);
      Vec3 first(0.0), second(0.0);
      for (std::size_t k = 0; k < s.offsets.size(); ++k) {
        const Vec3 difference = pointPosition(points_[at++], x) - c[j];
        first += s.first[k] * difference;
        second += s.second[k] * difference;
      }
      // A window far below the mesh's facets divides rounding by window^2 until it overflows.
      if (!isFinite(first) || !isFinite(second)) {
        return invalidArgument("boundary " + std::to_string(b) + ": the derivative fit over a window of " +
                               messageNumber(options_.derivative_window) +
                               " row heights gives u-derivatives that are not finite; widen the window");
      }
      c_u[j] = first;
      c_uu[j] = second;
    }
    std::string name("b");
    name += std::to_string(b);  // not "b" + ...: GCC 12's -Wrestrict false positive
    const auto first_curve = static_cast<std::uint32_t>(d.curve_names.size());
    for (std::vector<Vec3>* points : {&c, &c_u, &c_uu}) {
      std::string curve = name;
      if (points != &c) curve.append(points == &c_u ? "_u" : "_uu");
      d.curve_names.push_back(std::move(curve));
      d.curve_points.push_back(std::move(*points));
      d.curve_closed.push_back(false);
    }
    NetworkBoundary boundary;
    boundary.name = name;
    boundary.position = first_curve;
    boundary.source = DerivativeSource::kCurves;
    boundary.first_curve = first_curve + 1;
    boundary.second_curve = first_curve + 2;
    d.boundaries.push_back(boundary);
  }
  return d;
}

Result<Network> MeshNetwork::build(std::span<const Vec3> positions) const {
  ODESKIN_ASSIGN_OR_RETURN(NetworkDescription d, describe(positions));
  return Network::build(std::move(d));
}

std::vector<Vec3> MeshNetwork::reconstruct(const Network& network) const {
  return evaluateAtParameters(network, vertex_uv_);
}

}  // namespace odeskin

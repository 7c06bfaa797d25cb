// SPDX-License-Identifier: MIT
#include "pose_space_rbf.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "../core/disjoint_sets.hpp"

namespace odeskin {
namespace {

// Hull directions weaker than this (relative to the strongest) come from near-duplicate or
// near-collinear examples; keeping them would make the affine block nearly rank deficient.
constexpr double kHullRelativeThreshold = 1e-6;

double distance(const double* a, const double* b, std::size_t d) {
  double sum = 0.0;
  for (std::size_t j = 0; j < d; ++j) sum += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(sum);
}

}  // namespace

double RbfInterpolator::kernel(double r) const {
  switch (kernel_) {
    case RbfKernel::kGaussian: return std::exp(-(r / radius_) * (r / radius_));
    case RbfKernel::kPolyharmonic1: return r;
    case RbfKernel::kPolyharmonic3: return r * r * r;
  }
  return r * r * r;
}

Result<RbfInterpolator> RbfInterpolator::create(std::span<const double> examples, std::size_t dimension,
                                                const RbfOptions& options) {
  if (dimension == 0) return invalidArgument("rbf: pose-space dimension is 0");
  if (examples.empty() || examples.size() % dimension != 0) {
    return invalidArgument("rbf: " + std::to_string(examples.size()) + " values are not K >= 1 examples of dimension " +
                           std::to_string(dimension));
  }
  for (std::size_t i = 0; i < examples.size(); ++i) {
    if (!std::isfinite(examples[i])) {
      return invalidArgument("rbf: example " + std::to_string(i / dimension) + " coordinate " +
                             std::to_string(i % dimension) + " is not finite");
    }
  }
  if (!(options.regularization >= 0.0) || !std::isfinite(options.regularization)) {
    return invalidArgument("rbf: regularization must be a finite value >= 0");
  }
  if (!(options.radius_scale > 0.0) || !std::isfinite(options.radius_scale)) {
    return invalidArgument("rbf: radius scale must be positive");
  }
  RbfInterpolator rbf;
  rbf.kernel_ = options.kernel;
  rbf.dimension_ = dimension;
  rbf.example_count_ = examples.size() / dimension;
  rbf.groupExamples(examples);
  const std::size_t g_count = rbf.group_sizes_.size();  // the interpolation runs over the groups' centres
  const double* p = rbf.centres_.data();

  // Affine hull: principal directions of the centred examples.
  Eigen::MatrixXd centred(g_count, dimension);
  rbf.mean_.assign(dimension, 0.0);
  for (std::size_t k = 0; k < g_count; ++k) {
    for (std::size_t j = 0; j < dimension; ++j) rbf.mean_[j] += p[k * dimension + j] / static_cast<double>(g_count);
  }
  for (std::size_t k = 0; k < g_count; ++k) {
    for (std::size_t j = 0; j < dimension; ++j) {
      centred(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = p[k * dimension + j] - rbf.mean_[j];
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    if (sigma(i) > kHullRelativeThreshold * sigma(0) && sigma(i) > 0.0) ++rbf.hull_dimension_;
  }
  const std::size_t m = rbf.hull_dimension_;
  rbf.hull_.resize(m * dimension);
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < dimension; ++j) {
      rbf.hull_[i * dimension + j] = svd.matrixV()(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i));
    }
  }

  // Gaussian radius from the examples' spacing (1 when they all coincide).
  if (rbf.kernel_ == RbfKernel::kGaussian) {
    double sum = 0.0;
    for (std::size_t k = 0; k < g_count; ++k) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t l = 0; l < g_count; ++l) {
        if (l != k) nearest = std::min(nearest, distance(p + k * dimension, p + l * dimension, dimension));
      }
      if (std::isfinite(nearest)) sum += nearest;
    }
    const double mean_nearest = g_count > 1 ? sum / static_cast<double>(g_count) : 0.0;
    rbf.radius_ = options.radius_scale * (mean_nearest > 0.0 ? mean_nearest : 1.0);
  }

  const std::size_t n = g_count + 1 + m;
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  double largest = 1.0;
  for (std::size_t k = 0; k < g_count; ++k) {
    for (std::size_t l = 0; l < g_count; ++l) {
      const double phi = rbf.kernel(distance(p + k * dimension, p + l * dimension, dimension));
      system(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) = phi;
      largest = std::max(largest, std::abs(phi));
    }
  }
  const double ridge = options.regularization * largest;
  for (std::size_t k = 0; k < g_count; ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    system(row, row) += ridge;
    system(row, static_cast<Eigen::Index>(g_count)) = 1.0;
    system(static_cast<Eigen::Index>(g_count), row) = 1.0;
    for (std::size_t i = 0; i < m; ++i) {
      double yi = 0.0;
      for (std::size_t j = 0; j < dimension; ++j) yi += rbf.hull_[i * dimension + j] * (p[k * dimension + j] - rbf.mean_[j]);
      const auto col = static_cast<Eigen::Index>(g_count + 1 + i);
      system(row, col) = yi;
      system(col, row) = yi;
    }
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(system);
  if (!lu.isInvertible()) {
    return illPosed("rbf: the pose-space system is singular (" + std::to_string(g_count) +
                    " distinct examples; use a positive regularization)");
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(g_count));
  for (std::size_t k = 0; k < g_count; ++k) rhs(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k)) = 1.0;
  const Eigen::MatrixXd solution = lu.solve(rhs);
  if (!solution.allFinite()) return illPosed("rbf: the pose-space system gave non-finite weights");
  rbf.cardinal_.resize(n * g_count);
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t k = 0; k < g_count; ++k) {
      rbf.cardinal_[r * g_count + k] = solution(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
    }
  }
  return rbf;
}

// Interpolating two examples closer than kMergeRelative would take weights of order (spread /
// their distance): with horse keys whose skeletons were 1e-5 apart, psd_lbs was 144% of the box off.
void RbfInterpolator::groupExamples(std::span<const double> examples) {
  const std::size_t k_count = example_count_;
  const std::size_t d = dimension_;
  std::vector<double> between(k_count * k_count, 0.0);
  double diameter = 0.0;
  for (std::size_t k = 0; k < k_count; ++k) {
    for (std::size_t l = k + 1; l < k_count; ++l) {
      between[k * k_count + l] = distance(&examples[k * d], &examples[l * d], d);
      diameter = std::max(diameter, between[k * k_count + l]);
    }
  }
  // Single linkage: a chain of close examples is one group, numbered by its first example (a set's
  // root is its smallest member).
  DisjointSets sets(k_count);
  for (std::size_t k = 0; k < k_count; ++k) {
    for (std::size_t l = k + 1; l < k_count; ++l) {
      if (between[k * k_count + l] <= kMergeRelative * diameter) {
        sets.unite(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(l));
      }
    }
  }
  group_of_.assign(k_count, 0);
  std::vector<std::uint32_t> group_of_root(k_count, std::numeric_limits<std::uint32_t>::max());
  for (std::size_t k = 0; k < k_count; ++k) {
    std::uint32_t& g = group_of_root[sets.find(static_cast<std::uint32_t>(k))];
    if (g == std::numeric_limits<std::uint32_t>::max()) {
      g = static_cast<std::uint32_t>(group_sizes_.size());
      group_sizes_.push_back(0);
      centres_.resize(centres_.size() + d, 0.0);
    }
    group_of_[k] = g;
    ++group_sizes_[g];
    for (std::size_t j = 0; j < d; ++j) centres_[g * d + j] += examples[k * d + j];
  }
  for (std::size_t g = 0; g < group_sizes_.size(); ++g) {
    for (std::size_t j = 0; j < d; ++j) centres_[g * d + j] /= static_cast<double>(group_sizes_[g]);
  }
}

void RbfInterpolator::weights(std::span<const double> query, std::span<double> out) const {
  assert(query.size() >= dimension_ && out.size() >= example_count_);
  const std::size_t g_count = group_sizes_.size();
  const std::size_t m = hull_dimension_;
  std::vector<double> basis(g_count + 1 + m);
  for (std::size_t g = 0; g < g_count; ++g) basis[g] = kernel(distance(query.data(), centres_.data() + g * dimension_, dimension_));
  basis[g_count] = 1.0;
  for (std::size_t i = 0; i < m; ++i) {
    double yi = 0.0;
    for (std::size_t j = 0; j < dimension_; ++j) yi += hull_[i * dimension_ + j] * (query[j] - mean_[j]);
    basis[g_count + 1 + i] = yi;
  }
  for (std::size_t k = 0; k < example_count_; ++k) {
    const std::uint32_t g = group_of_[k];
    double a = 0.0;
    for (std::size_t r = 0; r < basis.size(); ++r) a += cardinal_[r * g_count + g] * basis[r];
    out[k] = a / static_cast<double>(group_sizes_[g]);
  }
}

}  // namespace odeskin

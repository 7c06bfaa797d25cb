// SPDX-License-Identifier: MIT
// Scattered-data interpolation over pose space for pose-space deformation (Lewis, Cordner, Fong
// 2000, section 4): radial basis functions plus an affine term,
//   s(q) = sum_k lambda_k phi(|q - p_k|) + c_0 + c^T y(q),
// where y(q) = U^T (q - pbar) are coordinates in the affine hull of the K examples p_k (U: an
// orthonormal basis of span{p_k - pbar}, at most K-1 directions). Interpolating the unit vectors
// e_k gives cardinal weights a_k(q): a_k(p_j) = delta_kj (every example reproduced), and since the
// affine term reproduces constants and affine functions on the hull, sum_k a_k(q) = 1 everywhere
// (partition of unity) and with two examples a_k is exactly linear along the line through them.
//
// Kernels (r = |q - p_k| in the full pose space, so poses off the hull are still weighed by
// distance):
//   kGaussian        phi = exp(-(r / sigma)^2), sigma = radius_scale x the mean distance from each
//                    example to its nearest other example (Lewis et al.'s choice of kernel; the
//                    radius follows the examples' spacing so the weights neither spike nor flatten).
//   kPolyharmonic1   phi = r       (conditionally positive definite of order 1; scale free)
//   kPolyharmonic3   phi = r^3     (order 2, the 3-D thin-plate analogue; C2 and scale free; default)
// Near-duplicate examples: examples within 1e-3 of the largest distance between two examples
// (chains of them included) are one group, interpolated at their mean and sharing its weight
// equally, so their correctives are averaged: interpolating each would take weights of order
// (spread / their distance), a blow-up wherever their correctives differ. Such keys are then hit
// only as well as their average hits them.
// Solve: the (G + 1 + m) saddle system over the G groups, [Phi + lambda I, P; P^T, 0], by Eigen's
// full-pivot LU, with the ridge lambda = regularization x max(1, max|Phi|); keys are hit to about
// that relative accuracy. Hull directions with a singular value below 1e-6 of the largest come from
// near-collinear examples and are dropped.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"

namespace odeskin {

enum class RbfKernel { kGaussian, kPolyharmonic1, kPolyharmonic3 };

struct RbfOptions {
  RbfKernel kernel = RbfKernel::kPolyharmonic3;
  double radius_scale = 1.0;       // kGaussian only
  double regularization = 1e-10;   // relative ridge (see above), >= 0
};

class RbfInterpolator {
 public:
  // Examples closer than this fraction of the largest distance between two examples are one group.
  static constexpr double kMergeRelative = 1e-3;

  // `examples`: K >= 1 points of the same dimension D >= 1, row-major (K x D). Errors:
  // kInvalidArgument (sizes, non-finite values, negative regularization or radius scale),
  // kIllPosed when the saddle system is singular (not seen with distinct groups; a guard).
  static Result<RbfInterpolator> create(std::span<const double> examples, std::size_t dimension,
                                        const RbfOptions& options = {});

  std::size_t exampleCount() const { return example_count_; }
  std::size_t groupCount() const { return group_sizes_.size(); }
  std::uint32_t groupOf(std::size_t example) const { return group_of_[example]; }  // numbered by first example
  std::size_t dimension() const { return dimension_; }
  std::size_t hullDimension() const { return hull_dimension_; }  // m, the affine hull's dimension
  double radius() const { return radius_; }                        // sigma (kGaussian), else 0

  // The K cardinal weights at `query` (D values) into `out` (K values). No checks beyond
  // assert-level sizes: the caller passes D and K entries.
  void weights(std::span<const double> query, std::span<double> out) const;

 private:
  double kernel(double r) const;
  // group_of_, group_sizes_ and centres_ from the K examples (see kMergeRelative).
  void groupExamples(std::span<const double> examples);

  RbfKernel kernel_ = RbfKernel::kPolyharmonic3;
  std::size_t example_count_ = 0;
  std::size_t dimension_ = 0;
  std::size_t hull_dimension_ = 0;
  double radius_ = 0.0;
  std::vector<std::uint32_t> group_of_;     // K
  std::vector<std::uint32_t> group_sizes_;  // G
  std::vector<double> centres_;             // G x D, each group's mean
  std::vector<double> mean_;                // D
  std::vector<double> hull_;                // m x D, orthonormal rows
  std::vector<double> cardinal_;            // (G + 1 + m) x G, row-major: M^-1 [I_G; 0]
};

}  // namespace odeskin

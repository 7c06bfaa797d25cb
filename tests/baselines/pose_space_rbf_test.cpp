// SPDX-License-Identifier: MIT
#include "engine/baselines/pose_space_rbf.hpp"

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace odeskin {
namespace {

constexpr RbfKernel kKernels[] = {RbfKernel::kGaussian, RbfKernel::kPolyharmonic1, RbfKernel::kPolyharmonic3};

// Five examples in 4-D (as a pose space of joint angles would give), not on one affine plane.
std::vector<double> examples() {
  return {0.0, 0.0, 0.0, 0.0,   0.9, 0.1, 0.0, 0.2,   0.2, 1.1, -0.3, 0.0,
          1.0, 1.0, 0.4, -0.5,  -0.4, 0.3, 0.8, 0.6};
}

TEST(RbfInterpolator, CardinalAtExamplesAndPartitionOfUnityEverywhere) {
  const std::vector<double> p = examples();
  for (RbfKernel kernel : kKernels) {
    RbfOptions options;
    options.kernel = kernel;
    Result<RbfInterpolator> rbf = RbfInterpolator::create(p, 4, options);
    ASSERT_TRUE(rbf.ok()) << rbf.status().toString();
    EXPECT_EQ(rbf->exampleCount(), 5u);
    EXPECT_EQ(rbf->hullDimension(), 4u);
    std::vector<double> a(5);
    for (std::size_t k = 0; k < 5; ++k) {
      rbf->weights(std::span<const double>(p).subspan(4 * k, 4), a);
      for (std::size_t l = 0; l < 5; ++l) EXPECT_NEAR(a[l], k == l ? 1.0 : 0.0, 1e-8) << k << " " << l;
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<double> q = {u(rng), u(rng), u(rng), u(rng)};
      rbf->weights(q, a);
      EXPECT_NEAR(std::accumulate(a.begin(), a.end(), 0.0), 1.0, 1e-9);
    }
  }
}

TEST(RbfInterpolator, TwoExamplesBlendLinearlyAlongTheirLine) {
  // With two examples the affine term alone interpolates: a_1 is the projection parameter s of the
  // query onto the line, whatever the kernel and whatever the query's distance from the line.
  const std::vector<double> p = {1.0, 0.0, 0.0, 3.0, 2.0, 0.0};
  for (RbfKernel kernel : kKernels) {
    RbfOptions options;
    options.kernel = kernel;
    Result<RbfInterpolator> rbf = RbfInterpolator::create(p, 3, options);
    ASSERT_TRUE(rbf.ok());
    EXPECT_EQ(rbf->hullDimension(), 1u);
    std::vector<double> a(2);
    for (double s : {0.0, 0.25, 0.5, 0.9, 1.3}) {
      const std::vector<double> q = {1.0 + 2.0 * s, 2.0 * s, 0.7};  // off the line along z
      rbf->weights(q, a);
      EXPECT_NEAR(a[1], s, 1e-12);
      EXPECT_NEAR(a[0], 1.0 - s, 1e-12);
    }
  }
}

TEST(RbfInterpolator, GaussianRadiusFollowsTheSpacing) {
  RbfOptions options;
  options.kernel = RbfKernel::kGaussian;
  options.radius_scale = 2.0;
  const std::vector<double> p = {0.0, 1.0, 3.0};  // nearest distances 1, 1, 2
  Result<RbfInterpolator> rbf = RbfInterpolator::create(p, 1, options);
  ASSERT_TRUE(rbf.ok());
  EXPECT_DOUBLE_EQ(rbf->radius(), 2.0 * 4.0 / 3.0);
}

TEST(RbfInterpolator, NearDuplicateExamplesStayFinite) {
  // Examples 1 and 2 are 1e-12 apart: one group, sharing its weight.
  const std::vector<double> p = {0.0, 0.0, 1.0, 0.0, 1.0, 1e-12, 0.0, 1.0};
  for (RbfKernel kernel : kKernels) {
    RbfOptions options;
    options.kernel = kernel;
    options.regularization = 1e-8;
    Result<RbfInterpolator> rbf = RbfInterpolator::create(p, 2, options);
    ASSERT_TRUE(rbf.ok()) << rbf.status().toString();
    std::vector<double> a(4);
    const std::vector<double> q = {0.6, 0.3};
    rbf->weights(q, a);
    for (double w : a) EXPECT_TRUE(std::isfinite(w));
    EXPECT_LT(std::abs(a[1]), 10.0);
    // Exact in exact arithmetic; the ridge leaves a condition number ~1e8, hence the tolerance.
    EXPECT_NEAR(a[0] + a[1] + a[2] + a[3], 1.0, 1e-6);
    // The first and last examples are still hit.
    rbf->weights(std::span<const double>(p).subspan(0, 2), a);
    EXPECT_NEAR(a[0], 1.0, 1e-6);
  }
}

TEST(RbfInterpolator, RejectsBadInput) {
  EXPECT_EQ(RbfInterpolator::create({}, 3).status().code(), StatusCode::kInvalidArgument);
  const std::vector<double> p = {0.0, 1.0, 2.0, 3.0};
  EXPECT_EQ(RbfInterpolator::create(p, 3).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(RbfInterpolator::create(p, 0).status().code(), StatusCode::kInvalidArgument);
  const std::vector<double> nan = {0.0, std::nan("")};
  EXPECT_EQ(RbfInterpolator::create(nan, 1).status().code(), StatusCode::kInvalidArgument);
  RbfOptions negative;
  negative.regularization = -1.0;
  EXPECT_EQ(RbfInterpolator::create(p, 2, negative).status().code(), StatusCode::kInvalidArgument);
}

TEST(RbfInterpolator, CoincidingExamplesShareOneWeightEvenWithoutARidge) {
  // Alone, their cubic kernel matrix is all zeros; as one group the system is well posed.
  RbfOptions no_ridge;
  no_ridge.regularization = 0.0;
  const std::vector<double> same = {1.0, 2.0, 1.0, 2.0};
  Result<RbfInterpolator> rbf = RbfInterpolator::create(same, 2, no_ridge);
  ASSERT_TRUE(rbf.ok()) << rbf.status().toString();
  EXPECT_EQ(rbf->groupCount(), 1u);
  std::vector<double> a(2);
  rbf->weights(std::vector<double>{5.0, -3.0}, a);
  EXPECT_EQ(a[0], 0.5);
  EXPECT_EQ(a[1], 0.5);
}

// Examples 0, e1, e1 + d e2 and e3: interpolating both near-duplicates needs slopes of 1/d, and at
// d = 1e-5 the weights reached 2e5 (found probing psd_lbs on horse keys whose skeletons were that
// close). Below 1e-3 of the largest distance they are one group now; above it they are still hit.
TEST(RbfInterpolator, NearDuplicatesAreAveragedNotBlownUp) {
  for (const double d : {1e-5, 1e-7, 1e-12}) {
    const std::vector<double> p = {0, 0, 0, 1, 0, 0, 1, d, 0, 0, 0, 1};
    for (RbfKernel kernel : kKernels) {
      RbfOptions options;
      options.kernel = kernel;
      Result<RbfInterpolator> rbf = RbfInterpolator::create(p, 3, options);
      ASSERT_TRUE(rbf.ok()) << rbf.status().toString();
      EXPECT_EQ(rbf->groupCount(), 3u);
      EXPECT_EQ(rbf->groupOf(1), rbf->groupOf(2));
      std::vector<double> a(4);
      double largest = 0.0;
      for (double x = -1.0; x <= 2.0; x += 0.25) {
        for (double y = -1.0; y <= 2.0; y += 0.25) {
          for (double z = -1.0; z <= 2.0; z += 0.25) {
            rbf->weights(std::vector<double>{x, y, z}, a);
            EXPECT_NEAR(a[0] + a[1] + a[2] + a[3], 1.0, 1e-9) << d << " " << x << " " << y << " " << z;
            EXPECT_EQ(a[1], a[2]);
            for (const double w : a) largest = std::max(largest, std::abs(w));
          }
        }
      }
      EXPECT_LT(largest, 4.0) << "d " << d;  // 3.0 at the grid's far corner, where the affine term extrapolates
      rbf->weights(std::span<const double>(p).subspan(3, 3), a);
      EXPECT_NEAR(a[1], 0.5, 1e-6) << d;
      EXPECT_NEAR(a[2], 0.5, 1e-6) << d;
    }
  }
  const std::vector<double> apart = {0, 0, 0, 1, 0, 0, 1, 1e-2, 0, 0, 0, 1};
  Result<RbfInterpolator> rbf = RbfInterpolator::create(apart, 3);
  ASSERT_TRUE(rbf.ok());
  EXPECT_EQ(rbf->groupCount(), 4u);
  std::vector<double> a(4);
  rbf->weights(std::span<const double>(apart).subspan(6, 3), a);
  EXPECT_NEAR(a[2], 1.0, 1e-6);
  EXPECT_NEAR(a[1], 0.0, 1e-6);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "engine/baselines/fd_curve_deformer.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "arm_fixture.hpp"
#include "engine/baselines/odeskin_baseline.hpp"
#include "engine/kernels/fourier_deform_job.hpp"
#include "engine/offline/residual_fit.hpp"

namespace odeskin {
namespace {

using testing::makeArmKeys;
using testing::maxDistance;

// Visible inertia and damping, and some bending (stiffening sign, so every mode is stable).
const Material kDynamic{1.0, 0.6, 30.0, 0.002, BendingSign::kStiffening};

std::vector<Vec3> evaluate(Baseline& method, std::uint32_t segment, double tau) {
  std::vector<Vec3> out(method.vertexCount());
  const Status s = method.evaluate({segment, tau, {}}, out);
  EXPECT_TRUE(s.ok()) << s.toString();
  return out;
}

FdCurveDeformer makeFd(const DeformAsset& asset, std::uint32_t points, std::uint32_t steps) {
  FdCurveOptions options;
  options.points = points;
  options.steps = steps;
  options.material = kDynamic;
  Result<FdCurveDeformer> fd = FdCurveDeformer::create(asset, options);
  EXPECT_TRUE(fd.ok()) << fd.status().toString();
  return std::move(*fd);
}

// Refines J and T together and checks the FD deformer's order against the analytic deformer.
void expectSecondOrder(const DeformAsset& asset, double box, const char* label) {
  Result<OdeskinBaseline> analytic = OdeskinBaseline::create(asset, kDynamic, BaselineMethod::kOdeskinDynamic);
  ASSERT_TRUE(analytic.ok()) << analytic.status().toString();
  // Frames on every grid's levels (tau = 1/2) and between levels (tau = 0.3), in the first segment
  // (from rest) and the second (the FD method's own carried rate against the analytic one).
  struct Frame {
    std::uint32_t segment;
    double tau;
  };
  for (const Frame f : {Frame{0, 0.5}, Frame{1, 0.5}, Frame{1, 0.3}}) {
    const std::vector<Vec3> exact = evaluate(*analytic, f.segment, f.tau);
    std::vector<double> errors;
    for (std::uint32_t scale : {1u, 2u, 4u, 8u}) {
      FdCurveDeformer fd = makeFd(asset, 12 * scale, 8 * scale);
      errors.push_back(maxDistance(evaluate(fd, f.segment, f.tau), exact) / box);
    }
    for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
      const double order = std::log2(errors[k] / errors[k + 1]);
      std::printf("[ fd vs analytic ] %-12s segment %u tau %.1f  J=%2u T=%2u  MVE %.3e -> %.3e  order %.2f\n", label,
                  f.segment, f.tau, 12u << k, 8u << k, errors[k], errors[k + 1], order);
      EXPECT_GT(order, 1.6);
      EXPECT_LT(order, 2.5);
    }
    EXPECT_LT(errors.back(), 1e-3);
  }
}

TEST(FdCurveDeformer, ConvergesToTheAnalyticDeformerAtSecondOrder) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 60.0, 120.0}, 0.4);
  const double box = longestBoxSide(arm.keys[1]);
  expectSecondOrder(arm.asset, box, "closed");
  // Open curves carry a linear trend slope * v (the last coefficient), solved on its own J = 1
  // grid; give every curve one, as an open curve's fit would.
  DeformAsset open = arm.asset;
  const std::size_t m_count = coefficientsPerCurve(open.modes);
  for (std::size_t s = 0; s < open.segments.size(); ++s) {
    for (std::size_t c = 0; c < open.curveCount(); ++c) {
      open.segments[s].coefficients[c * m_count + m_count - 1] = Vec3(0.01 * static_cast<double>(s + 1), -0.02, 0.005 * static_cast<double>(c));
    }
  }
  ASSERT_TRUE(chainSegmentRates(open).ok());
  expectSecondOrder(open, box, "open trend");
}

TEST(FdCurveDeformer, ReproducesTheSegmentEndsLikeOdeskin) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 60.0, 120.0}, 0.4);
  Result<OdeskinBaseline> analytic = OdeskinBaseline::create(arm.asset, kDynamic, BaselineMethod::kOdeskinDynamic);
  ASSERT_TRUE(analytic.ok());
  FdCurveDeformer fd = makeFd(arm.asset, 16, 10);
  EXPECT_EQ(fd.name(), "fd_curve");
  const double box = longestBoxSide(arm.keys[1]);
  for (std::uint32_t s = 0; s < 2; ++s) {
    for (double tau : {0.0, 1.0}) {
      const std::vector<Vec3> a = evaluate(*analytic, s, tau);
      const std::vector<Vec3> b = evaluate(fd, s, tau);
      EXPECT_LT(maxDistance(a, b), 1e-12 * box) << s << " " << tau;
      EXPECT_LT(maxDistance(b, arm.keys[s + (tau > 0.5 ? 1 : 0)]), 1e-4 * box);
    }
    // The last level holds the segment's fitted target exactly (the DFT inverts the sampling).
    const std::span<const Vec3> end = fd.levelCoefficients(s, fd.steps());
    const std::vector<Vec3>& d = arm.asset.segments[s].coefficients;
    for (std::size_t k = 0; k < d.size(); ++k) EXPECT_LT(glm::length(end[k] - d[k]), 1e-12) << k;
  }
}

TEST(FdCurveDeformer, ReportsSetupAndFrameCosts) {
  // Thesis Table 6.1 analogue on the arm: the FD method pays its space-time solves up front;
  // playback then costs about the analytic kernel. Printed for the record, checked for sanity.
  const testing::ArmKeys arm = makeArmKeys({0.0, 60.0, 120.0}, 0.4);
  FdCurveDeformer fd = makeFd(arm.asset, 32, 32);
  const FdCurveStats& stats = fd.stats();
  EXPECT_EQ(stats.curve_solves, 2 * arm.asset.curveCount());
  EXPECT_EQ(stats.unknowns_per_system, 32u * 32u);
  EXPECT_EQ(stats.factorizations, 2u);
  EXPECT_GT(stats.seconds_factor + stats.seconds_solve, 0.0);
  Result<OdeskinBaseline> analytic = OdeskinBaseline::create(arm.asset, kDynamic, BaselineMethod::kOdeskinDynamic);
  ASSERT_TRUE(analytic.ok());
  std::vector<Vec3> out(fd.vertexCount());
  auto per_frame = [&](Baseline& method) {
    constexpr int kFrames = 40;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < kFrames; ++f) EXPECT_TRUE(method.evaluate({1, (f + 0.5) / kFrames, {}}, out).ok());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kFrames;
  };
  const double fd_frame = per_frame(fd);
  const double analytic_frame = per_frame(*analytic);
  std::printf("[ fd timing ] %zu vertices, %zu curves: FD set-up %.2f ms (factor %.2f, %zu solves of %zu unknowns), "
              "FD %.3f ms/frame, analytic %.3f ms/frame\n",
              fd.vertexCount(), arm.asset.curveCount(), 1e3 * (stats.seconds_factor + stats.seconds_solve),
              1e3 * stats.seconds_factor, stats.curve_solves, stats.unknowns_per_system, 1e3 * fd_frame,
              1e3 * analytic_frame);
  EXPECT_GT(fd_frame, 0.0);
}

TEST(FdCurveDeformer, RejectsTooCoarseGrids) {
  const testing::ArmKeys arm = makeArmKeys({0.0, 60.0}, 0.4, 5);
  FdCurveOptions options;
  options.points = 10;  // 2N
  EXPECT_EQ(FdCurveDeformer::create(arm.asset, options).status().code(), StatusCode::kInvalidArgument);
  options.points = 11;
  options.steps = 1;
  EXPECT_EQ(FdCurveDeformer::create(arm.asset, options).status().code(), StatusCode::kInvalidArgument);
  options.steps = 4;
  options.material = Material{};
  EXPECT_EQ(FdCurveDeformer::create(arm.asset, options).status().code(), StatusCode::kDegenerate);
}

}  // namespace
}  // namespace odeskin

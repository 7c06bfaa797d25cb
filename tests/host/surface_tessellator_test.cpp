// SPDX-License-Identifier: MIT
// shaders/ode6_tessellate.comp against the CPU reference, under the validation layer (any message
// fails): the cardinal table for every shape of spec/vectors/ode6_cardinal.json, and the welded
// vertices of tubes, sheets, tori and the shipped sample networks at several resolutions (the
// smallest grid, sizes that are not multiples of the workgroup, and one that needs several
// dispatches). Parity: max |GPU - CPU| <= 1e-5 of the mesh's longest box side (positions) and
// <= 1e-5 (1 + |g|) (cardinal values); the worst index is reported.
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/offline/residual_fit.hpp"
#include "engine/surfaces/network_json.hpp"
#include "engine/surfaces/tessellation.hpp"
#include "host/gpu_test_support.hpp"
#include "host/surface_tessellator.hpp"
#include "surfaces/network_fixtures.hpp"

namespace odeskin {
namespace {

constexpr double kParity = 1e-5;

// One patch between two wavy open curves: the shape decides everything.
Network singlePatch(const Ode6Shape& shape) {
  NetworkDescription d;
  std::vector<Vec3> a, b;
  for (int k = 0; k < 9; ++k) {
    const double x = k / 8.0;
    a.emplace_back(2.0 * x, 0.0, 0.2 * std::sin(6.0 * x));
    b.emplace_back(2.0 * x, 1.5, 0.4 * std::cos(5.0 * x));
  }
  testing::addCurve(d, "a", a, false);
  testing::addCurve(d, "b", b, false);
  NetworkBoundary lower;
  lower.position = 0;
  lower.w_first = 0.8;
  lower.w_second = -1.5;
  NetworkBoundary upper;
  upper.position = 1;
  upper.w_first = 0.5;
  upper.w_second = 2.0;
  d.boundaries = {lower, upper};
  d.shapes = {shape};
  Result<Network> n = Network::build(d);
  EXPECT_TRUE(n.ok()) << n.status().toString();
  return std::move(n).value();
}

class SurfaceTessellatorTest : public testing::GpuTest {
 protected:
  // Worst |GPU - CPU| over the box side; `stride` > 1 compares every stride-th vertex only.
  double positionParity(const Network& n, TessellationResolution r, std::size_t stride = 1) {
    Result<SurfaceMesh> cpu = tessellateNetwork(n, r);
    EXPECT_TRUE(cpu.ok());
    Result<SurfaceTessellator> gpu = SurfaceTessellator::create(device(), n, r);
    EXPECT_TRUE(gpu.ok()) << gpu.status().toString();
    if (!cpu.ok() || !gpu.ok()) return INFINITY;
    EXPECT_TRUE(gpu->run().ok());
    std::vector<gpu::Float4> out(gpu->grid().vertexCount());
    EXPECT_TRUE(gpu->readPositions(out).ok());
    const double box = longestBoxSide(cpu->positions);
    double worst = 0.0;
    std::size_t worst_index = 0;
    for (std::size_t i = 0; i < out.size(); i += stride) {
      const Vec3 g(out[i].x, out[i].y, out[i].z);
      const double e = glm::length(g - cpu->positions[i]) / box;
      if (e > worst) {
        worst = e;
        worst_index = i;
      }
      EXPECT_EQ(out[i].w, 1.0f);
    }
    EXPECT_LE(worst, kParity) << "vertex " << worst_index << ": GPU (" << out[worst_index].x << ", "
                              << out[worst_index].y << ", " << out[worst_index].z << "), CPU ("
                              << cpu->positions[worst_index].x << ", " << cpu->positions[worst_index].y << ", "
                              << cpu->positions[worst_index].z << ")";
    return worst;
  }
};

TEST_F(SurfaceTessellatorTest, CardinalTableForEveryVectorShape) {
  std::ifstream in(std::string(ODESKIN_SPEC_DIR) + "/vectors/ode6_cardinal.json");
  const nlohmann::json vectors = nlohmann::json::parse(in);
  std::size_t cases = 0;
  double overall = 0.0;
  for (const nlohmann::json& c : vectors.at("cases")) {
    if (c.at("expect_error").get<bool>()) continue;
    const Ode6Shape shape{c.at("rho").get<double>(), c.at("eta").get<double>(), c.at("lambda").get<double>()};
    const Network n = singlePatch(shape);
    for (std::uint32_t samples : {2u, 11u, 65u}) {
      Result<SurfaceTessellator> gpu = SurfaceTessellator::create(device(), n, {samples, 3});
      ASSERT_TRUE(gpu.ok()) << gpu.status().toString();
      ASSERT_TRUE(gpu->run().ok());
      std::vector<float> table(gpu->cardinalTableSize());
      ASSERT_TRUE(gpu->readCardinalTable(table).ok());
      double worst = 0.0;
      for (std::uint32_t i = 0; i < samples; ++i) {
        const Ode6Values ref = n.cardinalAt(0).evaluate(static_cast<double>(i) / (samples - 1));
        for (std::size_t k = 0; k < 6; ++k) {
          worst = std::max(worst, std::abs(table[6 * std::size_t{i} + k] - ref[k]) / (1.0 + std::abs(ref[k])));
        }
      }
      EXPECT_LE(worst, kParity) << c.at("note") << ", " << samples << " samples";
      overall = std::max(overall, worst);
    }
    EXPECT_LE(positionParity(n, {65, 9}), kParity) << c.at("note");
    ++cases;
  }
  EXPECT_EQ(cases, 19u);
  std::printf("cardinal table, %zu vector shapes: worst |g_gpu - g_cpu| / (1 + |g_cpu|) = %.2e\n", cases, overall);
}

TEST_F(SurfaceTessellatorTest, NetworksMatchTheCpuReference) {
  testing::SweptSurface tube;
  testing::SweptSurface sheet;
  sheet.closed_v = false;
  sheet.columns = 3;
  sheet.points = 9;
  testing::SweptSurface torus;
  torus.closed_u = true;
  torus.rows = 4;
  torus.columns = 3;
  double overall = 0.0;
  for (const testing::SweptSurface& s : {tube, sheet, torus}) {
    Result<Network> n = Network::build(testing::sweptNetwork(s, testing::mixedRowShapes()));
    ASSERT_TRUE(n.ok());
    for (TessellationResolution r : {TessellationResolution{2, 2}, {7, 9}, {13, 100}, {33, 33}}) {
      overall = std::max(overall, positionParity(*n, r));
    }
  }
  const std::filesystem::path samples = std::filesystem::path(ODESKIN_SOURCE_DIR) / "samples/surfaces/networks";
  for (const char* name : {"vase.json", "sheet.json", "torus.json", "patch.json", "fig4_1b_warn.json"}) {
    Result<Network> n = loadNetwork(samples / name);
    ASSERT_TRUE(n.ok()) << n.status().toString();
    overall = std::max(overall, positionParity(*n, {41, 37}));
  }
  std::printf("networks: worst |S_gpu - S_cpu| / box = %.2e\n", overall);
}

TEST_F(SurfaceTessellatorTest, GridsLargerThanOneDispatch) {
  // 2100 x 2100 = 4.41M vertices > 65535 groups x 64: the vertex pass needs two dispatches.
  const Network n = singlePatch({1, 3, 1});
  EXPECT_LE(positionParity(n, {2100, 2100}, 997), kParity);
}

TEST_F(SurfaceTessellatorTest, ReadsCheckSizes) {
  Result<SurfaceTessellator> gpu = SurfaceTessellator::create(device(), singlePatch({1, 0, 0}), {3, 3});
  ASSERT_TRUE(gpu.ok());
  std::vector<gpu::Float4> wrong(8);
  EXPECT_EQ(gpu->readPositions(wrong).code(), StatusCode::kInvalidArgument);
  std::vector<float> table(5);
  EXPECT_EQ(gpu->readCardinalTable(table).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(SurfaceTessellator::create(device(), singlePatch({1, 0, 0}), {1, 3}).status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin

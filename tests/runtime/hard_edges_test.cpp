// SPDX-License-Identifier: MIT
// Hard edges (RuntimeAssetOptions::render_normals) on the CPU runtime: on the seamed cylinder
// (runtime_fixtures.hpp's withSeams: topology vertices 0-19 have a second render copy on the even
// faces), copies of vertices 0-9 are given bind normals 40 degrees apart (a hard edge) and those
// of 10-19 equal ones (a UV seam). Each side of a hard edge then gets the normal of its own
// triangles, every other render vertex the gathered normal to the bit, on both work paths; bad
// normals are refused naming them.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin {
namespace {

using testing::bindTangents;
using testing::Output;
using testing::readOutput;
using testing::withSeams;

using testing::hardEdgeNormals;
using testing::kHardCopies;

RuntimeAsset makeAsset(const DeformAsset& asset, std::vector<gpu::Float4> normals, bool tangents = false) {
  RuntimeAssetOptions options = testing::presetOptions();
  options.render_normals = std::move(normals);
  if (tangents) options.render_tangents = bindTangents(asset);
  Result<RuntimeAsset> r = RuntimeAsset::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}

CpuRuntime makeRuntime(const RuntimeAsset& asset, std::uint32_t capacity, bool tangents = false) {
  RuntimeOptions options;
  options.capacity = capacity;
  options.render_layout = true;
  options.tangents = tangents;
  Result<CpuRuntime> r = CpuRuntime::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}


Vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }

TEST(RuntimeAsset, HardEdgesAreWhereCopiesOfAVertexDisagree) {
  const DeformAsset source = withSeams(testing::cylinderAsset());
  const RuntimeAsset asset = makeAsset(source, hardEdgeNormals(source));
  EXPECT_TRUE(asset.hasHardEdges());
  EXPECT_EQ(asset.hardEdgeVertices(), kHardCopies);
  ASSERT_EQ(asset.renderCornerOffsets().size(), asset.renderVertexCount() + 1u);
  // A UV-seam copy (vertex 15's second) and a vertex off the seams keep their topology corners.
  const std::uint32_t v = asset.vertexCount();
  for (const std::uint32_t r : {v + 15, v - 1 - 100}) {
    const std::uint32_t i = asset.renderTopology()[r];
    const auto own = asset.renderCorners().subspan(asset.renderCornerOffsets()[r],
                                                   asset.renderCornerOffsets()[r + 1] - asset.renderCornerOffsets()[r]);
    const auto welded = asset.corners().subspan(asset.cornerOffsets()[i], asset.cornerOffsets()[i + 1] - asset.cornerOffsets()[i]);
    ASSERT_EQ(own.size(), welded.size()) << "render vertex " << r;
    EXPECT_EQ(0, std::memcmp(own.data(), welded.data(), own.size_bytes())) << "render vertex " << r;
  }
  // The two sides of a hard vertex split its corners between them.
  const std::uint32_t first = v - 1 - 3, second = v + 3;
  const auto count = [&](std::uint32_t r) { return asset.renderCornerOffsets()[r + 1] - asset.renderCornerOffsets()[r]; };
  EXPECT_EQ(count(first) + count(second), asset.cornerOffsets()[4] - asset.cornerOffsets()[3]);
  EXPECT_GT(count(first), 0u);
  EXPECT_GT(count(second), 0u);

  // Equal normals on every copy (a glTF with UV seams only): no hard edge, nothing changes.
  std::vector<gpu::Float4> smooth = hardEdgeNormals(source);
  for (std::uint32_t i = 0; i < kHardCopies; ++i) smooth[v + i] = smooth[v - 1 - i];
  EXPECT_FALSE(makeAsset(source, smooth).hasHardEdges());
}

// Two instances at different times; 4 threads, so capacity 1 spreads one instance over them and
// capacity 5 runs whole rounds: both give the same bits.
TEST(CpuRuntime, HardEdgeNormalsAreEachSidesOwn) {
  const tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
  const DeformAsset source = withSeams(testing::cylinderAsset());
  const RuntimeAsset hard = makeAsset(source, hardEdgeNormals(source), true);
  const RuntimeAsset smooth = testing::makeAssetWithTangents(source);
  CpuRuntime rt = makeRuntime(hard, 5, true);
  CpuRuntime gathered = makeRuntime(smooth, 5, true);
  CpuRuntime spread = makeRuntime(hard, 1, true);
  ASSERT_TRUE(rt.setInstanceCount(5).ok() && gathered.setInstanceCount(5).ok() && spread.setInstanceCount(1).ok());
  for (std::uint32_t k = 0; k < 5; ++k) {
    ASSERT_TRUE(rt.setInstance(k, InstanceState::atTime(0.6 * k + 0.1)).ok());
    ASSERT_TRUE(gathered.setInstance(k, InstanceState::atTime(0.6 * k + 0.1)).ok());
  }
  ASSERT_TRUE(spread.setInstance(0, InstanceState::atTime(0.1)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  Result<std::uint64_t> gathered_frame = gathered.submitFrame();
  Result<std::uint64_t> spread_frame = spread.submitFrame();
  ASSERT_TRUE(frame.ok() && gathered_frame.ok() && spread_frame.ok());

  const std::uint32_t v = hard.vertexCount();
  const std::span<const std::uint32_t> topology = hard.renderTopology();
  const std::span<const std::uint32_t> triangles = hard.renderTriangleIndices();
  double worst = 0.0, turn = 0.0;
  for (std::uint32_t k = 0; k < 5; ++k) {
    const auto positions = readOutput(rt, *frame, k, Output::kPositions);
    const auto normals = readOutput(rt, *frame, k, Output::kNormals);
    const auto tangents = readOutput(rt, *frame, k, Output::kTangents);
    const auto welded = readOutput(gathered, *gathered_frame, k, Output::kNormals);
    for (std::size_t r = 0; r < normals.size(); ++r) {
      if (topology[r] >= kHardCopies) {
        ASSERT_EQ(testing::bitsOf(normals[r]), testing::bitsOf(welded[r])) << "render vertex " << r;
        continue;
      }
      // This side's own triangles, in double, from the frame's positions.
      Vec3 expected(0.0);
      for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
        for (int c = 0; c < 3; ++c) {
          if (triangles[t + c] != r) continue;
          const Vec3 p = xyz(positions[r]);
          expected += glm::cross(xyz(positions[triangles[t + (c + 1) % 3]]) - p, xyz(positions[triangles[t + (c + 2) % 3]]) - p);
        }
      }
      expected = glm::normalize(expected);
      const double gap = glm::length(xyz(normals[r]) - expected);
      worst = std::max(worst, gap);
      ASSERT_LT(gap, 1e-5) << "instance " << k << " render vertex " << r;
      turn = std::max(turn, std::acos(std::min(1.0, glm::dot(xyz(normals[r]), xyz(welded[r])))));
      ASSERT_LT(std::fabs(glm::dot(xyz(tangents[r]), xyz(normals[r]))), 1e-5) << "render vertex " << r;
    }
  }
  // The hard sides differ from the welded normal: the cylinder's faces turn 18 degrees apiece.
  EXPECT_GT(turn, 0.05);
  std::printf("hard edges: max |normal - own triangles' normal| = %.2e; sides up to %.1f degrees from the welded normal\n",
              worst, turn * 180.0 / M_PI);
  EXPECT_EQ(v + 20, hard.renderVertexCount());

  for (const Output what : {Output::kNormals, Output::kTangents}) {
    const auto rounds = readOutput(rt, *frame, 0, what), alone = readOutput(spread, *spread_frame, 0, what);
    EXPECT_EQ(0, std::memcmp(rounds.data(), alone.data(), rounds.size() * sizeof(gpu::Float4)))
        << (what == Output::kNormals ? "normals" : "tangents");
  }
}

TEST(RuntimeAsset, RefusesBadRenderNormalsNamingThem) {
  const DeformAsset source = withSeams(testing::cylinderAsset());
  auto refused = [&](std::vector<gpu::Float4> normals) {
    RuntimeAssetOptions options;
    options.render_normals = std::move(normals);
    return RuntimeAsset::create(source, options).status();
  };
  const std::vector<gpu::Float4> normals = hardEdgeNormals(source);
  Status status = refused(std::vector<gpu::Float4>(normals.begin(), normals.begin() + 10));
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("render normals: 10 normals for " + std::to_string(normals.size()) + " render vertices"),
            std::string::npos)
      << status.message();
  std::vector<gpu::Float4> bad = normals;
  bad[3].z = INFINITY;
  EXPECT_NE(refused(bad).message().find("normal 3 is not finite"), std::string::npos);
  bad = normals;
  bad[8] = gpu::Float4{0.0f, 0.0f, 0.0f, 0.0f};
  EXPECT_NE(refused(bad).message().find("normal 8 is zero"), std::string::npos);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// RuntimeOptions::render_layout on the CPU runtime: a glTF-like asset's render vertices (split at
// seams, here a synthetic layout: runtime_fixtures.hpp's withSeams) get exactly the position and
// normal of their topology vertex, on both of the runtime's paths (an instance per thread, and one
// instance spread over the threads), with the same bounds; the reads take the render count.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "engine/runtime/instance_outputs.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin {
namespace {

using testing::makeAsset;
using testing::withSeams;

CpuRuntime makeRuntime(const RuntimeAsset& asset, std::uint32_t capacity, bool render_layout, bool normals = true) {
  RuntimeOptions options;
  options.capacity = capacity;
  options.render_layout = render_layout;
  options.normals = normals;
  Result<CpuRuntime> r = CpuRuntime::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}

TEST(RuntimeAsset, RenderVerticesOfAGltfLikeAsset) {
  const DeformAsset& source = testing::cylinderAsset();
  const RuntimeAsset plain = makeAsset(source);
  EXPECT_EQ(plain.renderVertexCount(), plain.vertexCount());
  EXPECT_TRUE(plain.renderTopology().empty());
  EXPECT_EQ(plain.renderTriangleIndices().size(), plain.triangleIndices().size());

  const DeformAsset seamed = withSeams(source);
  ASSERT_TRUE(validateDeformAsset(seamed).ok());
  const RuntimeAsset asset = makeAsset(seamed);
  EXPECT_EQ(asset.renderVertexCount(), asset.vertexCount() + 20);
  ASSERT_EQ(asset.renderTopology().size(), asset.renderVertexCount());
  ASSERT_EQ(asset.renderTriangleIndices().size(), asset.triangleIndices().size());
  // Each render triangle is its topology triangle, vertex for vertex.
  for (std::size_t i = 0; i < asset.triangleIndices().size(); ++i) {
    EXPECT_EQ(asset.renderTopology()[asset.renderTriangleIndices()[i]], asset.triangleIndices()[i]) << "corner " << i;
  }
}

// One draw per input primitive, so an engine binds each one's material over the one output buffer.
TEST(RuntimeAsset, DrawRangesFollowTheInputsPrimitives) {
  const RuntimeAsset plain = makeAsset(testing::cylinderAsset());
  ASSERT_EQ(plain.renderDrawRanges().size(), 1u);
  EXPECT_EQ(plain.renderDrawRanges()[0].first_index, 0u);
  EXPECT_EQ(plain.renderDrawRanges()[0].index_count, plain.renderTriangleIndices().size());
  EXPECT_EQ(plain.renderDrawRanges()[0].material, -1);

  DeformAsset source = withSeams(testing::cylinderAsset());
  const FaceList& faces = source.render.faces;
  const auto third = static_cast<std::uint32_t>(faces.faceCount() / 3);
  source.render.primitives = {{third, 2}, {third, 7}, {static_cast<std::uint32_t>(faces.faceCount()), -1}};
  ASSERT_TRUE(validateDeformAsset(source).ok());
  const RuntimeAsset asset = makeAsset(source);
  std::uint32_t first_run = 0;  // indices of the first third of the faces, counted corner by corner
  for (std::uint32_t f = 0; f < third; ++f) first_run += 3 * (faces.face_offsets[f + 1] - faces.face_offsets[f] - 2);
  const std::span<const RuntimeAsset::DrawRange> ranges = asset.renderDrawRanges();
  ASSERT_EQ(ranges.size(), 2u) << "the empty primitive has no draw";
  EXPECT_EQ(ranges[0].first_index, 0u);
  EXPECT_EQ(ranges[0].index_count, first_run);
  EXPECT_EQ(ranges[0].material, 2);
  EXPECT_EQ(ranges[1].first_index, first_run);
  EXPECT_EQ(ranges[1].index_count, asset.renderTriangleIndices().size() - first_run);
  EXPECT_EQ(ranges[1].material, -1);
}

// 1 instance (spread over the threads), 5 (four whole rounds of one per thread, then one spread).
TEST(CpuRuntime, RenderLayoutGathersEachRenderVertexFromItsTopologyVertex) {
  const tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
  const RuntimeAsset asset = makeAsset(withSeams(testing::catAsset()));
  const std::uint32_t v = asset.vertexCount();
  const std::uint32_t r = asset.renderVertexCount();
  const std::span<const std::uint32_t> topology = asset.renderTopology();
  for (const bool normals : {true, false}) {
    CpuRuntime welded = makeRuntime(asset, 5, false, normals);
    CpuRuntime rendered = makeRuntime(asset, 5, true, normals);
    EXPECT_EQ(welded.outputVertexCount(), v);
    EXPECT_EQ(rendered.outputVertexCount(), r);
    for (const std::uint32_t count : {1u, 5u}) {
      for (CpuRuntime* rt : {&welded, &rendered}) {
        ASSERT_TRUE(rt->setInstanceCount(count).ok());
        for (std::uint32_t k = 0; k < count; ++k) {
          ASSERT_TRUE(rt->setInstance(k, InstanceState::atTime(0.4 + 1.7 * k).withPreset(k % 3)).ok());
        }
      }
      Result<std::uint64_t> a = welded.submitFrame();
      Result<std::uint64_t> b = rendered.submitFrame();
      ASSERT_TRUE(a.ok() && b.ok());
      const std::span<const gpu::Float4> wp = *welded.positions(*a), rp = *rendered.positions(*b);
      ASSERT_EQ(wp.size(), std::size_t{count} * v);
      ASSERT_EQ(rp.size(), std::size_t{count} * r);
      const std::span<const gpu::Float4> wn = *welded.normals(*a), rn = *rendered.normals(*b);
      ASSERT_EQ(rn.empty(), !normals);
      for (std::uint32_t k = 0; k < count; ++k) {
        for (std::uint32_t i = 0; i < r; ++i) {
          const gpu::Float4& got = rp[std::size_t{k} * r + i];
          const gpu::Float4& want = wp[std::size_t{k} * v + topology[i]];
          ASSERT_TRUE(got.x == want.x && got.y == want.y && got.z == want.z && got.w == want.w)
              << count << " instances, instance " << k << ", render vertex " << i;
          if (!normals) continue;
          const gpu::Float4& got_n = rn[std::size_t{k} * r + i];
          const gpu::Float4& want_n = wn[std::size_t{k} * v + topology[i]];
          ASSERT_TRUE(got_n.x == want_n.x && got_n.y == want_n.y && got_n.z == want_n.z)
              << count << " instances, instance " << k << ", render vertex " << i << "'s normal";
        }
      }
      std::vector<InstanceBounds> lhs(count), rhs(count);
      ASSERT_TRUE(welded.readBounds(*a, lhs).ok() && rendered.readBounds(*b, rhs).ok());
      for (std::uint32_t k = 0; k < count; ++k) {
        EXPECT_EQ(lhs[k].min, rhs[k].min);
        EXPECT_EQ(lhs[k].max, rhs[k].max);
      }
      // readPositions takes the render count, and says so.
      std::vector<gpu::Float4> out(r);
      ASSERT_TRUE(rendered.readPositions(*b, count - 1, out).ok());
      EXPECT_EQ(out[0].x, rp[std::size_t{count - 1} * r].x);
      std::vector<gpu::Float4> wrong(v);
      const Status status = rendered.readPositions(*b, 0, wrong);
      EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
      EXPECT_NE(status.message().find("expected the asset's " + std::to_string(r) + " render vertices"), std::string::npos)
          << status.message();
    }
  }
}

// The runtime's render vertices are those `odeskin play` writes for glTF input (outputPositions on
// the double-precision reference), within float rounding.
TEST(CpuRuntime, RenderLayoutIsTheLayoutPlayWrites) {
  const RuntimeAsset asset = makeAsset(withSeams(testing::cylinderAsset()));
  CpuRuntime rt = makeRuntime(asset, 1, true);
  ASSERT_TRUE(rt.setInstanceCount(1).ok());
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atSegment(1, 0.3).withPreset(1)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const std::vector<Vec3> played =
      outputPositions(asset.source(), testing::referencePositions(asset, 1, 1, 0.3));
  const std::span<const gpu::Float4> got = *rt.positions(*frame);
  ASSERT_EQ(got.size(), played.size());
  const double box = longestBoxSide(asset.source().rest_positions);
  EXPECT_LT(testing::worstGap(played, got).gap / box, 1e-5);
}

// An asset without a render layout (OBJ input) outputs its topology vertices either way.
TEST(CpuRuntime, RenderLayoutOfAnObjAssetIsItsTopology) {
  const RuntimeAsset asset = makeAsset(testing::cylinderAsset());
  CpuRuntime welded = makeRuntime(asset, 2, false);
  CpuRuntime rendered = makeRuntime(asset, 2, true);
  EXPECT_FALSE(rendered.gathersRenderVertices());
  EXPECT_EQ(rendered.outputVertexCount(), asset.vertexCount());
  for (CpuRuntime* rt : {&welded, &rendered}) {
    ASSERT_TRUE(rt->setInstanceCount(2).ok());
    ASSERT_TRUE(rt->setInstance(1, InstanceState::atTime(1.25)).ok());
  }
  Result<std::uint64_t> a = welded.submitFrame();
  Result<std::uint64_t> b = rendered.submitFrame();
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(testing::worstGap(*welded.positions(*a), *rendered.positions(*b)).gap, 0.0);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// RuntimeOptions::tangents on the CPU runtime: the bind tangents (runtime_fixtures.hpp's
// bindTangents) carried through each frame equal, within float rounding, an independent
// double-precision least-squares fit of each one-ring's deformation (Eigen, from the frame's own
// positions); they turn with a rigid placement; both of the runtime's work paths give the same
// bits, which are the scalar formula's; and bad tangents and options are refused naming the problem.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "engine/runtime/cpu_runtime.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin {
namespace {

using testing::bindTangents;
using testing::makeAssetWithTangents;
using testing::Output;
using testing::readOutput;
using testing::withSeams;

CpuRuntime makeRuntime(const RuntimeAsset& asset, std::uint32_t capacity, bool render_layout) {
  RuntimeOptions options;
  options.capacity = capacity;
  options.render_layout = render_layout;
  options.tangents = true;
  Result<CpuRuntime> r = CpuRuntime::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}


Vec3 xyz(const gpu::Float4& f) { return {f.x, f.y, f.z}; }

// The expected tangent of output vertex o of topology vertex i, from the deformed `positions` and
// `normal` (the frame's, in double): the least-squares linear map of i's bind tangent plane that
// takes its corner edges to their deformed edges, applied to the bind tangent, made orthogonal to
// the normal and normalised.
Vec3 expectedTangent(const RuntimeAsset& asset, std::uint32_t i, const std::vector<Vec3>& positions, const Vec3& normal,
                     const gpu::Float4& bind) {
  const std::vector<Vec3>& rest = asset.source().rest_positions;
  const std::uint32_t first = asset.cornerOffsets()[i], end = asset.cornerOffsets()[i + 1];
  Vec3 n0(0.0);
  for (std::uint32_t k = first; k < end; ++k) {
    const gpu::Corner c = asset.corners()[k];
    n0 += glm::cross(rest[c.next] - rest[i], rest[c.prev] - rest[i]);
  }
  n0 = glm::normalize(n0);
  // Any orthonormal basis of the bind tangent plane gives the same map.
  const Vec3 u = glm::normalize(glm::cross(n0, std::fabs(n0.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0)));
  const Vec3 v = glm::cross(n0, u);
  const Eigen::Index edges = 2 * static_cast<Eigen::Index>(end - first);
  Eigen::MatrixXd plane(2, edges), deformed(3, edges);
  Eigen::Index j = 0;
  for (std::uint32_t k = first; k < end; ++k) {
    for (const std::uint32_t other : {asset.corners()[k].next, asset.corners()[k].prev}) {
      const Vec3 e = rest[other] - rest[i], d = positions[other] - positions[i];
      plane.col(j) << glm::dot(u, e), glm::dot(v, e);
      deformed.col(j) << d.x, d.y, d.z;
      ++j;
    }
  }
  const Eigen::Matrix2d gram = plane * plane.transpose();
  const Eigen::MatrixXd map = deformed * plane.transpose() * gram.inverse();  // 3 x 2
  const Vec3 t = xyz(bind);
  const Eigen::Vector3d carried = map * Eigen::Vector2d(glm::dot(u, t), glm::dot(v, t));
  Vec3 out(carried.x(), carried.y(), carried.z());
  out -= normal * glm::dot(normal, out);
  return glm::normalize(out);
}

// Three instances, each on its own bones, of the seamed cylinder (render layout) and of the plain
// cat (topology layout).
TEST(CpuRuntime, TangentsCarryTheBindTangentsThroughEachOneRingsDeformation) {
  for (const bool seamed : {true, false}) {
    const DeformAsset& source = seamed ? testing::cylinderAsset() : testing::catAsset();
    const RuntimeAsset asset = makeAssetWithTangents(seamed ? withSeams(source) : source);
    const std::vector<gpu::Float4> bind = bindTangents(asset.source());
    CpuRuntime rt = makeRuntime(asset, 3, seamed);
    ASSERT_TRUE(rt.setInstanceCount(3).ok());
    for (std::uint32_t k = 0; k < 3; ++k) ASSERT_TRUE(rt.setInstance(k, InstanceState::atTime(0.8 * k + 0.3)).ok());
    Result<std::uint64_t> frame = rt.submitFrame();
    ASSERT_TRUE(frame.ok());
    const std::uint32_t v = asset.vertexCount();
    const std::span<const std::uint32_t> topology = asset.renderTopology();
    double worst = 0.0;
    for (std::uint32_t k = 0; k < 3; ++k) {
      const auto positions = readOutput(rt, *frame, k, Output::kPositions);
      const auto normals = readOutput(rt, *frame, k, Output::kNormals);
      const auto tangents = readOutput(rt, *frame, k, Output::kTangents);
      // Every topology vertex has an output vertex (withSeams' first V are a permutation).
      std::vector<Vec3> topology_positions(v), topology_normals(v);
      for (std::size_t o = 0; o < positions.size(); ++o) {
        const std::uint32_t i = topology.empty() ? static_cast<std::uint32_t>(o) : topology[o];
        topology_positions[i] = xyz(positions[o]);
        topology_normals[i] = xyz(normals[o]);
      }
      for (std::size_t o = 0; o < tangents.size(); ++o) {
        const std::uint32_t i = topology.empty() ? static_cast<std::uint32_t>(o) : topology[o];
        const Vec3 expected = expectedTangent(asset, i, topology_positions, topology_normals[i], bind[o]);
        const double gap = glm::length(xyz(tangents[o]) - expected);
        worst = std::max(worst, gap);
        ASSERT_LT(gap, 1e-4) << (seamed ? "cylinder" : "cat") << " instance " << k << " output vertex " << o;
        ASSERT_EQ(tangents[o].w, bind[o].w) << "output vertex " << o;
        ASSERT_LT(std::fabs(glm::dot(xyz(tangents[o]), xyz(normals[o]))), 1e-5) << "output vertex " << o;
      }
    }
    std::printf("%s: max |tangent - least-squares reference| = %.2e\n", seamed ? "seamed cylinder" : "cat", worst);
  }
}

// The engine's world placement (a rotation and a translation after the bones) turns every
// tangent by the same rotation.
TEST(CpuRuntime, TangentsTurnWithARigidPlacement) {
  const RuntimeAsset asset = makeAssetWithTangents(withSeams(testing::cylinderAsset()));
  CpuRuntime rt = makeRuntime(asset, 2, true);
  ASSERT_TRUE(rt.setInstanceCount(2).ok());
  std::vector<gpu::BoneMatrix> bones(asset.boneCount());
  asset.bonesAt(1, 0.4, bones);
  const double angle = 0.9;
  const std::vector<gpu::BoneMatrix> moved = testing::placed(bones, angle, Vec3(3.0, -1.0, 2.0));
  ASSERT_TRUE(rt.setInstance(0, InstanceState::atSegment(1, 0.4).withBones(bones)).ok());
  ASSERT_TRUE(rt.setInstance(1, InstanceState::atSegment(1, 0.4).withBones(moved)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const auto still = readOutput(rt, *frame, 0, Output::kTangents), turned = readOutput(rt, *frame, 1, Output::kTangents);
  const glm::dmat3 rotation(std::cos(angle), 0.0, -std::sin(angle), 0.0, 1.0, 0.0, std::sin(angle), 0.0, std::cos(angle));
  double worst = 0.0;
  for (std::size_t o = 0; o < still.size(); ++o) {
    const double gap = glm::length(xyz(turned[o]) - rotation * xyz(still[o]));
    worst = std::max(worst, gap);
    ASSERT_LT(gap, 1e-4) << "output vertex " << o;
    ASSERT_EQ(turned[o].w, still[o].w);
  }
  std::printf("max |placed tangent - R tangent| = %.2e\n", worst);
}

// 1 instance (spread over the threads) and 5 (whole rounds of one per thread, then one spread):
// the same instance gives the same bits either way.
TEST(CpuRuntime, TangentsAreTheSameOnBothWorkPaths) {
  const tbb::global_control four(tbb::global_control::max_allowed_parallelism, 4);
  const RuntimeAsset asset = makeAssetWithTangents(withSeams(testing::catAsset()));
  CpuRuntime one = makeRuntime(asset, 1, true);
  CpuRuntime five = makeRuntime(asset, 5, true);
  ASSERT_TRUE(one.setInstanceCount(1).ok() && five.setInstanceCount(5).ok());
  const InstanceState state = InstanceState::atTime(2.6).withPreset(2);
  ASSERT_TRUE(one.setInstance(0, state).ok());
  for (std::uint32_t k = 0; k < 5; ++k) ASSERT_TRUE(five.setInstance(k, state).ok());
  Result<std::uint64_t> a = one.submitFrame();
  Result<std::uint64_t> b = five.submitFrame();
  ASSERT_TRUE(a.ok() && b.ok());
  const auto spread = readOutput(one, *a, 0, Output::kTangents);
  for (std::uint32_t k = 0; k < 5; ++k) {
    const auto rounds = readOutput(five, *b, k, Output::kTangents);
    ASSERT_EQ(0, std::memcmp(spread.data(), rounds.data(), spread.size() * sizeof(gpu::Float4))) << "instance " << k;
  }
  Result<std::span<const gpu::Float4>> view = five.tangents(*b);
  ASSERT_TRUE(view.ok());
  EXPECT_EQ(view->size(), 5u * asset.renderVertexCount());
}

// computeVertexTangents (one register per vertex on x86-64) against the scalar glm form it stands
// for, bit for bit, on a frame of the cat with a few zero bind tangents.
TEST(ComputeVertexTangents, IsTheScalarFormToTheBit) {
  const DeformAsset& source = testing::catAsset();
  RuntimeAssetOptions options;
  options.render_tangents = bindTangents(source);
  for (std::size_t o = 0; o < options.render_tangents.size(); o += 97) options.render_tangents[o] = {0.0f, 0.0f, 0.0f, -1.0f};
  Result<RuntimeAsset> asset = RuntimeAsset::create(source, options);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  CpuRuntime rt = makeRuntime(*asset, 1, false);
  ASSERT_TRUE(rt.setInstanceCount(1).ok() && rt.setInstance(0, InstanceState::atTime(4.4)).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const auto positions = readOutput(rt, *frame, 0, Output::kPositions);
  const auto normals = readOutput(rt, *frame, 0, Output::kNormals);
  const auto tangents = readOutput(rt, *frame, 0, Output::kTangents);
  const TangentTables tables = asset->tangentTables();
  auto vec = [](const gpu::Float4& f) { return glm::vec3(f.x, f.y, f.z); };
  for (std::size_t i = 0; i < tangents.size(); ++i) {
    const glm::vec3 p = vec(positions[i]);
    glm::vec3 t(0.0f);
    const std::uint32_t first = tables.corner_offsets[i];
    for (std::uint32_t k = first; k < tables.corner_offsets[i + 1]; ++k) {
      const gpu::Corner c = tables.corners[k];
      const gpu::TangentWeights w = tables.weights[tables.frames[i].weights + (k - first)];
      t += w.next * (vec(positions[c.next]) - p) + w.prev * (vec(positions[c.prev]) - p);
    }
    const glm::vec3 n = vec(normals[i]);
    t -= n * glm::dot(n, t);
    const float length = glm::length(t);
    t = length > 0.0f ? t / length : glm::vec3(0.0f);
    const gpu::Float4 expected{t.x, t.y, t.z, tables.frames[i].handedness};
    ASSERT_EQ(testing::bitsOf(expected), testing::bitsOf(tangents[i])) << "vertex " << i;
  }
  EXPECT_EQ(vec(tangents[97]), glm::vec3(0.0f));
  EXPECT_EQ(tangents[97].w, -1.0f);
}

TEST(RuntimeAsset, RefusesBadRenderTangentsNamingThem) {
  const DeformAsset source = withSeams(testing::cylinderAsset());
  auto refused = [&](std::vector<gpu::Float4> tangents) {
    RuntimeAssetOptions options;
    options.render_tangents = std::move(tangents);
    return RuntimeAsset::create(source, options).status();
  };
  std::vector<gpu::Float4> tangents = bindTangents(source);
  Status status = refused(std::vector<gpu::Float4>(tangents.begin(), tangents.end() - 1));
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find(std::to_string(tangents.size() - 1) + " tangents for " +
                                  std::to_string(tangents.size()) + " render vertices"),
            std::string::npos)
      << status.message();
  std::vector<gpu::Float4> bad = tangents;
  bad[7].y = NAN;
  status = refused(bad);
  EXPECT_NE(status.message().find("render tangents: tangent 7 is not finite"), std::string::npos) << status.message();
  bad = tangents;
  bad[9].w = 0.0f;
  status = refused(bad);
  EXPECT_NE(status.message().find("tangent 9 has w = 0"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("+1 or -1"), std::string::npos) << status.message();
  // A zero tangent is allowed (a glTF's degenerate UVs give them) and stays zero; only a
  // tangent's direction counts, however long or short it is given.
  bad = tangents;
  bad[4] = gpu::Float4{0.0f, 0.0f, 0.0f, 1.0f};
  const std::size_t huge = 5, tiny = 6;
  for (const std::size_t o : {huge, tiny}) {
    const float scale = o == huge ? 1e30f : 1e-30f;
    bad[o] = gpu::Float4{tangents[o].x * scale, tangents[o].y * scale, tangents[o].z * scale, tangents[o].w};
  }
  RuntimeAssetOptions options;
  options.render_tangents = bad;
  Result<RuntimeAsset> asset = RuntimeAsset::create(source, options);
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  CpuRuntime rt = makeRuntime(*asset, 1, true);
  ASSERT_TRUE(rt.setInstanceCount(1).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  ASSERT_TRUE(frame.ok());
  const auto out = readOutput(rt, *frame, 0, Output::kTangents);
  EXPECT_EQ(xyz(out[4]), Vec3(0.0));
  EXPECT_EQ(out[4].w, 1.0f);
  options.render_tangents = tangents;
  Result<RuntimeAsset> unit = RuntimeAsset::create(source, options);
  ASSERT_TRUE(unit.ok());
  CpuRuntime unit_rt = makeRuntime(*unit, 1, true);
  ASSERT_TRUE(unit_rt.setInstanceCount(1).ok());
  Result<std::uint64_t> unit_frame = unit_rt.submitFrame();
  ASSERT_TRUE(unit_frame.ok());
  const auto expected = readOutput(unit_rt, *unit_frame, 0, Output::kTangents);
  for (const std::size_t o : {huge, tiny}) {
    EXPECT_LT(glm::length(xyz(out[o]) - xyz(expected[o])), 1e-6) << "tangent " << o;
    EXPECT_NEAR(glm::length(xyz(out[o])), 1.0, 1e-6) << "tangent " << o;
  }
}

TEST(CpuRuntime, TangentOptionsAreChecked) {
  const RuntimeAsset plain = testing::makeAsset(testing::cylinderAsset());
  const RuntimeAsset seamed = makeAssetWithTangents(withSeams(testing::cylinderAsset()));
  auto created = [](const RuntimeAsset& asset, bool normals, bool render_layout) {
    RuntimeOptions options;
    options.tangents = true;
    options.normals = normals;
    options.render_layout = render_layout;
    return CpuRuntime::create(asset, options).status();
  };
  Status status = created(plain, true, false);
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("the asset has none"), std::string::npos) << status.message();
  status = created(seamed, false, true);
  EXPECT_NE(status.message().find("tangents need normals"), std::string::npos) << status.message();
  status = created(seamed, true, false);
  EXPECT_NE(status.message().find("RuntimeOptions::render_layout"), std::string::npos) << status.message();

  Result<CpuRuntime> off = CpuRuntime::create(seamed, RuntimeOptions{});
  ASSERT_TRUE(off.ok());
  ASSERT_TRUE(off->setInstanceCount(1).ok());
  Result<std::uint64_t> frame = off->submitFrame();
  ASSERT_TRUE(frame.ok());
  std::vector<gpu::Float4> out(off->outputVertexCount());
  EXPECT_NE(off->readTangents(*frame, 0, out).message().find("tangents off"), std::string::npos);
  EXPECT_TRUE(off->tangents(*frame)->empty());
}

}  // namespace
}  // namespace odeskin

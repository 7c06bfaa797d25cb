// SPDX-License-Identifier: MIT
// Bones handed over by an engine (engine_bones.hpp): column-major matrices as the runtime's rows,
// joints remapped by name, and an engine's frame through those helpers against the runtime's own
// interpolated bones. Also measures the three mistakes docs/runtime.md warns of ("Bones from the
// engine"): joints left in the engine's order, matrices read as rows, inverse bind matrices left out.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include "engine/kernels/packed_deform.hpp"
#include "engine/runtime/cpu_runtime.hpp"
#include "engine/runtime/engine_bones.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin {
namespace {

using testing::makeAsset;
using testing::worstGap;

// What an engine holds for a bone: the same matrix as a column-major glm::mat4 (every float kept).
glm::mat4 asMat4(const gpu::BoneMatrix& b) { return glm::mat4(glm::dmat4(fromGpuBone(b))); }

// The cylinder with named bones, so that an engine can find them.
DeformAsset namedCylinder() {
  DeformAsset a = testing::cylinderAsset();
  a.bone_names.clear();
  for (std::uint32_t b = 0; b < a.bone_count; ++b) a.bone_names.push_back("bone_" + std::to_string(b));
  return a;
}

std::vector<gpu::Float4> frameOf(CpuRuntime& rt, const InstanceState& state) {
  EXPECT_TRUE(rt.setInstanceCount(1).ok());
  EXPECT_TRUE(rt.setInstance(0, state).ok());
  Result<std::uint64_t> frame = rt.submitFrame();
  EXPECT_TRUE(frame.ok()) << frame.status().toString();
  std::vector<gpu::Float4> out(rt.asset().vertexCount());
  EXPECT_TRUE(rt.readPositions(*frame, 0, out).ok());
  return out;
}

TEST(EngineBones, ColumnMajorMatricesBecomeTheRuntimesRows) {
  glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, -2.0f, 3.25f));
  m = glm::rotate(m, 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f)));
  m = glm::scale(m, glm::vec3(1.5f, 0.75f, 2.0f));
  const gpu::BoneMatrix b = boneMatrixFromMat4(m);
  const gpu::BoneMatrix c = boneMatrixFromColumnMajor(std::span<const float, 16>(glm::value_ptr(m), 16));
  const gpu::Float4 b_rows[3] = {b.row0, b.row1, b.row2};
  const gpu::Float4 c_rows[3] = {c.row0, c.row1, c.row2};
  for (int r = 0; r < 3; ++r) {
    EXPECT_EQ(b_rows[r].x, c_rows[r].x);
    EXPECT_EQ(b_rows[r].y, c_rows[r].y);
    EXPECT_EQ(b_rows[r].z, c_rows[r].z);
    EXPECT_EQ(b_rows[r].w, c_rows[r].w);
  }
  const glm::vec3 p(0.3f, -1.2f, 2.5f);
  const glm::vec4 expected = m * glm::vec4(p, 1.0f);
  const gpu::Float4 rows[3] = {b.row0, b.row1, b.row2};
  for (int r = 0; r < 3; ++r) {
    const float got = rows[r].x * p.x + rows[r].y * p.y + rows[r].z * p.z + rows[r].w;
    EXPECT_NEAR(got, expected[r], 1e-5f) << "row " << r;
  }
}

TEST(EngineBones, JointsAreFoundByName) {
  const RuntimeAsset asset = makeAsset(namedCylinder());
  const std::uint32_t bones = asset.boneCount();
  ASSERT_GE(bones, 2u);
  // The engine's skeleton: an extra joint first, then the asset's bones in reverse.
  std::vector<std::string> joints = {"root_motion"};
  for (std::uint32_t b = bones; b-- > 0;) joints.push_back("bone_" + std::to_string(b));
  Result<std::vector<std::uint32_t>> map = engineJointOfEachBone(asset, joints);
  ASSERT_TRUE(map.ok()) << map.status().toString();
  for (std::uint32_t b = 0; b < bones; ++b) EXPECT_EQ((*map)[b], bones - b) << "bone " << b;

  std::vector<std::string> missing(joints.begin(), joints.end() - 1);
  Result<std::vector<std::uint32_t>> none = engineJointOfEachBone(asset, missing);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(none.status().message().find("no engine joint is named 'bone_0'"), std::string::npos) << none.status().message();

  std::vector<std::string> twice = joints;
  twice.push_back("bone_1");
  Result<std::vector<std::uint32_t>> repeated = engineJointOfEachBone(asset, twice);
  ASSERT_FALSE(repeated.ok());
  EXPECT_NE(repeated.status().message().find("both named 'bone_1'"), std::string::npos) << repeated.status().message();

  DeformAsset same_names = namedCylinder();
  same_names.bone_names[1] = same_names.bone_names[0];
  Result<std::vector<std::uint32_t>> ambiguous = engineJointOfEachBone(makeAsset(same_names), joints);
  ASSERT_FALSE(ambiguous.ok());
  EXPECT_NE(ambiguous.status().message().find("bones 0 and 1 are both named 'bone_0'"), std::string::npos)
      << ambiguous.status().message();

  DeformAsset unnamed = namedCylinder();
  unnamed.bone_names.clear();
  Result<std::vector<std::uint32_t>> numbered = engineJointOfEachBone(makeAsset(unnamed), joints);
  ASSERT_FALSE(numbered.ok());
  EXPECT_NE(numbered.status().message().find("have no names"), std::string::npos) << numbered.status().message();

  std::vector<gpu::BoneMatrix> engine(joints.size()), out(bones);
  EXPECT_TRUE(gatherBones(*map, engine, out).ok());
  std::vector<gpu::BoneMatrix> short_out(bones - 1);
  EXPECT_EQ(gatherBones(*map, engine, short_out).code(), StatusCode::kInvalidArgument);
  const std::vector<gpu::BoneMatrix> too_few(1);
  EXPECT_EQ(gatherBones(*map, too_few, out).code(), StatusCode::kInvalidArgument);
  // In place, the reordering read joints it had already overwritten, and returned ok.
  const Status in_place = gatherBones(*map, engine, std::span(engine).first(bones));
  EXPECT_EQ(in_place.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(in_place.message().find("overlap"), std::string::npos) << in_place.message();
}

// An engine's frame: its joints in its own order, as column-major matrices, remapped and converted
// by the helpers, deforms exactly as the runtime's own bones at the same time. Each of the three
// mistakes moves the mesh far from that (measured, and printed for docs/runtime.md).
TEST(EngineBones, AnEnginesFrameThroughTheHelpersMatchesTheAssetsBones) {
  const RuntimeAsset asset = makeAsset(namedCylinder());
  const std::uint32_t bones = asset.boneCount();
  Result<CpuRuntime> rt = CpuRuntime::create(asset, RuntimeOptions{});
  ASSERT_TRUE(rt.ok());
  const double t = 0.6;
  const auto [segment, tau] = asset.locate(t);
  std::vector<gpu::BoneMatrix> truth(bones);
  asset.bonesAt(segment, tau, truth);
  const std::vector<gpu::Float4> expected = frameOf(*rt, InstanceState::atTime(t));

  // The engine: joints in reverse order, each as a glm::mat4.
  std::vector<std::string> joint_names;
  std::vector<glm::mat4> joint_matrices;
  for (std::uint32_t b = bones; b-- > 0;) {
    joint_names.push_back("bone_" + std::to_string(b));
    joint_matrices.push_back(asMat4(truth[b]));
  }
  Result<std::vector<std::uint32_t>> map = engineJointOfEachBone(asset, joint_names);
  ASSERT_TRUE(map.ok());
  std::vector<gpu::BoneMatrix> joints(joint_matrices.size()), ordered(bones);
  for (std::size_t j = 0; j < joints.size(); ++j) joints[j] = boneMatrixFromMat4(joint_matrices[j]);
  ASSERT_TRUE(gatherBones(*map, joints, ordered).ok());
  const std::vector<gpu::Float4> engine = frameOf(*rt, InstanceState::atTime(t).withBones(ordered));
  EXPECT_EQ(worstGap(expected, engine).gap, 0.0);

  const double box = longestBoxSide(asset.source().rest_positions);
  // 1. The joints in the engine's order.
  const double order = worstGap(expected, frameOf(*rt, InstanceState::atTime(t).withBones(joints))).gap / box;
  // 2. The column-major floats copied as if they were rows.
  std::vector<gpu::BoneMatrix> as_rows(bones);
  for (std::uint32_t b = 0; b < bones; ++b) std::memcpy(&as_rows[b], glm::value_ptr(asMat4(truth[b])), sizeof(gpu::BoneMatrix));
  const double layout = worstGap(expected, frameOf(*rt, InstanceState::atTime(t).withBones(as_rows))).gap / box;
  // 3. Global joint transforms without the inverse bind matrix: for a skeleton whose joints sit at
  // their pivots unrotated, the inverse bind matrix is a translation by -pivot.
  std::vector<gpu::BoneMatrix> global(bones);
  for (std::uint32_t b = 0; b < bones; ++b) {
    const glm::vec3 pivot(asset.source().bone_pivots[b]);
    global[b] = boneMatrixFromMat4(glm::translate(asMat4(truth[b]), pivot));
  }
  const double no_inverse_bind = worstGap(expected, frameOf(*rt, InstanceState::atTime(t).withBones(global))).gap / box;
  std::printf("worst vertex error of the box: joints in the engine's order %.3f, column-major read as rows %.3f, "
              "no inverse bind matrices %.3f\n",
              order, layout, no_inverse_bind);
  EXPECT_GT(order, 0.01);
  EXPECT_GT(layout, 0.01);
  EXPECT_GT(no_inverse_bind, 0.01);
}

}  // namespace
}  // namespace odeskin

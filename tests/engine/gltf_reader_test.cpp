// SPDX-License-Identifier: MIT
// The glTF reader against the tube model (gltf_tube_model.hpp) in every layout it can take: the
// seam welded and the render layout kept, normals, texture coordinates, the skin's skeleton and
// weights, animated and morphed poses, quantized and transformed meshes.
#include "engine/io/gltf_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/float_rounding.hpp"  // tests/engine
#include "engine/gltf_tube_model.hpp"  // tests/engine
#include <tiny_gltf.h>

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using namespace testing;  // odeskin::testing: the tube model

class GltfFormats : public ::testing::TestWithParam<bool> {};  // parameter: write GLB

TEST_P(GltfFormats, SeamIsWeldedAndRenderLayoutKept) {
  const Tube tube = makeTube();
  const auto examples = read(write(tube.model, GetParam() ? "tube.glb" : "tube.gltf", GetParam()), {0.5});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.render.topology_of_render.size(), 15u);
  ASSERT_EQ(e.rest_positions.size(), 12u);  // 3 rings x 4 corners; the seam column is welded
  for (std::uint32_t r = 0; r < 15; ++r) {
    const std::uint32_t t = e.render.topology_of_render[r];
    EXPECT_EQ(e.rest_positions[t], tube.render_positions[r]) << "render vertex " << r;
    if (r % kColumns == 4) {
      EXPECT_EQ(t, e.render.topology_of_render[r - 4]) << "seam vertex " << r;
    }
  }
  ASSERT_EQ(e.faces.faceCount(), 16u);
  ASSERT_EQ(e.render.faces.faceCount(), 16u);
  for (std::size_t k = 0; k < e.faces.indices.size(); ++k) {
    EXPECT_EQ(e.faces.indices[k], e.render.topology_of_render[e.render.faces.indices[k]]);
  }
  EXPECT_EQ(e.pose_labels, (std::vector<std::string>{std::string(GetParam() ? "tube.glb" : "tube.gltf") + " bind",
                                                     std::string(GetParam() ? "tube.glb" : "tube.gltf") + " bend at 0.5 s"}));
}

TEST_P(GltfFormats, TwoPrimitivesIndexedAndNotWeldIntoOneTopology) {
  TubeOptions o;
  o.two_primitives = true;
  const Tube tube = makeTube(o);
  const auto examples = read(write(tube.model, GetParam() ? "two.glb" : "two.gltf", GetParam()), {1.0}, {0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.render.topology_of_render.size(), 10u + 24u);
  ASSERT_EQ(e.rest_positions.size(), 12u);
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    EXPECT_EQ(e.rest_positions[e.render.topology_of_render[r]], tube.render_positions[r]) << "render vertex " << r;
  }
  EXPECT_EQ(e.faces.faceCount(), 16u);
  EXPECT_EQ(e.render.faces.faceCount(), 16u);
  // The morph target: zeros in primitive 0 (no bufferView), sparse in primitive 1.
  ASSERT_EQ(e.poses.size(), 3u);
  for (std::size_t v = 0; v < 12; ++v) {
    expectNear(e.poses[2][v], e.rest_positions[v] + deltaOf(ringOf(e.rest_positions[v]), o), 1e-12, "target pose");
  }
}

INSTANTIATE_TEST_SUITE_P(GltfAndGlb, GltfFormats, ::testing::Bool());

TEST(GltfReader, TriangleCollapsedByWeldingStaysOnlyInRenderFaces) {
  TubeOptions o;
  o.tweak = [](Prim& p) { p.indices.insert(p.indices.end(), {0, 4, 5}); };  // 0 and 4 are the seam pair
  const auto examples = read(write(makeTube(o).model, "sliver.gltf", false), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_EQ(examples->render.faces.faceCount(), 17u);
  EXPECT_EQ(examples->faces.faceCount(), 16u);
}


TEST(GltfReader, NormalsAreKeptPerRenderVertex) {
  TubeOptions o;
  o.normal = [](int, int column) { return cornerNormal(column, true); };
  auto examples = read(write(makeTube(o).model, "normals.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.normals.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) {
    EXPECT_EQ(examples->render.normals[r], roundedToFloat(cornerNormal(static_cast<int>(r % kColumns), true)))
        << "render vertex " << r;
  }
  EXPECT_TRUE(examples->warnings.empty());

  // KHR_mesh_quantization's normalized bytes decode to within 1/127.
  o.normal_type = kByteType;
  o.position_type = kFloatType;
  tinygltf::Model quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "normals-q.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.normals.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) {
    EXPECT_LT(glm::length(examples->render.normals[r] - cornerNormal(static_cast<int>(r % kColumns), true)), 1.0 / 127.0);
  }

  // A zero normal drops them all, with a warning naming the file and the vertex.
  o.normal_type = kFloatType;
  o.normal = [](int ring, int column) { return ring == 1 && column == 2 ? Vec3(0.0) : cornerNormal(column, true); };
  examples = read(write(makeTube(o).model, "zero-normal.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.normals.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("zero-normal.glb: NORMAL of vertex 7 is zero or not finite"), std::string::npos)
      << examples->warnings[0];
}

// TEXCOORD_0 per render vertex: float as stored, normalized integers decoded; what cannot be kept
// (unnormalized quantized integers, a primitive without it) is dropped with a warning.
TEST(GltfReader, TexcoordsAreKeptPerRenderVertex) {
  auto expected = [](std::size_t r) {
    const std::size_t ring = r / kColumns;  // the tube's vertices go ring by ring
    return Vec2(static_cast<double>(r % kColumns) / 4.0, static_cast<double>(ring) / 2.0);
  };
  TubeOptions o;
  auto examples = read(write(makeTube(o).model, "uv.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_EQ(examples->render.uvs[r], expected(r)) << "render vertex " << r;  // exact in float32
  EXPECT_TRUE(examples->warnings.empty());

  o.uv_type = kUShortType;  // core glTF: normalized unsigned short
  o.uv_normalized = true;
  o.uv_scale = 65535.0;
  examples = read(write(makeTube(o).model, "uv-ushort.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_LT(glm::length(examples->render.uvs[r] - expected(r)), 1.0 / 65535.0);

  o.uv_type = kShortType;  // KHR_mesh_quantization: normalized short, then unnormalized
  o.uv_scale = 32767.0;
  tinygltf::Model quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "uv-short.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_LT(glm::length(examples->render.uvs[r] - expected(r)), 1.0 / 32767.0);
  o.uv_normalized = false;
  quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "uv-raw.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.uvs.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("uv-raw.glb: TEXCOORD_0 is not kept: primitive 0 stores TEXCOORD_0 as unnormalized "
                                       "integers"),
            std::string::npos)
      << examples->warnings[0];

  o = TubeOptions{};
  o.two_primitives = true;
  o.uv_in_first_primitive_only = true;
  examples = read(write(makeTube(o).model, "uv-partial.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.uvs.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("TEXCOORD_0 is not kept: some primitives have no TEXCOORD_0"), std::string::npos)
      << examples->warnings[0];

  // A NaN is refused like in any accessor, naming it.
  o = TubeOptions{};
  o.uv = [](int ring, int column) { return ring == 2 && column == 1 ? Vec2(std::nan(""), 0.0) : Vec2(0.5); };
  examples = read(write(makeTube(o).model, "uv-nan.glb", true), {1.0});
  ASSERT_FALSE(examples.ok());
  EXPECT_NE(examples.status().message().find("uv-nan.glb: accessor 1 (mesh 0 primitive 0 TEXCOORD_0): element 11 is not a "
                                             "finite number"),
            std::string::npos)
      << examples.status().message();
}

TEST(GltfReader, SkeletonFromSkin) {
  const auto examples = read(write(makeTube().model, "tube.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_TRUE(examples->rig.has_value());
  const Skeleton& s = examples->rig->skeleton;
  EXPECT_EQ(s.names, (std::vector<std::string>{"root", "tip"}));
  EXPECT_EQ(s.parents, (std::vector<std::int32_t>{-1, 0}));
  ASSERT_EQ(s.heads.size(), 2u);
  EXPECT_EQ(s.heads[0], Vec3(0.0));
  EXPECT_EQ(s.heads[1], kTipJoint);
  EXPECT_EQ(s.tails[0], kTipJoint);  // the first child joint's head
  EXPECT_EQ(s.tails[1], kTipJoint);  // no child: its own head
}

struct WeightCase {
  int joint_type;
  int weight_type;
  std::array<double, 2> ring1;
  bool two_sets;
};

void PrintTo(const WeightCase& c, std::ostream* os) {
  *os << "joints " << c.joint_type << " weights " << c.weight_type << " ring 1 (" << c.ring1[0] << ", " << c.ring1[1]
      << ")" << (c.two_sets ? " in two sets" : "");
}

class GltfWeights : public ::testing::TestWithParam<WeightCase> {};

TEST_P(GltfWeights, NormalisedPerVertexForEveryComponentType) {
  TubeOptions o;
  o.joint_type = GetParam().joint_type;
  o.weight_type = GetParam().weight_type;
  o.ring1_weights = GetParam().ring1;
  o.two_sets = GetParam().two_sets;
  const auto examples = read(write(makeTube(o).model, "weights.gltf", false), {0.5});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  const Influences& in = e.rig->influences;
  ASSERT_EQ(in.vertexCount(), 12u);
  for (std::size_t v = 0; v < 12; ++v) {
    const int ring = ringOf(e.rest_positions[v]);
    std::map<std::uint32_t, double> w;
    double sum = 0.0;
    for (std::uint32_t k = in.offsets[v]; k < in.offsets[v + 1]; ++k) {
      w[in.bones[k]] += in.weights[k];
      sum += in.weights[k];
      EXPECT_GT(in.weights[k], 0.0) << "zero weights are dropped";
    }
    EXPECT_NEAR(sum, 1.0, 1e-15) << "vertex " << v;
    EXPECT_NEAR(w[1], tipWeight(ring, o), 1e-12) << "vertex " << v;
    EXPECT_EQ(in.offsets[v + 1] - in.offsets[v], ring == 1 ? 2u : 1u) << "vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(
    ComponentTypes, GltfWeights,
    ::testing::Values(WeightCase{kUByteType, kFloatType, {1.0, 3.0}, false},        // sums to 4: normalised
                      WeightCase{kUShortType, kFloatType, {0.25, 0.75}, false},
                      WeightCase{kUByteType, kUByteType, {64.0, 191.0}, false},     // 64/255, 191/255
                      WeightCase{kUShortType, kUByteType, {100.0, 100.0}, false},   // sums to 200/255
                      WeightCase{kUByteType, kUShortType, {16384.0, 49151.0}, false},
                      WeightCase{kUShortType, kUShortType, {1000.0, 3000.0}, true}, // JOINTS_1/WEIGHTS_1
                      WeightCase{kUByteType, kFloatType, {0.5, 0.5}, true}));

struct PoseCase {
  std::string interpolation;
  bool binary;
};

void PrintTo(const PoseCase& c, std::ostream* os) { *os << c.interpolation << (c.binary ? " glb" : " gltf"); }

class GltfPoses : public ::testing::TestWithParam<PoseCase> {};

TEST_P(GltfPoses, EqualIndependentLinearBlendSkinning) {
  TubeOptions o;
  o.interpolation = GetParam().interpolation;
  const std::vector<double> times{-0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0};
  const auto examples = read(write(makeTube(o).model, GetParam().binary ? "bend.glb" : "bend.gltf", GetParam().binary), times);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.poses.size(), times.size() + 1);
  ASSERT_EQ(e.rig->key_poses.size(), times.size() + 1);
  for (std::size_t v = 0; v < 12; ++v) EXPECT_EQ(e.poses[0][v], e.rest_positions[v]);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const PoseParams p{0.5 * std::clamp(t, 0.0, 1.0), bendAngle(o.interpolation, t), 0.0};
    const std::vector<Vec3>& pose = e.poses[k + 1];
    for (std::size_t v = 0; v < 12; ++v) {
      const Vec3& x = e.rest_positions[v];
      expectNear(pose[v], expectedVertex(x, tipWeight(ringOf(x), o), Vec3(0.0), p), 1e-9,
                 "t " + std::to_string(t) + " vertex " + std::to_string(v));
    }
    // Key poses are the joints' skin matrices (rigid here).
    const std::vector<RigidTransform>& key = e.rig->key_poses[k + 1];
    for (const Vec3& x : {Vec3(0.0), Vec3(1.0, 2.0, 3.0), Vec3(-1.0, 0.5, 0.0)}) {
      expectNear(key[0].apply(x), x + Vec3(p.root_dx, 0.0, 0.0), 1e-9, "root key pose");
      expectNear(key[1].apply(x), tipSkin(x, p), 1e-9, "tip key pose");
    }
  }
  // A quarter turn at the end (float data aside), and none at the start.
  EXPECT_NEAR(bendAngle(o.interpolation, 2.0), std::numbers::pi / 2, 1e-7);
  for (const RigidTransform& identity : e.rig->key_poses[0]) {
    EXPECT_EQ(identity.rotation, glm::dquat(1.0, 0.0, 0.0, 0.0));
    EXPECT_EQ(identity.translation, Vec3(0.0));
  }
}

INSTANTIATE_TEST_SUITE_P(Interpolations, GltfPoses,
                         ::testing::Values(PoseCase{"LINEAR", false}, PoseCase{"LINEAR", true}, PoseCase{"STEP", false},
                                           PoseCase{"CUBICSPLINE", false}, PoseCase{"CUBICSPLINE", true}),
                         [](const auto& case_info) { return case_info.param.interpolation + (case_info.param.binary ? "_glb" : "_gltf"); });

TEST(GltfReader, AnimatedMorphWeightsApplyBeforeSkinning) {
  const TubeOptions o;
  const auto examples = read(write(makeTube(o).model, "wiggle.gltf", false), {1.0, 2.0}, {}, "wiggle");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  for (std::size_t k = 0; k < 2; ++k) {
    const double t = k == 0 ? 1.0 : 2.0;
    const PoseParams p{0.0, bendAngle("LINEAR", t), t / 2.0};
    for (std::size_t v = 0; v < 12; ++v) {
      const Vec3& x = e.rest_positions[v];
      expectNear(e.poses[k + 1][v], expectedVertex(x, tipWeight(ringOf(x), o), deltaOf(ringOf(x), o), p), 1e-9,
                 "wiggle t " + std::to_string(t) + " vertex " + std::to_string(v));
    }
  }
  EXPECT_EQ(e.pose_labels[1], "wiggle.gltf wiggle at 1 s");
}

TEST(GltfReader, AnimationByIndex) {
  const auto examples = read(write(makeTube().model, "tube.gltf", false), {2.0}, {}, "1");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_EQ(examples->pose_labels[1], "tube.gltf wiggle at 2 s");
}

TEST(GltfReader, TimesOutsideTheKeyframesAreReadWithAWarning) {
  const fs::path path = write(makeTube().model, "tube.gltf", false);
  const auto inside = read(path, {0.0, 0.5, 2.0});
  ASSERT_TRUE(inside.ok()) << inside.status().toString();
  EXPECT_TRUE(inside->warnings.empty());

  // "bend" keys its rotation at 0 and 2 s and its translation at 0 and 1 s.
  const auto outside = read(path, {-0.5, 1.0, 3.0});
  ASSERT_TRUE(outside.ok()) << outside.status().toString();
  ASSERT_EQ(outside->warnings.size(), 2u);
  for (const std::string& piece :
       std::vector<std::string>{path.string() + ": -0.5 s is outside bend's keyframes (0 to 2 s)", "at 0 s"}) {
    EXPECT_NE(outside->warnings[0].find(piece), std::string::npos) << outside->warnings[0];
  }
  for (const std::string& piece : std::vector<std::string>{path.string() + ": 3 s is outside", "at 2 s"}) {
    EXPECT_NE(outside->warnings[1].find(piece), std::string::npos) << outside->warnings[1];
  }
  // The warning says what happened: the pose at 3 s is the one at 2 s.
  const auto end = read(path, {2.0});
  ASSERT_TRUE(end.ok());
  EXPECT_EQ(outside->poses[3], end->poses[1]);
}

TEST(GltfReader, AnAnimationThatMovesNothingIsReadWithAWarning) {
  Builder b;
  b.model = makeTube().model;
  // Its one channel targets no node (as one of an extension's may), so odeskin skips it.
  tinygltf::Animation still;
  still.name = "still";
  addChannel(b, still, -1, "translation", "LINEAR", {0.0, 1.0}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.model.animations.push_back(still);
  const fs::path path = write(b.model, "still.gltf", false);
  const auto examples = read(path, {0.5, 1.0}, {}, "still");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find(path.string() + ": still animates no node"), std::string::npos)
      << examples->warnings[0];
}

TEST(GltfReader, SparseMorphTargetIsApplied) {
  for (int index_type : {kUByteType, kUShortType, kUIntType}) {
    for (bool over_base : {false, true}) {
      TubeOptions o;
      o.sparse_index_type = index_type;
      o.sparse_over_base = over_base;
      GltfPoseRequest request;
      request.morph_targets = {0};
      const auto examples = readGltfExamples(write(makeTube(o).model, "sparse.glb", true), request);
      ASSERT_TRUE(examples.ok()) << examples.status().toString();
      const ExampleSet& e = *examples;
      ASSERT_EQ(e.poses.size(), 2u);
      EXPECT_EQ(e.pose_labels[1], "sparse.glb target 0");
      for (std::size_t v = 0; v < 12; ++v) {
        const Vec3& x = e.rest_positions[v];
        EXPECT_EQ(e.poses[1][v], x + deltaOf(ringOf(x), o)) << "vertex " << v << " index type " << index_type;
      }
      for (const RigidTransform& key : e.rig->key_poses[1]) EXPECT_EQ(key.translation, Vec3(0.0));
    }
  }
}

TEST(GltfReader, QuantizedPositions) {
  TubeOptions o;
  o.position_type = kShortType;
  o.position_normalized = true;
  o.position_scale = 16000.0;
  GltfPoseRequest request;
  request.morph_targets = {0};
  const Tube tube = makeTube(o);
  const auto examples = readGltfExamples(write(tube.model, "quantized.gltf", false), request);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->rest_positions.size(), 12u);
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    const Vec3 stored = tube.render_positions[r] * 16000.0;
    EXPECT_EQ(examples->rest_positions[examples->render.topology_of_render[r]], stored / 32767.0);
  }
  // Without the extension those formats are not glTF.
  tinygltf::Model plain = tube.model;
  plain.extensionsRequired.clear();
  plain.extensionsUsed.clear();
  const auto refused = readGltfExamples(write(plain, "plain.gltf", false), request);
  EXPECT_EQ(refused.status().code(), StatusCode::kParseError);
  EXPECT_NE(refused.status().message().find("accessor " + std::to_string(tube.position_accessor)), std::string::npos)
      << refused.status().message();
}

// gltfpack's layout: 16-bit unsigned grid coordinates, the dequantization folded into the IBMs.
TubeOptions gltfpackLayout() {
  TubeOptions o;
  o.position_type = kUShortType;
  o.position_scale = 65535.0 / 2.0;  // the tube spans 2 along every axis
  o.position_offset = Vec3(-1.0, 0.0, -1.0);
  o.fold_into_skin = true;
  return o;
}

TEST(GltfReader, QuantizedSkinGivesTheFloatFilesPoses) {
  const TubeOptions o = gltfpackLayout();
  const double step = 1.0 / o.position_scale;
  const auto exact = read(write(makeTube().model, "float.glb", true), {0.5, 1.0}, {0});
  const auto quantized = read(write(makeTube(o).model, "quantized.glb", true), {0.5, 1.0}, {0});
  ASSERT_TRUE(exact.ok()) << exact.status().toString();
  ASSERT_TRUE(quantized.ok()) << quantized.status().toString();
  // The rest pose is the bind pose, so the grid goes back to the tube's own coordinates.
  ASSERT_EQ(quantized->rest_positions.size(), exact->rest_positions.size());
  for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
    expectNear(quantized->rest_positions[v], exact->rest_positions[v], step, "rest vertex " + std::to_string(v));
  }
  ASSERT_EQ(quantized->poses.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
      expectNear(quantized->poses[k][v], exact->poses[k][v], 2.0 * step,
                 quantized->pose_labels[k] + " vertex " + std::to_string(v));
    }
    for (std::size_t j = 0; j < 2; ++j) {
      const RigidTransform& a = quantized->rig->key_poses[k][j];
      const RigidTransform& b = exact->rig->key_poses[k][j];
      expectNear(a.translation, b.translation, 1e-6, "key translation");
      EXPECT_GT(std::abs(glm::dot(a.rotation, b.rotation)), 1.0 - 1e-9);
    }
  }
  for (std::size_t j = 0; j < 2; ++j) {
    expectNear(quantized->rig->skeleton.heads[j], exact->rig->skeleton.heads[j], 1e-6, "joint head");
  }
}

TEST(GltfReader, QuantizedSkinAwayFromItsBindPoseKeepsThePoses) {
  // The root rests 2 to the side of where it was bound: the bind space may move, the poses may not.
  auto shifted = [](const TubeOptions& o) {
    tinygltf::Model m = makeTube(o).model;
    m.nodes[1].translation = {2.0, 0.0, 0.0};
    return m;
  };
  const TubeOptions o = gltfpackLayout();
  const auto exact = read(write(shifted(TubeOptions{}), "float.glb", true), {0.5, 1.0}, {0});
  const auto quantized = read(write(shifted(o), "quantized.glb", true), {0.5, 1.0}, {0});
  ASSERT_TRUE(exact.ok()) << exact.status().toString();
  ASSERT_TRUE(quantized.ok()) << quantized.status().toString();
  for (std::size_t k = 1; k < 3; ++k) {  // the poses at times; the bind pose and target are bind space
    for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
      expectNear(quantized->poses[k][v], exact->poses[k][v], 2.0 / o.position_scale,
                 quantized->pose_labels[k] + " vertex " + std::to_string(v));
    }
  }
}

TEST(GltfReader, QuantizedSkinWhoseJointsScaleDifferentlyIsRefused) {
  tinygltf::Model m = makeTube(gltfpackLayout()).model;
  // Joint 1's inverse bind matrix scaled once more: no one grid explains both joints.
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(m.skins[0].inverseBindMatrices)];
  const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  auto* floats = reinterpret_cast<float*>(m.buffers[0].data.data() + view.byteOffset + a.byteOffset);
  for (int k = 0; k < 12; ++k) floats[16 + k] *= 1.5f;
  const fs::path path = write(m, "two-scales.glb", true);
  const auto r = read(path, {1.0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  for (const std::string& w : std::vector<std::string>{path.string(), "skin 0", "joint 1 'tip'", "joint 0 'root'",
                                                       "KHR_mesh_quantization"}) {
    EXPECT_NE(r.status().message().find(w), std::string::npos) << w << " not in: " << r.status().message();
  }
}

TEST(GltfReader, QuantizedUnskinnedMeshTakesItsNodesTransform) {
  TubeOptions o = gltfpackLayout();
  o.fold_into_skin = false;
  Tube tube = makeTube(o);
  tinygltf::Node& node = tube.model.nodes[0];
  node.skin = -1;  // the node's transform now counts: it holds the dequantization
  node.translation = {o.position_offset.x, o.position_offset.y, o.position_offset.z};
  node.scale = std::vector<double>(3, 1.0 / o.position_scale);
  GltfPoseRequest request;
  request.morph_targets = {0};
  const auto examples = readGltfExamples(write(tube.model, "unskinned.glb", true), request);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    expectNear(examples->rest_positions[examples->render.topology_of_render[r]], tube.render_positions[r],
               1.0 / o.position_scale, "render vertex " + std::to_string(r));
  }
}

// An unskinned mesh is read where its node's world transform puts it, as viewers show it: Blender's
// exporter leaves such a transform on every mesh it turns (a character imported from a y-up OBJ
// gets a quarter turn about x). A mirroring transform reverses the triangles' corners so they keep
// facing out; one that collapses the mesh is refused.
TEST(GltfReader, UnskinnedMeshIsReadWhereItsNodePutsIt) {
  tinygltf::Model model = makeTube().model;
  model.nodes[0].skin = -1;
  model.nodes[0].translation.clear();  // the tube's skinned node is translated: here its mesh space is wanted
  const auto local = read(write(model, "local.gltf", false), {}, {0});
  ASSERT_TRUE(local.ok()) << local.status().toString();
  // The mesh node under a parent: world = parent (translate) x node (turn, scale).
  tinygltf::Node parent;
  parent.translation = {1.0, 2.0, 3.0};
  parent.children = {0};
  model.nodes.push_back(parent);
  model.scenes[0].nodes = {static_cast<int>(model.nodes.size() - 1)};
  model.nodes[0].rotation = {std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};  // x, y, z, w: 90 degrees about x
  model.nodes[0].scale = {2.0, 2.0, 2.0};
  const auto placed = read(write(model, "placed.gltf", false), {}, {0});
  ASSERT_TRUE(placed.ok()) << placed.status().toString();
  auto world = [](const Vec3& p) { return Vec3(1.0, 2.0, 3.0) + 2.0 * Vec3(p.x, -p.z, p.y); };
  ASSERT_EQ(placed->poses.size(), local->poses.size());
  for (std::size_t k = 0; k < placed->poses.size(); ++k) {
    for (std::size_t v = 0; v < placed->poses[k].size(); ++v) {
      expectNear(placed->poses[k][v], world(local->poses[k][v]), 1e-12, "pose " + std::to_string(k));
    }
  }
  EXPECT_EQ(placed->faces.indices, local->faces.indices);
  for (std::size_t r = 0; r < placed->render.normals.size(); ++r) {
    const Vec3& n = local->render.normals[r];
    expectNear(placed->render.normals[r], Vec3(n.x, -n.z, n.y), 1e-12, "normal");
  }
  model.nodes[0].scale = {-2.0, 2.0, 2.0};
  const auto mirrored = read(write(model, "mirrored.gltf", false), {}, {0});
  ASSERT_TRUE(mirrored.ok()) << mirrored.status().toString();
  ASSERT_EQ(mirrored->faces.indices.size(), local->faces.indices.size());
  for (std::size_t t = 0; t < local->faces.indices.size(); t += 3) {
    EXPECT_EQ(mirrored->faces.indices[t], local->faces.indices[t]);
    EXPECT_EQ(mirrored->faces.indices[t + 1], local->faces.indices[t + 2]);
    EXPECT_EQ(mirrored->faces.indices[t + 2], local->faces.indices[t + 1]);
  }
  model.nodes[0].scale = {2.0, 0.0, 2.0};
  const auto collapsed = read(write(model, "collapsed.gltf", false), {}, {0});
  ASSERT_FALSE(collapsed.ok());
  EXPECT_NE(collapsed.status().message().find("collapsed.gltf: node 0 'tube': its world transform collapses the mesh (determinant 0)"), std::string::npos)
      << collapsed.status().message();
  // A node matrix must be affine: a projective last row is refused, not dropped.
  model.nodes[0].scale.clear();
  model.nodes[0].rotation.clear();
  model.nodes[0].matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  const auto projective = read(write(model, "projective.gltf", false), {}, {0});
  ASSERT_FALSE(projective.ok());
  EXPECT_NE(projective.status().message().find("projective.gltf: node 0: matrix's last row must be 0, 0, 0, 1"),
            std::string::npos)
      << projective.status().message();
  model.nodes[0].matrix.clear();
  model.nodes[0].scale = {1e300, 1e300, 1e300};
  const auto overflowing = read(write(model, "overflowing.gltf", false), {}, {0});
  ASSERT_FALSE(overflowing.ok());
  EXPECT_NE(overflowing.status().message().find("node 0 'tube': its world transform scales the mesh beyond double precision"),
            std::string::npos)
      << overflowing.status().message();
}

TEST(GltfReader, InterleavedPositionsHonourByteStride) {
  Tube tube = makeTube();
  // POSITION moved into an interleaved view: x y z and one float of something else per vertex.
  std::vector<double> interleaved;
  for (const Vec3& p : tube.render_positions) interleaved.insert(interleaved.end(), {p.x, p.y, p.z, 99.0});
  std::vector<unsigned char>& data = tube.model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteStride = 16;
  const std::vector<unsigned char> bytes = pack(interleaved, kFloatType);
  view.byteLength = bytes.size() - 4;  // the last vertex's extra float is not needed
  data.insert(data.end(), bytes.begin(), bytes.end());
  tube.model.bufferViews.push_back(view);
  tinygltf::Accessor& a = tube.model.accessors[static_cast<std::size_t>(tube.position_accessor)];
  a.bufferView = static_cast<int>(tube.model.bufferViews.size()) - 1;
  const auto examples = read(write(tube.model, "stride.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    EXPECT_EQ(examples->rest_positions[examples->render.topology_of_render[r]], tube.render_positions[r]);
  }
  tube.model.bufferViews.back().byteStride = 8;  // smaller than a VEC3 of floats
  expectError(read(write(tube.model, "short_stride.glb", true), {1.0}), StatusCode::kParseError, {"byteStride 8"});
}

// parseGltfExamples reads bytes in memory as readGltfExamples reads the file, GLB or JSON with
// embedded buffers, and refuses a buffer in an external file (there is no folder to look in).
TEST_P(GltfFormats, BytesInMemoryReadAsTheFile) {
  const bool binary = GetParam();
  const fs::path path = write(makeTube().model, binary ? "tube.glb" : "tube.gltf", binary);
  const std::string bytes = fileBytes(path);
  GltfPoseRequest request;
  request.times = {0.5, 1.0};
  request.morph_targets = {0};
  const Result<ExampleSet> from_file = readGltfExamples(path, request);
  const Result<ExampleSet> from_bytes = parseGltfExamples(bytes, path.string(), request);
  ASSERT_TRUE(from_file.ok()) << from_file.status().toString();
  ASSERT_TRUE(from_bytes.ok()) << from_bytes.status().toString();
  EXPECT_EQ(from_bytes->poses, from_file->poses);
  EXPECT_EQ(from_bytes->pose_labels, from_file->pose_labels);
  EXPECT_EQ(from_bytes->faces.indices, from_file->faces.indices);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin export` read back: the written GLB is decoded with tinygltf and played by an independent
// implementation of the glTF 2.0 specification (gltf_playback.hpp), and compared with odeskin's
// player (DeformPlayer + the reference kernel) at keys and mid-segment: positions, and the normals
// the NORMAL deltas give before skinning against the player's shape's.
#include "engine/export/gltf_export.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "../pipeline/dataset_fixtures.hpp"
#include "gltf_playback.hpp"
#include "engine/export/mode_targets.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "temp_dir_test.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Channel;
using testing::GltfPlayback;
using testing::readAccessor;

constexpr double kMatchTolerance = 1e-4;  // of the bounding box's longest side (issue 4.1)
constexpr double kKeyTolerance = 1e-6;    // at key times: float32 rounding only

// ---------------------------------------------------------------------------------------------
// Assets and odeskin's own playback

// The player's V topology positions at global time t: posed, or with identity bones the bind-space
// shape X + residual that the morph targets reproduce.
std::vector<Vec3> playerShape(const DeformAsset& asset, double t, bool posed) {
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  EXPECT_TRUE(player.ok());
  std::vector<Vec3> out(asset.vertexCount());
  const auto [segment, tau] = player->locate(t);
  if (posed) {
    EXPECT_TRUE(player->play(asset, segment, tau, out).ok());
    return out;
  }
  std::vector<ModeBasisValue> basis(player->basisSize());
  player->basisAt(tau, basis);
  const std::vector<BoneTransform> identity(asset.bone_count, BoneTransform(1.0));
  EXPECT_TRUE(referenceJob(asset, segment, basis, identity, out).run().ok());
  return out;
}

std::vector<Vec3> playerPositions(const DeformAsset& asset, double t) {
  return outputPositions(asset, playerShape(asset, t, true));
}

double degreesBetween(const Vec3& a, const Vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / std::numbers::pi;
}

// The procedural arm bent to 100 degrees and back to 40 (two segments, so the second carries a rate),
// with the upper arm as the forearm's parent.
DeformAsset armAsset(std::vector<Material> materials, bool alternate_materials, ResidualSpace space = ResidualSpace::kBind,
                     SkinningMode skinning = SkinningMode::kLinear) {
  ArmOptions bent;
  ArmOptions half = bent;
  half.bend_degrees = 40.0;
  half.bulge = 0.15;
  Result<ProceduralArm> a = makeProceduralArm(bent);
  Result<ProceduralArm> b = makeProceduralArm(half);
  EXPECT_TRUE(a.ok() && b.ok());
  FitInput input = a->fit_input;
  input.poses.push_back(b->end_positions);
  input.key_poses.push_back(b->fit_input.key_poses[1]);
  FitOptions options;
  options.modes = 6;
  options.residual_space = space;
  options.skinning = skinning;
  options.materials = std::move(materials);
  if (alternate_materials) {
    for (std::size_t c = 0; c < input.curves.size(); ++c) options.curve_materials.push_back(static_cast<std::uint32_t>(c % 2));
  }
  Result<DeformAsset> asset = fitDeformAsset(input, options);
  EXPECT_TRUE(asset.ok()) << asset.status().toString();
  DeformAsset out = std::move(asset).value();
  out.bone_parents = {-1, 0};
  out.bone_names = {"upper_arm", "forearm"};
  out.segment_seconds = 0.75;
  return out;
}

DeformAsset fitted(const Result<ExampleSet>& examples, const Material& material) {
  EXPECT_TRUE(examples.ok()) << examples.status().toString();
  PipelineOptions options;
  options.material = material;
  Result<PipelineResult> result = runFitPipeline(*examples, options);
  EXPECT_TRUE(result.ok()) << result.status().toString();
  return std::move(result->asset);
}

class GltfExportTest : public testing::TempDirTest {
 protected:
  GltfExportTest() : TempDirTest("odeskin_gltf_export_") {}

  // Exports `asset`, reads it back and compares with the player at keys and inside segments.
  GltfExportReport exportAndCompare(const DeformAsset& asset, const std::string& name,
                                    const GltfExportOptions& options = {}, bool nlerp_rotations = false) {
    const fs::path path = dir_ / (name + ".glb");
    Result<GltfExportReport> report = exportGltf(asset, path, options);
    EXPECT_TRUE(report.ok()) << report.status().toString();
    if (!report.ok()) return {};
    EXPECT_FALSE(report->baked);
    EXPECT_TRUE(fs::exists(path));
    EXPECT_FALSE(fs::exists(fs::path(path.string() + ".partial")));
    GltfPlayback gltf(path);
    if (!gltf.ok()) return *report;
    gltf.playRotationsAsNlerp(nlerp_rotations);
    expectSkinRules(gltf, asset.bone_count);
    expectWeightKeysInUnitRange(gltf, options.interpolation);
    const double box = report->box;
    const double t_end = static_cast<double>(asset.segments.size());
    double worst = 0.0, worst_t = 0.0, worst_key = 0.0;
    for (std::size_t eighth = 0; eighth <= 8 * asset.segments.size(); ++eighth) {  // every 1/8 of a segment
      const double t = 0.125 * static_cast<double>(eighth);
      for (const double at : {t, std::min(t + 0.0371, t_end)}) {  // keys, and times off the key grid
        const std::vector<Vec3> expected = playerPositions(asset, at);
        const std::vector<Vec3> played = gltf.positionsAt(at * asset.segment_seconds);
        EXPECT_EQ(played.size(), expected.size());
        if (played.size() != expected.size()) return *report;
        const bool key = at == std::floor(at);
        for (std::size_t i = 0; i < played.size(); ++i) {
          const double e = glm::length(played[i] - expected[i]) / box;
          if (e > worst) worst = e, worst_t = at;
          if (key) worst_key = std::max(worst_key, e);
        }
      }
    }
    std::printf("%s: %zu targets, %zu weight keys, %zu skeleton keys, %ju bytes; max |glTF - player| %.2e of the box "
                "(t = %.4f), at the keys %.2e; bounds: weights %.2e, skeleton %.2e, key corrections %.2e\n",
                name.c_str(), report->morph_targets, report->weight_keys, report->skeleton_keys, report->bytes, worst,
                worst_t, worst_key, report->weight_position_error, report->skeleton_position_error,
                report->player_deviation);
    expectNormalsFollowThePlayer(asset, gltf, *report, name);
    EXPECT_LT(worst, kMatchTolerance) << name << " at t = " << worst_t;
    // At the keys every weight and joint transform is a key value itself: the example poses come
    // back to float32 rounding, however many segments were summed before (the key corrections).
    EXPECT_LT(worst_key, kKeyTolerance) << name;
    return *report;
  }

  // The NORMAL deltas: before skinning, the normals viewers compute match the player's bind-space
  // shape's (exact at the keys, within the reported linearisation bound between them); skinned,
  // they are nearer the player's posed normals than the base NORMAL alone.
  static void expectNormalsFollowThePlayer(const DeformAsset& asset, const GltfPlayback& gltf,
                                           const GltfExportReport& report, const std::string& name) {
    ASSERT_TRUE(report.target_normals);
    ASSERT_TRUE(gltf.hasTargetNormals());
    double worst = 0.0, worst_key = 0.0, posed_with = 0.0, posed_without = 0.0, bind_with = 0.0, bind_without = 0.0;
    std::size_t samples = 0;
    for (std::size_t eighth = 0; eighth <= 8 * asset.segments.size(); ++eighth) {
      const double t = 0.125 * static_cast<double>(eighth);
      const std::vector<Vec3> exact = outputNormals(asset, playerShape(asset, t, false));
      const std::vector<Vec3> played = gltf.bindNormalsAt(t * asset.segment_seconds);
      const std::vector<Vec3> unmorphed = gltf.bindNormalsAt(t * asset.segment_seconds, false);
      ASSERT_EQ(played.size(), exact.size());
      const std::vector<Vec3> posed = outputNormals(asset, playerShape(asset, t, true));
      const std::vector<Vec3> with = gltf.normalsAt(t * asset.segment_seconds, true);
      const std::vector<Vec3> without = gltf.normalsAt(t * asset.segment_seconds, false);
      for (std::size_t i = 0; i < exact.size(); ++i) {
        const double e = degreesBetween(played[i], exact[i]);
        worst = std::max(worst, e);
        bind_with += e;
        bind_without += degreesBetween(unmorphed[i], exact[i]);
        if (t == std::floor(t)) worst_key = std::max(worst_key, e);
        posed_with += degreesBetween(with[i], posed[i]);
        posed_without += degreesBetween(without[i], posed[i]);
      }
      samples += exact.size();
    }
    posed_with /= static_cast<double>(samples);
    posed_without /= static_cast<double>(samples);
    bind_with /= static_cast<double>(samples);
    bind_without /= static_cast<double>(samples);
    std::printf("%s normals, degrees from the player's: bind space mean %.3f with the NORMAL deltas, %.3f without; max "
                "%.2f (reported %.2f, mean %.3f, 99%% of vertices %.2f), at the keys %.1e; skinned, mean %.3f with, "
                "%.3f without\n",
                name.c_str(), bind_with, bind_without, worst, report.normal_max_degrees, report.normal_mean_degrees,
                report.normal_p99_degrees, worst_key, posed_with, posed_without);
    EXPECT_LT(worst_key, 1e-3) << name;  // float32 deltas summed over the segments before
    // The report's figures are on the exact weight curves and the export's own shape; the keyed
    // weights and the key corrections' deviation from the player (both ~1e-5 of the box) add a little.
    EXPECT_LT(worst, report.normal_max_degrees + 0.05) << name;
    EXPECT_LE(report.normal_mean_degrees, report.normal_p99_degrees) << name;
    EXPECT_LE(report.normal_p99_degrees, report.normal_max_degrees) << name;
    // Where the deformation turns normals at all, the deltas take most of that error away.
    if (bind_without > 0.01) {
      EXPECT_LT(bind_with, 0.2 * bind_without) << name;
      EXPECT_LT(posed_with, posed_without) << name;
    } else {
      EXPECT_LE(bind_with, bind_without + 1e-6) << name;
    }
  }

  // ECOSYSTEM.md 2.1-2.2: skinned mesh node at the root with no transform, IBM last rows, weights.
  static void expectSkinRules(const GltfPlayback& gltf, std::uint32_t bones) {
    const tinygltf::Node& node = gltf.model().nodes[static_cast<std::size_t>(gltf.meshNode())];
    EXPECT_TRUE(node.translation.empty() && node.rotation.empty() && node.scale.empty() && node.matrix.empty());
    for (const tinygltf::Node& n : gltf.model().nodes) {
      EXPECT_EQ(std::count(n.children.begin(), n.children.end(), gltf.meshNode()), 0) << "the mesh node has a parent";
    }
    for (const Channel& c : gltf.channels()) {
      if (c.node == gltf.meshNode()) {
        EXPECT_EQ(c.path, "weights");
      }
    }
    const std::vector<double>& ibm = gltf.inverseBinds();
    ASSERT_EQ(ibm.size(), 16u * bones);
    for (std::size_t j = 0; j < bones; ++j) {
      EXPECT_EQ(ibm[16 * j + 3], 0.0);
      EXPECT_EQ(ibm[16 * j + 7], 0.0);
      EXPECT_EQ(ibm[16 * j + 11], 0.0);
      EXPECT_EQ(ibm[16 * j + 15], 1.0);
    }
    const std::vector<double>& joints = gltf.joints();
    const std::vector<double>& weights = gltf.weights();
    ASSERT_EQ(weights.size(), 4 * gltf.vertexCount());
    for (std::size_t i = 0; i < gltf.vertexCount(); ++i) {
      float sum = 0.0f;  // accumulated in float32 as the glTF-Validator does
      int non_zero = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        const double w = weights[4 * i + k];
        const double j = joints[4 * i + k];
        EXPECT_GE(w, 0.0);
        EXPECT_LT(j, bones);
        if (w == 0.0) {
          EXPECT_EQ(j, 0.0) << "unused joint slots must be 0";
        }
        if (w > 0.0) {
          ++non_zero;
          for (std::size_t other = 0; other < k; ++other) {
            if (weights[4 * i + other] > 0.0) {
              EXPECT_NE(joints[4 * i + other], j) << "joint twice at vertex " << i;
            }
          }
        }
        sum += static_cast<float>(w);
      }
      EXPECT_LE(std::abs(sum - 1.0f), 2e-7f * static_cast<float>(non_zero)) << "vertex " << i;
    }
  }

  // Also: every channel, the joints' too, has the interpolation asked for.
  static void expectWeightKeysInUnitRange(const GltfPlayback& gltf, KeyInterpolation interpolation) {
    const std::size_t targets = gltf.model().meshes[0].primitives[0].targets.size();
    const bool cubic = interpolation == KeyInterpolation::kCubicSpline;
    const std::size_t per_key = cubic ? 3 * targets : targets;
    for (const Channel& c : gltf.channels()) {
      EXPECT_EQ(c.interpolation, gltfInterpolationName(interpolation)) << c.path;
      if (c.path != "weights") continue;
      EXPECT_EQ(c.output.size(), per_key * c.input.size());
      for (std::size_t k = 0; k < c.input.size(); ++k) {
        if (k > 0) {
          EXPECT_GT(c.input[k], c.input[k - 1]);
        }
        for (std::size_t j = 0; j < targets; ++j) {
          const double w = c.output[k * per_key + (cubic ? targets : 0) + j];
          EXPECT_GE(w, 0.0);
          EXPECT_LE(w, 1.0);
        }
      }
    }
  }
};

TEST_F(GltfExportTest, ModeTargetsSumToTheKernelResidual) {
  // Inside segment s the targets of segment s weighted by their curves, plus everything earlier
  // held, reproduce the reference kernel's bind-space residual (exactly up to rounding, except the
  // key correction, whose difference from the player is the stated deviation bound).
  const DeformAsset asset = armAsset({staticMaterial(), skinMaterial()}, true);
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  ASSERT_TRUE(player.ok());
  Result<ModeTargetSet> set = buildModeTargets(asset, *player);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const std::vector<BoneTransform> identity(asset.bone_count, BoneTransform(1.0));
  std::vector<ModeBasisValue> basis(player->basisSize());
  std::vector<Vec3> kernel(asset.vertexCount());
  for (std::uint32_t s = 0; s < asset.segments.size(); ++s) {
    for (const double tau : {0.0, 0.3, 0.77, 1.0}) {
      player->basisAt(tau, basis);
      ASSERT_TRUE(referenceJob(asset, s, basis, identity, kernel).run().ok());  // identity bones: X + residual
      std::vector<Vec3> sum(asset.vertexCount());
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] = asset.rest_positions[i] + asset.segments[0].base_residuals[i];
      for (const ModeTarget& t : set->targets) {
        if (t.segment > s) continue;
        const double w = t.curve.at(t.segment == s ? tau : 1.0).value;
        for (std::size_t k = 0; k < t.field.vertices.size(); ++k) sum[t.field.vertices[k]] += w * t.field.values[k];
      }
      double worst = 0.0;
      for (std::size_t i = 0; i < sum.size(); ++i) worst = std::max(worst, glm::length(sum[i] - kernel[i]));
      EXPECT_LE(worst, remainderWeight(tau) * set->max_player_deviation + 1e-12) << "segment " << s << " tau " << tau;
    }
  }
}

TEST_F(GltfExportTest, ArmWithTwoMaterialsOnAlternateCurves) {
  const DeformAsset asset = armAsset({staticMaterial(), skinMaterial()}, true);
  const GltfExportReport report = exportAndCompare(asset, "arm_two_materials");
  EXPECT_EQ(report.joints, 2u);
  EXPECT_GT(report.merged_fields, 0u);  // the static material's modes all follow gamma = tau
}

TEST_F(GltfExportTest, ArmDynamicSkin) { exportAndCompare(armAsset({skinMaterial()}, false), "arm_skin"); }

TEST_F(GltfExportTest, RenderLayoutOfAGltfInputIsWritten) {
  // A glTF-fitted asset keeps its render vertices (split at seams): here every face's first corner
  // gets its own copy of the topology vertex, so render vertices outnumber topology vertices.
  DeformAsset asset = armAsset({skinMaterial()}, false);
  for (std::uint32_t v = 0; v < asset.vertexCount(); ++v) asset.render.topology_of_render.push_back(v);
  asset.render.faces = asset.faces;
  for (std::size_t f = 0; f < asset.faces.faceCount(); f += 7) {
    std::uint32_t& corner = asset.render.faces.indices[asset.faces.face_offsets[f]];
    asset.render.topology_of_render.push_back(corner);
    corner = static_cast<std::uint32_t>(asset.render.topology_of_render.size() - 1);
  }
  const GltfExportReport report = exportAndCompare(asset, "arm_render_layout");
  EXPECT_EQ(report.vertices, asset.render.topology_of_render.size());
}

// The input's hard edges (RenderLayout::normals that disagree) stay creased in the export: each
// side's NORMAL is the normal of its own faces, while a copy with the same normal as its vertex's
// first (a UV seam) keeps the welded one.
TEST_F(GltfExportTest, HardEdgesOfTheInputStayCreased) {
  DeformAsset asset = armAsset({skinMaterial()}, false);
  const std::uint32_t v = static_cast<std::uint32_t>(asset.vertexCount());
  std::vector<Vec3> area(v, Vec3(0.0));
  for (std::size_t f = 0; f < asset.faces.faceCount(); ++f) {
    const std::uint32_t b = asset.faces.face_offsets[f], e = asset.faces.face_offsets[f + 1];
    for (std::uint32_t k = b + 1; k + 1 < e; ++k) {
      const Vec3& a = asset.rest_positions[asset.faces.indices[b]];
      const Vec3 n = glm::cross(asset.rest_positions[asset.faces.indices[k]] - a, asset.rest_positions[asset.faces.indices[k + 1]] - a);
      for (std::uint32_t c = b; c < e; ++c) area[asset.faces.indices[c]] += n;
    }
  }
  for (std::uint32_t i = 0; i < v; ++i) {
    asset.render.topology_of_render.push_back(i);
    asset.render.normals.push_back(glm::normalize(area[i]));
  }
  asset.render.faces = asset.faces;
  std::vector<bool> turned(v, false);  // the render copy turned 40 degrees: a hard edge
  for (std::size_t f = 0; f < asset.faces.faceCount(); f += 7) {
    std::uint32_t& corner = asset.render.faces.indices[asset.faces.face_offsets[f]];
    const std::uint32_t i = corner;
    Vec3 n = glm::normalize(area[i]);
    if (f % 14 == 7) {
      n = std::cos(0.7) * n + std::sin(0.7) * glm::normalize(glm::cross(n, std::fabs(n.z) < 0.9 ? Vec3(0, 0, 1) : Vec3(1, 0, 0)));
      turned.push_back(true);
    } else {
      turned.push_back(false);
    }
    asset.render.topology_of_render.push_back(i);
    asset.render.normals.push_back(n);
    corner = static_cast<std::uint32_t>(asset.render.topology_of_render.size() - 1);
  }
  std::vector<bool> hard(v, false);
  for (std::size_t r = v; r < turned.size(); ++r) {
    if (turned[r]) hard[asset.render.topology_of_render[r]] = true;
  }
  const fs::path path = dir_ / "arm_hard_edges.glb";
  ASSERT_TRUE(exportGltf(asset, path, GltfExportOptions{}).ok());
  GltfPlayback gltf(path);
  ASSERT_TRUE(gltf.ok());
  const tinygltf::Primitive& prim = gltf.model().meshes.at(0).primitives.at(0);
  const std::vector<double> positions = readAccessor(gltf.model(), prim.attributes.at("POSITION"));
  const std::vector<double> normals = readAccessor(gltf.model(), prim.attributes.at("NORMAL"));
  ASSERT_EQ(normals.size(), 3 * asset.render.topology_of_render.size());
  auto at = [](const std::vector<double>& xs, std::size_t r) { return Vec3(xs[3 * r], xs[3 * r + 1], xs[3 * r + 2]); };
  // Each render face's fan normal goes to its corners' groups: a hard vertex's turned and
  // unturned copies apart, every other vertex's copies together.
  auto group = [&](std::uint32_t r) {
    const std::uint32_t i = asset.render.topology_of_render[r];
    return 2 * std::size_t{i} + (hard[i] && turned[r] ? 1 : 0);
  };
  std::vector<Vec3> sums(2 * std::size_t{v}, Vec3(0.0));
  const FaceList& faces = asset.render.faces;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t b = faces.face_offsets[f], e = faces.face_offsets[f + 1];
    Vec3 n(0.0);
    for (std::uint32_t k = b + 1; k + 1 < e; ++k) {
      const Vec3 a = at(positions, faces.indices[b]);
      n += glm::cross(at(positions, faces.indices[k]) - a, at(positions, faces.indices[k + 1]) - a);
    }
    for (std::uint32_t c = b; c < e; ++c) sums[group(faces.indices[c])] += n;
  }
  double worst = 0.0, crease = 0.0;
  for (std::uint32_t r = 0; r < asset.render.topology_of_render.size(); ++r) {
    const Vec3 expected = glm::normalize(sums[group(r)]);
    worst = std::max(worst, glm::length(at(normals, r) - expected));
    const std::uint32_t i = asset.render.topology_of_render[r];
    if (hard[i]) crease = std::max(crease, std::acos(std::min(1.0, glm::dot(at(normals, r), at(normals, i)))));
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(crease, 0.1);  // the sides of a crease differ
  std::printf("hard edges: max |NORMAL - own faces' normal| %.2e, creases up to %.1f degrees\n", worst,
              crease * 180.0 / 3.141592653589793);
}

TEST_F(GltfExportTest, CylinderWithItsRigStaticAndSkin) {
  const DeformAsset skin = fitted(testing::cylinderWithRig(true, true), skinMaterial());
  ASSERT_EQ(skin.segments.size(), 3u);
  exportAndCompare(skin, "cylinder_skin");
  exportAndCompare(fitted(testing::cylinderWithRig(true, true), staticMaterial()), "cylinder_static");
}

TEST_F(GltfExportTest, HorseFourKeysAutoRigSkin) {
  const DeformAsset asset = fitted(readObjSequence(testing::horseFrames({1, 5, 9, 13})), skinMaterial());
  ASSERT_EQ(asset.segments.size(), 3u);
  const GltfExportReport report = exportAndCompare(asset, "horse");
  EXPECT_LT(report.weight_position_error, 1e-5);
  EXPECT_LT(report.skeleton_position_error, 1e-5);

  // LINEAR keys meet the same bounds with more keys, played with glTF's slerp or Blender's nlerp.
  GltfExportOptions linear;
  linear.interpolation = KeyInterpolation::kLinear;
  for (const bool nlerp : {false, true}) {
    const GltfExportReport lin = exportAndCompare(asset, nlerp ? "horse_linear_nlerp" : "horse_linear", linear, nlerp);
    EXPECT_EQ(lin.interpolation, KeyInterpolation::kLinear);
    EXPECT_LT(lin.weight_position_error, 1e-5);
    EXPECT_LT(lin.skeleton_position_error, 1e-5);
    EXPECT_GT(lin.weight_keys, report.weight_keys);
    EXPECT_GT(lin.skeleton_keys, report.skeleton_keys);
  }
}

// Three segments whose weights and joints turn at the joins: LINEAR keys follow them too.
TEST_F(GltfExportTest, CylinderWithLinearKeys) {
  GltfExportOptions linear;
  linear.interpolation = KeyInterpolation::kLinear;
  const DeformAsset skin = fitted(testing::cylinderWithRig(true, true), skinMaterial());
  exportAndCompare(skin, "cylinder_skin_linear", linear, false);
  exportAndCompare(skin, "cylinder_skin_linear_nlerp", linear, true);
}

// --quantize: it plays as the float export within the rounding error its report measured, is a
// quarter smaller or more, odeskin's reader takes it back, and no inverse bind matrix carries the
// grid's scale (the skeleton root node does: Blender 3.4 drops a scale in inverse bind matrices).
// The same for the baked form, whose mesh node carries the grid.
TEST_F(GltfExportTest, QuantizedExportPlaysAsTheFloatOneWithinItsRounding) {
  const DeformAsset asset = fitted(testing::cylinderWithRig(true, true), skinMaterial());
  GltfExportOptions options;
  options.quantize = true;
  const fs::path float_path = dir_ / "float.glb";
  const fs::path quantized_path = dir_ / "quantized.glb";
  Result<GltfExportReport> exact = exportGltf(asset, float_path, GltfExportOptions{});
  Result<GltfExportReport> quantized = exportGltf(asset, quantized_path, options);
  ASSERT_TRUE(exact.ok() && quantized.ok()) << quantized.status().toString();
  EXPECT_FALSE(exact->quantized);
  EXPECT_TRUE(quantized->quantized);
  EXPECT_LT(static_cast<double>(quantized->bytes), 0.75 * static_cast<double>(exact->bytes));
  EXPECT_NEAR(quantized->quantization_step * 65534.0, 1.0, 1e-9);
  EXPECT_GT(quantized->quantization_error, 0.0);
  EXPECT_LT(quantized->quantization_error, 3e-4);
  EXPECT_LT(quantized->normal_quantization_p99_degrees, 1.0);
  EXPECT_EQ(quantized->float_deltas, 0u);

  GltfPlayback a(float_path);
  GltfPlayback b(quantized_path);
  ASSERT_TRUE(a.ok() && b.ok());
  const tinygltf::Model& m = b.model();
  EXPECT_EQ(m.extensionsRequired, std::vector<std::string>{"KHR_mesh_quantization"});
  const tinygltf::Primitive& primitive = m.meshes.at(0).primitives.at(0);
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(primitive.attributes.at("POSITION"))).componentType,
            TINYGLTF_COMPONENT_TYPE_SHORT);
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(primitive.attributes.at("NORMAL"))).componentType,
            TINYGLTF_COMPONENT_TYPE_BYTE);
  const std::vector<double> ibm = readAccessor(m, m.skins.at(0).inverseBindMatrices);
  for (std::size_t k = 0; k < ibm.size(); ++k) {
    const std::size_t entry = k % 16;
    if (entry < 12) {
      EXPECT_EQ(ibm[k], entry % 5 == 0 ? 1.0 : 0.0) << "inverse bind matrix " << k / 16;
    }
  }
  const double step = quantized->quantization_step * quantized->box;
  EXPECT_EQ(m.nodes.at(1).scale, std::vector<double>(3, step));

  const double box = quantized->box;
  const double bound = 1.5 * quantized->quantization_error + 2e-6;  // weights between keys may overshoot theirs
  for (std::size_t eighth = 0; eighth <= 8 * asset.segments.size(); ++eighth) {
    const double seconds = 0.125 * static_cast<double>(eighth) * asset.segment_seconds;
    const std::vector<Vec3> p = a.positionsAt(seconds);
    const std::vector<Vec3> q = b.positionsAt(seconds);
    ASSERT_EQ(p.size(), q.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) worst = std::max(worst, glm::length(q[i] - p[i]) / box);
    EXPECT_LT(worst, bound) << "at " << seconds << " s";
  }

  // odeskin's reader finds the grid in the skin: its poses are the file's.
  GltfPoseRequest request;
  request.include_bind_pose = false;
  request.times = {0.6 * asset.segment_seconds, 2.3 * asset.segment_seconds};
  Result<ExampleSet> read = readGltfExamples(quantized_path, request);
  ASSERT_TRUE(read.ok()) << read.status().toString();
  for (std::size_t k = 0; k < request.times.size(); ++k) {
    const std::vector<Vec3> played = b.positionsAt(request.times[k]);
    const std::vector<Vec3>& pose = read->poses[k];
    ASSERT_EQ(pose.size(), played.size());
    for (std::size_t i = 0; i < pose.size(); ++i) {
      EXPECT_LT(glm::length(pose[i] - played[i]) / box, 1e-5) << "vertex " << i << " at " << request.times[k] << " s";
    }
  }

  // Baked, the mesh node undoes the grid, and every frame is within the reported error.
  GltfExportOptions baked = options;
  baked.bake = true;
  baked.bake_fps = 8.0;
  GltfExportOptions baked_float = baked;
  baked_float.quantize = false;
  Result<GltfExportReport> frames_q = exportGltf(asset, dir_ / "baked-q.glb", baked);
  Result<GltfExportReport> frames_f = exportGltf(asset, dir_ / "baked-f.glb", baked_float);
  ASSERT_TRUE(frames_q.ok() && frames_f.ok()) << frames_q.status().toString();
  EXPECT_TRUE(frames_q->baked && frames_q->quantized);
  EXPECT_LT(frames_q->bytes, frames_f->bytes);  // less so: a turning normal's delta stays float32
  EXPECT_GT(frames_q->quantization_error, 0.0);
  EXPECT_LT(frames_q->quantization_error, 1e-4);
  GltfPlayback c(dir_ / "baked-f.glb");
  GltfPlayback d(dir_ / "baked-q.glb");
  ASSERT_TRUE(c.ok() && d.ok());
  EXPECT_EQ(d.model().nodes.at(0).scale, std::vector<double>(3, frames_q->quantization_step * frames_q->box));
  for (std::size_t frame = 0; frame < frames_q->frames; ++frame) {
    const double seconds = std::min(static_cast<double>(frame) / 8.0, 3.0 * asset.segment_seconds);
    const std::vector<Vec3> p = c.positionsAt(seconds);
    const std::vector<Vec3> q = d.positionsAt(seconds);
    double worst = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) worst = std::max(worst, glm::length(q[i] - p[i]) / box);
    EXPECT_LT(worst, frames_q->quantization_error + 2e-6) << "frame " << frame;
  }
}

// Without NORMAL deltas every target has POSITION only, the file is smaller, and a segment whose
// key correction moves nothing has no target for it.
TEST_F(GltfExportTest, TargetNormalsCanBeLeftOut) {
  const DeformAsset asset = fitted(testing::cylinderWithRig(true, true), staticMaterial());
  GltfExportOptions options;
  options.target_normals = false;
  Result<GltfExportReport> without = exportGltf(asset, dir_ / "without.glb", options);
  Result<GltfExportReport> with = exportGltf(asset, dir_ / "with.glb", GltfExportOptions{});
  ASSERT_TRUE(without.ok() && with.ok());
  EXPECT_FALSE(without->target_normals);
  EXPECT_TRUE(with->target_normals);
  EXPECT_LT(without->bytes, with->bytes);
  EXPECT_LT(without->morph_targets, with->morph_targets);
  GltfPlayback gltf(dir_ / "without.glb");
  ASSERT_TRUE(gltf.ok());
  EXPECT_FALSE(gltf.hasTargetNormals());
  for (const auto& target : gltf.model().meshes.at(0).primitives.at(0).targets) {
    EXPECT_EQ(target.size(), 1u);
    EXPECT_EQ(target.count("POSITION"), 1u);
  }
}

TEST_F(GltfExportTest, PosedResidualAndDualQuaternionAssetsAreBaked) {
  for (const bool posed : {true, false}) {
    const DeformAsset asset = posed ? armAsset({skinMaterial()}, false, ResidualSpace::kPosed)
                                    : armAsset({skinMaterial()}, false, ResidualSpace::kBind, SkinningMode::kDualQuaternion);
    const fs::path path = dir_ / (posed ? "posed.glb" : "dqs.glb");
    GltfExportOptions options;
    options.bake_fps = 8.0;
    Result<GltfExportReport> report = exportGltf(asset, path, options);
    ASSERT_TRUE(report.ok()) << report.status().toString();
    EXPECT_TRUE(report->baked);
    EXPECT_NE(report->bake_reason.find(posed ? "posed space" : "dual-quaternion"), std::string::npos);
    // 2 segments of 0.75 s at 8 fps: frames at 0, 1/8, ..., 11/8 s and the end at 1.5 s.
    EXPECT_EQ(report->frames, 13u);
    GltfPlayback gltf(path);
    ASSERT_TRUE(gltf.ok());
    EXPECT_TRUE(gltf.model().skins.empty());
    ASSERT_EQ(gltf.channels().size(), 1u);
    EXPECT_EQ(gltf.channels()[0].interpolation, "LINEAR");
    // At frame times the bake is the player (float32); between them it cross-fades linearly.
    for (const double seconds : {0.0, 0.5, 1.375, 1.5}) {
      const std::vector<Vec3> expected = playerPositions(asset, seconds / asset.segment_seconds);
      const std::vector<Vec3> played = gltf.positionsAt(seconds);
      ASSERT_EQ(played.size(), expected.size());
      double worst = 0.0;
      for (std::size_t i = 0; i < played.size(); ++i) worst = std::max(worst, glm::length(played[i] - expected[i]));
      EXPECT_LT(worst, 1e-6) << "t = " << seconds << " s";
    }
    const std::vector<Vec3> a = playerPositions(asset, 0.5 / 0.75), b = playerPositions(asset, 0.625 / 0.75);
    const std::vector<Vec3> mid = gltf.positionsAt(0.5625);
    for (std::size_t i = 0; i < mid.size(); ++i) ASSERT_LT(glm::length(mid[i] - 0.5 * (a[i] + b[i])), 1e-6);
    // Each frame's NORMAL (the mesh's, plus the frame's target delta) is that frame's shape's,
    // so viewers shade it smooth and following the corrective deformation.
    const tinygltf::Primitive& prim = gltf.model().meshes.at(0).primitives.at(0);
    const std::vector<double> base = readAccessor(gltf.model(), prim.attributes.at("NORMAL"));
    for (const std::size_t frame : {std::size_t{0}, std::size_t{4}, std::size_t{12}}) {
      const double seconds = frame == 12 ? 1.5 : static_cast<double>(frame) / 8.0;
      const std::vector<Vec3> expected = outputNormals(asset, playerPositions(asset, seconds / asset.segment_seconds));
      std::vector<double> normals = base;
      if (frame > 0) {
        const std::vector<double> delta = readAccessor(gltf.model(), prim.targets.at(frame - 1).at("NORMAL"));
        for (std::size_t k = 0; k < normals.size(); ++k) normals[k] += delta[k];
      }
      ASSERT_EQ(normals.size(), 3 * expected.size());
      double worst = 0.0;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        worst = std::max(worst, glm::length(Vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]) - expected[i]));
      }
      EXPECT_LT(worst, 1e-6) << "frame " << frame;
    }
  }
}

TEST_F(GltfExportTest, BakeOnRequest) {
  const DeformAsset asset = armAsset({skinMaterial()}, false);
  GltfExportOptions options;
  options.bake = true;
  options.bake_fps = 4.0;
  Result<GltfExportReport> report = exportGltf(asset, dir_ / "bake.glb", options);
  ASSERT_TRUE(report.ok()) << report.status().toString();
  EXPECT_TRUE(report->baked);
  EXPECT_TRUE(report->bake_reason.empty());
  EXPECT_EQ(report->frames, 7u);  // 0 .. 1.5 s at 4 fps
  EXPECT_EQ(report->morph_targets, 6u);
}

// A huge segment length is refused at once, from the frame count: the times were stored frame by
// frame before the size check, which took memory without limit (and never ended past 1e308 s).
TEST_F(GltfExportTest, HugeBakeIsRefusedBeforeAnyFrame) {
  DeformAsset asset = armAsset({skinMaterial()}, false);
  GltfExportOptions options;
  options.bake = true;
  for (const double segment_seconds : {1e6, 1e300, std::numeric_limits<double>::max()}) {
    asset.segment_seconds = segment_seconds;
    Result<GltfExportReport> report = exportGltf(asset, dir_ / "huge.glb", options);
    ASSERT_FALSE(report.ok()) << segment_seconds;
    EXPECT_EQ(report.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(report.status().message().find("export: baking "), std::string::npos) << report.status().message();
    EXPECT_NE(report.status().message().find("needs 2 GiB or more"), std::string::npos) << report.status().message();
  }
  EXPECT_NE(exportGltf(asset, dir_ / "huge.glb", options).status().message().find("baking more than 1.79769e+308 frames"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "huge.glb"));
}

TEST_F(GltfExportTest, UnwritableOutputLeavesNoFile) {
  const DeformAsset asset = armAsset({skinMaterial()}, false);
  // The parent is a regular file: nothing can be created there.
  const fs::path blocker = write("not-a-folder", "x");
  Result<GltfExportReport> report = exportGltf(asset, blocker / "out.glb", GltfExportOptions{});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.status().code(), StatusCode::kIoError);
  EXPECT_NE(report.status().message().find("out.glb"), std::string::npos);
  // The output is a non-empty folder: the file is written, then cannot replace it, and is removed.
  const fs::path folder = dir_ / "taken.glb";
  fs::create_directories(folder / "inside");
  report = exportGltf(asset, folder, GltfExportOptions{});
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.status().code(), StatusCode::kIoError);
  EXPECT_TRUE(fs::is_directory(folder / "inside"));
  EXPECT_FALSE(fs::exists(dir_ / "taken.glb.partial"));
  report = exportGltf(asset, folder, [] {
    GltfExportOptions o;
    o.bake = true;
    return o;
  }());
  ASSERT_FALSE(report.ok());
  EXPECT_FALSE(fs::exists(dir_ / "taken.glb.partial"));
}

TEST_F(GltfExportTest, RejectsBadOptionsAndAssets) {
  DeformAsset asset = armAsset({skinMaterial()}, false);
  GltfExportOptions options;
  options.tolerance = 0.0;
  Result<GltfExportReport> report = exportGltf(asset, dir_ / "x.glb", options);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.status().code(), StatusCode::kInvalidArgument);
  options = GltfExportOptions{};
  options.bake_fps = -1.0;
  EXPECT_FALSE(exportGltf(asset, dir_ / "x.glb", options).ok());
  asset.bone_parents = {1, 0};  // a cycle
  report = exportGltf(asset, dir_ / "x.glb", GltfExportOptions{});
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.status().message().find("cycle"), std::string::npos);
  asset.bone_parents.clear();
  // A vertex beyond float32's range: refused up front, where a morph target failed on it before.
  DeformAsset far = asset;
  far.rest_positions[3] *= 1e50;
  report = exportGltf(far, dir_ / "x.glb", GltfExportOptions{});
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.status().message().find("export: vertex 3 is outside glTF's float32 range"), std::string::npos)
      << report.status().message();
  asset.segments[0].coefficients.pop_back();  // inconsistent sizes
  EXPECT_FALSE(exportGltf(asset, dir_ / "x.glb", GltfExportOptions{}).ok());
  EXPECT_FALSE(fs::exists(dir_ / "x.glb"));
}

}  // namespace
}  // namespace odeskin

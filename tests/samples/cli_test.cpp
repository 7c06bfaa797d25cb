// SPDX-License-Identifier: MIT
// The odeskin verbs play and info, called as the program calls them, on the procedural arm fitted
// and saved to a temporary .odsk; plus the option parsers behind play and fit.
#include <filesystem>
#include <fstream>
#include <cstring>
#include <functional>
#include <iterator>
#include <sstream>

#include <gtest/gtest.h>

#include "engine/io/gltf_reader.hpp"

#include "engine/io/asset_file.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/io/text_tokens.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "host/gpu_test_support.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/asset_info.hpp"
#include "samples/odeskin/compare_command.hpp"
#include "samples/odeskin/fit_options.hpp"
#include "samples/odeskin/material_options.hpp"
#include "samples/odeskin/play_command.hpp"
#include "samples/odeskin/progress.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;

constexpr double kKeyTolerance = 1e-4;     // of the box: --t k reproduces example pose k
constexpr double kBackendTolerance = 1e-5; // of the box: cpu and vulkan outputs agree

using testing::Captured;
using testing::CommandCase;

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_cli_test_", name); }

double maxDistance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  return worst;
}

std::vector<Vec3> readPositions(const fs::path& path) {
  Result<ObjMesh> mesh = readObj(path);
  EXPECT_TRUE(mesh.ok()) << mesh.status().toString();
  return mesh.ok() ? mesh->positions : std::vector<Vec3>{};
}

// The procedural arm (skin material, default key tolerance), saved once for every test.
class Cli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
    ASSERT_TRUE(arm.ok()) << arm.status().toString();
    FitOptions fit;
    fit.materials = {skinMaterial()};
    Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, fit);
    ASSERT_TRUE(asset.ok()) << asset.status().toString();
    arm_ = new ProceduralArm(std::move(arm).value());
    asset_ = new DeformAsset(std::move(asset).value());
    dir_ = new fs::path(scratch("assets"));
    ASSERT_TRUE(saveAsset(assetPath(), *asset_).ok());
  }
  static void TearDownTestSuite() {
    delete arm_;
    delete asset_;
    delete dir_;
  }
  static fs::path assetPath() { return *dir_ / "arm.odsk"; }
  static double box() { return longestBoxSide(arm_->end_positions); }

  static int play(const PlayOptions& options, Captured& io, PlayReport* report = nullptr) {
    return runPlayCommand(options, io.console, report);
  }
  // The asset played at 4 fps into dir/frames/arm_NNN.obj: the frames other outputs are checked against.
  static PlayOptions sequenceAt4Fps(const fs::path& dir) {
    PlayOptions o;
    o.asset = assetPath();
    o.fps = 4.0;
    o.output = (dir / "frames" / "arm_%03d.obj").string();
    return o;
  }
  static PlayOptions atTime(double t, const fs::path& output) {
    PlayOptions o;
    o.asset = assetPath();
    o.t = t;
    o.output = output.string();
    return o;
  }

  static ProceduralArm* arm_;
  static DeformAsset* asset_;
  static fs::path* dir_;
};
ProceduralArm* Cli::arm_ = nullptr;
DeformAsset* Cli::asset_ = nullptr;
fs::path* Cli::dir_ = nullptr;

TEST_F(Cli, PlayAtKeyTimesReproducesTheExamplePoses) {
  const fs::path dir = scratch("keys");
  Captured io;
  ASSERT_EQ(play(atTime(0.0, dir / "t0.obj"), io), kExitOk) << io.err.str();
  ASSERT_EQ(play(atTime(1.0, dir / "nested" / "folder" / "t1.obj"), io), kExitOk) << io.err.str();
  ASSERT_EQ(play(atTime(0.5, dir / "mid.obj"), io), kExitOk) << io.err.str();
  EXPECT_LE(maxDistance(readPositions(dir / "t0.obj"), arm_->start_positions), kKeyTolerance * box());
  EXPECT_LE(maxDistance(readPositions(dir / "nested" / "folder" / "t1.obj"), arm_->end_positions), kKeyTolerance * box());
  // The middle really moves: it is neither pose.
  const std::vector<Vec3> mid = readPositions(dir / "mid.obj");
  EXPECT_GT(maxDistance(mid, arm_->start_positions), 0.05 * box());
  EXPECT_GT(maxDistance(mid, arm_->end_positions), 0.05 * box());
  // Faces are the asset's.
  Result<ObjMesh> mesh = readObj(dir / "mid.obj");
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->faces.indices, asset_->faces.indices);
  EXPECT_NE(io.out.str().find("t = 0.5 (segment 0, tau 0.5)"), std::string::npos) << io.out.str();
  EXPECT_TRUE(io.err.str().empty()) << io.err.str();  // not a terminal: no progress bar
}

TEST_F(Cli, PlaySequenceMapsSecondsToKeyTime) {
  const fs::path dir = scratch("sequence");
  PlayOptions o = sequenceAt4Fps(dir);
  Captured io;
  PlayReport report;
  ASSERT_EQ(play(o, io, &report), kExitOk) << io.err.str();
  // 1 s (one segment of the default length) at 4 fps: t = 0, 0.25, ..., 1.
  ASSERT_EQ(report.files.size(), 5u);
  EXPECT_EQ(report.files[2], dir / "frames" / "arm_002.obj");
  EXPECT_DOUBLE_EQ(report.times[1], 0.25);
  for (const fs::path& file : report.files) EXPECT_TRUE(fs::exists(file)) << file;
  EXPECT_FALSE(fs::exists(dir / "frames" / "arm_005.obj"));
  EXPECT_LE(maxDistance(readPositions(report.files.back()), arm_->end_positions), kKeyTolerance * box());
  // The sequence's frame 2 is the single frame at t = 0.5, bit for bit.
  ASSERT_EQ(play(atTime(0.5, dir / "mid.obj"), io), kExitOk);
  EXPECT_EQ(readPositions(dir / "mid.obj"), readPositions(report.files[2]));

  // --seconds past the end clamps to the last key, and says so.
  o.seconds = 1.5;
  o.output = (dir / "long_%d.obj").string();
  Captured held;
  ASSERT_EQ(play(o, held, &report), kExitOk) << held.err.str();
  EXPECT_NE(held.err.str().find("note: --seconds 1.5 runs past " + o.asset.string() +
                                "'s 1 s; the frames after it hold the last key pose"),
            std::string::npos)
      << held.err.str();
  ASSERT_EQ(report.files.size(), 7u);
  EXPECT_EQ(report.files.back(), dir / "long_6.obj");
  EXPECT_DOUBLE_EQ(report.times.back(), 1.0);
}

TEST_F(Cli, PlaySequenceToGlbHoldsEveryFrameAsAMorphTarget) {
  const fs::path dir = scratch("glb");
  PlayOptions o = sequenceAt4Fps(dir);
  Captured io;
  PlayReport frames;
  ASSERT_EQ(play(o, io, &frames), kExitOk) << io.err.str();
  o.output = (dir / "arm.glb").string();
  PlayReport baked;
  ASSERT_EQ(play(o, io, &baked), kExitOk) << io.err.str();
  ASSERT_EQ(baked.files, std::vector<fs::path>{dir / "arm.glb"});
  // Read back with odeskin's own glTF reader: the mesh is frame 0, target k - 1 at weight 1 is frame k.
  GltfPoseRequest request;
  for (int k = 0; k + 1 < static_cast<int>(frames.files.size()); ++k) request.morph_targets.push_back(k);
  Result<ExampleSet> read = readGltfExamples(dir / "arm.glb", request);
  ASSERT_TRUE(read.ok()) << read.status().toString();
  ASSERT_EQ(read->poses.size(), frames.files.size());
  for (std::size_t k = 0; k < frames.files.size(); ++k) {
    // float32 storage of positions and of the displacements from frame 0
    EXPECT_LE(maxDistance(read->poses[k], readPositions(frames.files[k])), 1e-6 * box()) << "frame " << k;
  }
  // With NORMALs, so viewers shade it smooth (glTF has them compute flat normals otherwise).
  EXPECT_EQ(read->render.normals.size(), read->render.topology_of_render.size());
  // At a time, as a viewer plays it: the STEP weights animation shows frame k from k / 4 s on.
  GltfPoseRequest timed;
  timed.include_bind_pose = false;
  timed.min_poses = 1;
  timed.times = {0.5, 0.6};
  read = readGltfExamples(dir / "arm.glb", timed);
  ASSERT_TRUE(read.ok()) << read.status().toString();
  ASSERT_EQ(read->poses.size(), 2u);
  EXPECT_FALSE(read->rig.has_value());
  for (const std::vector<Vec3>& pose : read->poses) {
    EXPECT_LE(maxDistance(pose, readPositions(frames.files[2])), 1e-6 * box());
  }

  // --quantize: the same frames on a 16-bit grid the mesh node undoes, within the error it prints.
  o.output = (dir / "arm-q.glb").string();
  o.quantize = true;
  Captured quantized_io;
  ASSERT_EQ(play(o, quantized_io, &baked), kExitOk) << quantized_io.err.str();
  EXPECT_NE(quantized_io.out.str().find("quantized (KHR_mesh_quantization): grid step 1.53e-05 of the box"),
            std::string::npos)
      << quantized_io.out.str();
  EXPECT_LT(fs::file_size(dir / "arm-q.glb"), fs::file_size(dir / "arm.glb"));
  read = readGltfExamples(dir / "arm-q.glb", request);
  ASSERT_TRUE(read.ok()) << read.status().toString();
  for (std::size_t k = 0; k < frames.files.size(); ++k) {
    EXPECT_LE(maxDistance(read->poses[k], readPositions(frames.files[k])), 5e-5 * box()) << "quantized frame " << k;
  }
}

TEST_F(Cli, PlaySequenceToPc2HoldsEveryFrame) {
  const fs::path dir = scratch("pc2");
  PlayOptions o = sequenceAt4Fps(dir);
  Captured io;
  PlayReport frames;
  ASSERT_EQ(play(o, io, &frames), kExitOk) << io.err.str();
  o.output = (dir / "cache" / "arm.pc2").string();
  PlayReport cached;
  ASSERT_EQ(play(o, io, &cached), kExitOk) << io.err.str();
  ASSERT_EQ(cached.files, std::vector<fs::path>{dir / "cache" / "arm.pc2"});
  EXPECT_NE(io.out.str().find("arm.pc2 (point cache of " + std::to_string(asset_->vertexCount()) + " vertices"),
            std::string::npos) << io.out.str();

  std::ifstream in(cached.files.front(), std::ios::binary);
  const std::string b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::size_t v = asset_->vertexCount();
  ASSERT_EQ(b.size(), 32 + frames.files.size() * v * 12);
  auto f32 = [&b](std::size_t at) {
    float x = 0.0F;
    std::memcpy(&x, b.data() + at, 4);  // x86 and ARM are little-endian, as PC2 is
    return x;
  };
  std::uint32_t samples = 0;
  std::memcpy(&samples, b.data() + 28, 4);
  EXPECT_EQ(samples, frames.files.size());
  EXPECT_EQ(f32(20), 0.0F);  // sample k at frame k
  EXPECT_EQ(f32(24), 1.0F);
  for (std::size_t k = 0; k < frames.files.size(); ++k) {
    const std::vector<Vec3> frame = readPositions(frames.files[k]);
    ASSERT_EQ(frame.size(), v);
    double worst = 0.0;
    for (std::size_t i = 0; i < v; ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        worst = std::max(worst, std::abs(f32(32 + (k * v + i) * 12 + std::size_t(axis) * 4) - frame[i][axis]));
      }
    }
    EXPECT_LE(worst, 1e-6 * box()) << "frame " << k;  // float32 against OBJ's printed doubles
  }
  // --t writes a one-sample cache.
  ASSERT_EQ(play(atTime(0.5, dir / "one.pc2"), io), kExitOk) << io.err.str();
  EXPECT_EQ(fs::file_size(dir / "one.pc2"), 32 + v * 12);

  // The same frames as MDD: big-endian counts, a time per sample, the same positions byte-swapped.
  o.output = (dir / "arm.mdd").string();
  ASSERT_EQ(play(o, io), kExitOk) << io.err.str();
  std::ifstream mdd_in(dir / "arm.mdd", std::ios::binary);
  const std::string mdd{std::istreambuf_iterator<char>(mdd_in), std::istreambuf_iterator<char>()};
  const std::size_t n = frames.files.size();
  ASSERT_EQ(mdd.size(), 8 + 4 * n + n * v * 12);
  EXPECT_EQ(static_cast<std::uint8_t>(mdd[3]), n);  // big-endian: the low byte last
  EXPECT_EQ(std::string(mdd.rbegin(), mdd.rbegin() + 4), b.substr(b.size() - 4)) << "z of the last vertex";
}

TEST_F(Cli, PlayUsesTheSegmentLengthAndTheRenderLayout) {
  const fs::path dir = scratch("layout");
  DeformAsset asset = *asset_;
  asset.segment_seconds = 2.0;
  // Split vertex 0 into a second render vertex used by the first face.
  for (std::uint32_t i = 0; i < asset.vertexCount(); ++i) asset.render.topology_of_render.push_back(i);
  asset.render.topology_of_render.push_back(0);
  asset.render.faces = asset.faces;
  asset.render.faces.indices[0] = static_cast<std::uint32_t>(asset.vertexCount());
  ASSERT_TRUE(saveAsset(dir / "layout.odsk", asset).ok());
  PlayOptions o;
  o.asset = dir / "layout.odsk";
  o.fps = 2.0;
  o.output = (dir / "f%02d.obj").string();
  Captured io;
  PlayReport report;
  ASSERT_EQ(play(o, io, &report), kExitOk) << io.err.str();
  ASSERT_EQ(report.files.size(), 5u);  // 2 s at 2 fps
  EXPECT_DOUBLE_EQ(report.times[1], 0.25);
  Result<ObjMesh> last = readObj(report.files.back());
  ASSERT_TRUE(last.ok()) << last.status().toString();
  ASSERT_EQ(last->positions.size(), asset.vertexCount() + 1);
  EXPECT_EQ(last->positions.back(), last->positions.front());
  EXPECT_EQ(last->faces.indices, asset.render.faces.indices);
  last->positions.pop_back();
  EXPECT_LE(maxDistance(last->positions, arm_->end_positions), kKeyTolerance * box());
}

// An asset fitted from OBJ files with `vt` keeps the input's vertex order in its OBJ frames and
// point caches (each corner naming its UV, the seams kept), and says where its UVs came from.
TEST_F(Cli, PlayKeepsAnObjInputsVertexOrderAndTexcoords) {
  const fs::path dir = scratch("obj-uvs");
  const std::size_t v = asset_->vertexCount();
  ObjMesh input;
  input.positions = asset_->rest_positions;
  input.faces = asset_->faces;
  for (std::size_t i = 0; i < v; ++i) {
    input.texcoords.emplace_back(static_cast<double>(i % 8) / 8.0, static_cast<double>(i / 8 % 8) / 8.0);
  }
  input.texcoords.emplace_back(0.5, 0.5);  // the first corner's, across a seam
  input.corner_texcoords = input.faces.indices;
  input.corner_texcoords[0] = static_cast<std::uint32_t>(v);
  DeformAsset asset = *asset_;
  asset.render = objRenderLayout(input);
  ASSERT_EQ(asset.render.topology_of_render.size(), v + 1);
  ASSERT_TRUE(saveAsset(dir / "uv.odsk", asset).ok());

  PlayOptions o = atTime(1.0, dir / "t1.obj");
  o.asset = dir / "uv.odsk";
  Captured io;
  ASSERT_EQ(play(o, io), kExitOk) << io.err.str();
  Result<ObjMesh> frame = readObj(dir / "t1.obj");
  ASSERT_TRUE(frame.ok()) << frame.status().toString();
  ASSERT_EQ(frame->positions.size(), v);
  EXPECT_LE(maxDistance(frame->positions, arm_->end_positions), kKeyTolerance * box());
  EXPECT_EQ(frame->faces.indices, asset.faces.indices);
  const RenderLayout read_back = objRenderLayout(*frame);
  EXPECT_EQ(read_back.topology_of_render, asset.render.topology_of_render);
  EXPECT_EQ(read_back.uvs, asset.render.uvs);

  o.output = (dir / "t1.pc2").string();
  ASSERT_EQ(play(o, io), kExitOk) << io.err.str();
  EXPECT_EQ(fs::file_size(dir / "t1.pc2"), 32 + v * 12);
  EXPECT_NE(io.out.str().find("(point cache of " + std::to_string(v) + " vertices"), std::string::npos) << io.out.str();

  Captured info;
  ASSERT_EQ(runInfoCommand(o.asset, info.console), kExitOk) << info.err.str();
  EXPECT_NE(info.out.str().find(std::to_string(v) + " (" + std::to_string(v + 1) +
                                " render vertices); with the input's texture coordinates (vt)"),
            std::string::npos)
      << info.out.str();
}

TEST_F(Cli, PlayRejectsBadUsageWithExitCode2) {
  const fs::path dir = scratch("usage");
  std::vector<CommandCase<PlayOptions>> cases;
  cases.push_back({atTime(1.5, dir / "x.obj"), "--t 1.5 is outside [0, 1]"});
  cases.push_back({atTime(-0.1, dir / "x.obj"), "outside [0, 1]"});
  cases.push_back({atTime(1.0000001, dir / "x.obj"), "--t 1.0000001 is outside [0, 1]"});  // once "--t 1"
  cases.push_back({atTime(std::nan(""), dir / "x.obj"), "--t must be a number"});
  cases.push_back({atTime(0.5, dir / "x.gltf"), "write .glb"});
  cases.push_back({atTime(0.5, dir / "x.ply"), "unknown output format"});
  cases.push_back({atTime(0.5, ""), "-o OUT is required"});
  PlayOptions dressed = atTime(0.5, dir / "x.obj");
  dressed.materials = dir / "look.glb";
  cases.push_back({dressed, "--materials needs -o OUT.glb"});
  PlayOptions quantized = atTime(0.5, dir / "x.obj");
  quantized.quantize = true;
  cases.push_back({quantized, "--quantize needs -o OUT.glb"});
  PlayOptions both = atTime(0.5, dir / "x.obj");
  both.fps = 30.0;
  cases.push_back({both, "either --t T"});
  PlayOptions neither = atTime(0.5, dir / "x.obj");
  neither.t.reset();
  cases.push_back({neither, "either --t T"});
  PlayOptions fps = neither;
  fps.fps = 0.0;
  fps.output = (dir / "x%d.obj").string();
  cases.push_back({fps, "--fps must be positive"});
  fps.fps = 30.0;
  fps.seconds = -1.0;
  cases.push_back({fps, "--seconds must be zero or positive"});
  fps.seconds = 1e9;
  cases.push_back({fps, "more than 1000000 frames"});
  fps.seconds.reset();
  fps.output = (dir / "x.obj").string();
  cases.push_back({fps, "needs a frame number"});
  fps.output = (dir / "x%d_%d.obj").string();
  cases.push_back({fps, "more than one % conversion"});
  // One .glb holds every frame (positions and normals): refused before any frame is played.
  fps.fps = 1000.0;
  fps.seconds = 100.0;
  fps.output = (dir / "x.glb").string();
  cases.push_back({fps, "x.glb: baking 100001 frames of " + std::to_string(arm_->start_positions.size()) +
                            " vertices needs 2 GiB or more; lower --fps or --seconds, or write .obj frames"});
  fps.output = (dir / "x.pc2").string();
  fps.seconds = 999.0;
  cases.push_back({fps, "x.pc2: 999001 frames of " + std::to_string(asset_->vertexCount()) + " vertices need"});
  testing::expectRejected(cases, [](const PlayOptions& o, Captured& io) { return play(o, io); }, kExitUsage, "play");
  EXPECT_TRUE(fs::is_empty(dir)) << "a rejected command wrote something";
}

// `odeskin compare`: the asset at its last key against that example pose, then against the first
// pose with a heat-map PLY and a JSON report, and the refusals.
TEST_F(Cli, CompareScoresAnAssetAgainstAPose) {
  const fs::path dir = scratch("compare");
  ASSERT_TRUE(writeObj(dir / "end.obj", arm_->end_positions, asset_->faces).ok());
  CompareOptions o;
  o.mesh = assetPath();
  o.reference = dir / "end.obj";
  o.t = 1.0;
  Captured io;
  CompareReport report;
  ASSERT_EQ(runCompareCommand(o, io.console, &report), kExitOk) << io.err.str();
  EXPECT_EQ(report.vertices, asset_->vertexCount());
  EXPECT_NEAR(report.box, box(), 1e-6 * box());  // the reference went through OBJ text
  EXPECT_LE(report.max_error, kKeyTolerance);
  EXPECT_LE(report.mean_error, report.rms_error);
  EXPECT_LE(report.rms_error, report.max_error);
  EXPECT_LE(report.p99_error, report.max_error);
  EXPECT_NE(io.out.str().find("max error (MVE): "), std::string::npos) << io.out.str();

  // At t = 0 the asset is the start pose: far from the end pose, the worst vertex where it says.
  o.t = 0.0;
  o.ply = dir / "heat" / "start.ply";
  o.json = dir / "start.json";
  o.heat_max = 0.5;
  ASSERT_EQ(runCompareCommand(o, io.console, &report), kExitOk) << io.err.str();
  const double worst = maxDistance(arm_->start_positions, arm_->end_positions) / box();
  EXPECT_NEAR(report.max_error, worst, kKeyTolerance);
  EXPECT_NEAR(glm::length(arm_->start_positions[report.max_vertex] - arm_->end_positions[report.max_vertex]) / box(),
              worst, kKeyTolerance);
  EXPECT_EQ(report.heat_max, 0.5);
  std::ifstream ply(o.ply, std::ios::binary);
  std::string header;
  std::getline(ply, header);
  EXPECT_EQ(header, "ply");
  const std::string text{std::istreambuf_iterator<char>(ply), std::istreambuf_iterator<char>()};
  EXPECT_NE(text.find("element vertex " + std::to_string(asset_->vertexCount()) + "\n"), std::string::npos);
  EXPECT_NE(text.find("colour = error / 0.5 of the box"), std::string::npos);
  Result<std::string> json = readTextFile(o.json);
  ASSERT_TRUE(json.ok());
  EXPECT_NE(json->find("\"p99\""), std::string::npos) << *json;
  EXPECT_NE(json->find("\"heat_max\": 0.5"), std::string::npos) << *json;

  // An asset with a glTF layout plays OBJ frames in render vertices (one more here: vertex 0 is split
  // at a seam); compare reads them back in the asset's welded order, either way round.
  DeformAsset seamed = *asset_;
  const auto v = static_cast<std::uint32_t>(seamed.vertexCount());
  for (std::uint32_t i = 0; i < v; ++i) seamed.render.topology_of_render.push_back(i);
  seamed.render.topology_of_render.push_back(0);
  seamed.render.faces = seamed.faces;
  seamed.render.faces.indices[0] = v;
  ASSERT_TRUE(saveAsset(dir / "seamed.odsk", seamed).ok());
  PlayOptions frame;
  frame.asset = dir / "seamed.odsk";
  frame.t = 0.0;  // the reference side of compare is read at t = 0
  frame.output = (dir / "seamed-start.obj").string();
  ASSERT_EQ(play(frame, io), kExitOk) << io.err.str();
  ASSERT_EQ(readPositions(dir / "seamed-start.obj").size(), v + 1u);
  CompareOptions split = o;
  split.mesh = dir / "seamed.odsk";
  split.reference = dir / "seamed-start.obj";
  split.ply.clear();
  split.json.clear();
  split.heat_max.reset();
  split.t = 0.0;
  ASSERT_EQ(runCompareCommand(split, io.console, &report), kExitOk) << io.err.str();
  EXPECT_EQ(report.vertices, v);
  EXPECT_LT(report.max_error, 1e-6);
  std::swap(split.mesh, split.reference);
  split.t.reset();
  ASSERT_EQ(runCompareCommand(split, io.console, &report), kExitOk) << io.err.str();
  EXPECT_EQ(report.vertices, v + 1u);
  EXPECT_LT(report.max_error, 1e-6);

  // A reference with other vertices fails, naming both counts.
  std::vector<Vec3> fewer = arm_->end_positions;
  fewer.pop_back();
  FaceList triangle;
  triangle.indices = {0, 1, 2};
  triangle.face_offsets = {0, 3};
  ASSERT_TRUE(writeObj(dir / "fewer.obj", fewer, triangle).ok());
  CompareOptions mismatch;
  mismatch.mesh = assetPath();
  mismatch.reference = dir / "fewer.obj";
  Captured failed;
  EXPECT_EQ(runCompareCommand(mismatch, failed.console), kExitFailure);
  EXPECT_NE(failed.err.str().find(std::to_string(asset_->vertexCount()) + " vertices but the reference has " +
                                  std::to_string(fewer.size())), std::string::npos) << failed.err.str();

  const fs::path usage = scratch("compare_usage");
  std::vector<CommandCase<CompareOptions>> cases;
  CompareOptions base = mismatch;
  base.reference = dir / "end.obj";
  CompareOptions c = base;
  c.heat_max = 0.1;
  cases.push_back({c, "--heat-max needs -o OUT.ply"});
  c.ply = usage / "x.ply";
  c.heat_max = -1.0;
  cases.push_back({c, "--heat-max must be a positive fraction of the box"});
  c = base;
  c.ply = usage / "x.obj";
  cases.push_back({c, "write .ply"});
  c = base;
  c.json = usage / "x.txt";
  cases.push_back({c, "write .json"});
  c = base;
  c.ply = dir / "folder.ply";
  fs::create_directories(c.ply);
  cases.push_back({c, "folder.ply is a folder"});
  c = base;
  c.mesh = dir / "end.obj";
  c.t = 0.5;  // an OBJ is one pose: the time was ignored
  cases.push_back({c, "--t applies to a .odsk or .glb/.gltf MESH; "});
  testing::expectRejected(cases, [](const CompareOptions& options, Captured& out) { return runCompareCommand(options, out.console); },
                          kExitUsage, "compare");
  EXPECT_TRUE(fs::is_empty(usage)) << "a rejected command wrote something";
}

TEST_F(Cli, MissingOrCorruptAssetFailsWithExitCode1) {
  const fs::path dir = scratch("corrupt");
  Captured io;
  PlayOptions o = atTime(0.5, dir / "x.obj");
  o.asset = dir / "absent.odsk";
  EXPECT_EQ(play(o, io), kExitFailure);
  EXPECT_EQ(io.err.str().rfind("odeskin: error: " + o.asset.string() + ": ", 0), 0u) << io.err.str();

  std::ifstream in(assetPath(), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x10);
  o.asset = dir / "corrupt.odsk";
  std::ofstream(o.asset, std::ios::binary) << bytes;
  Captured io2;
  EXPECT_EQ(play(o, io2), kExitFailure);
  EXPECT_NE(io2.err.str().find("corrupt.odsk: checksum mismatch"), std::string::npos) << io2.err.str();
  Captured io3;
  EXPECT_EQ(runInfoCommand(o.asset, io3.console), kExitFailure);
  EXPECT_NE(io3.err.str().find("corrupt.odsk: checksum mismatch"), std::string::npos) << io3.err.str();
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

TEST_F(Cli, InfoNumbers) {
  const std::uintmax_t bytes = fs::file_size(assetPath());
  const AssetStats s = assetStats(*asset_, bytes);
  const std::size_t v = arm_->start_positions.size();
  EXPECT_EQ(s.vertices, v);
  EXPECT_EQ(s.render_vertices, v);
  EXPECT_EQ(s.faces, asset_->faces.faceCount());
  EXPECT_EQ(s.curves, 21u);
  EXPECT_EQ(s.parts, 1u);  // the arm's curves all belong to part 0
  EXPECT_EQ(s.terms, 9);
  EXPECT_EQ(s.key_poses, 2u);
  EXPECT_EQ(s.segments, 1u);
  EXPECT_EQ(s.bones, 2u);
  EXPECT_EQ(s.coefficient_floats, 1u * 21u * 20u * 3u);
  EXPECT_EQ(s.remainders, asset_->segments[0].remainders.size());
  EXPECT_EQ(s.file_bytes, bytes);
  EXPECT_EQ(s.pose_bytes, 2 * v * 3 * 4);
  EXPECT_EQ(s.baked_frames, 31.0);  // 1 s at 30 fps, both ends
  EXPECT_EQ(s.baked_bytes, static_cast<double>(31 * v * 3 * 4));
  EXPECT_DOUBLE_EQ(s.ratio_to_poses, static_cast<double>(bytes) / static_cast<double>(2 * v * 12));
  EXPECT_DOUBLE_EQ(s.ratio_to_baked, static_cast<double>(bytes) / static_cast<double>(31 * v * 12));
  EXPECT_GT(s.gpu_bytes, 0u);

  // Three keys of 2.5 s each: 5 s at 30 fps is 151 frames.
  DeformAsset longer = *asset_;
  longer.segment_seconds = 2.5;
  longer.key_poses.push_back(longer.key_poses[0]);
  longer.segments.push_back(longer.segments[0]);
  const AssetStats l = assetStats(longer, bytes);
  EXPECT_EQ(l.segments, 2u);
  EXPECT_EQ(l.baked_frames, 151.0);
  EXPECT_EQ(l.coefficient_floats, 2u * 21u * 20u * 3u);
  EXPECT_EQ(l.pose_bytes, 3 * v * 12);

  Captured io;
  ASSERT_EQ(runInfoCommand(assetPath(), io.console), kExitOk) << io.err.str();
  const std::string text = io.out.str();
  EXPECT_NE(text.find("vertices:       " + std::to_string(v) + "\n"), std::string::npos) << text;
  EXPECT_NE(text.find("terms N:        9"), std::string::npos) << text;
  EXPECT_NE(text.find("coefficients:   1260 floats"), std::string::npos) << text;
  EXPECT_NE(text.find("31 frames x V x 3 float32"), std::string::npos) << text;
  EXPECT_NE(text.find("file bytes:     " + std::to_string(bytes) + " B"), std::string::npos) << text;

  // A huge segment length: the bake is counted in double, where std::size_t wrapped around and
  // printed "9223372036854775809 frames"; past double's range it is said so.
  DeformAsset huge = *asset_;
  huge.segment_seconds = 1e300;
  const AssetStats huge_stats = assetStats(huge, bytes);
  EXPECT_EQ(huge_stats.baked_frames, 3e301);
  std::ostringstream huge_text;
  printAssetStats(huge_text, "huge.odsk", huge_stats);
  EXPECT_NE(huge_text.str().find("1e+300 s)"), std::string::npos) << huge_text.str();
  EXPECT_NE(huge_text.str().find(" (3e+301 frames x V x 3 float32)"), std::string::npos) << huge_text.str();
  huge.segment_seconds = 1e308;
  std::ostringstream endless_text;
  printAssetStats(endless_text, "huge.odsk", assetStats(huge, bytes));
  EXPECT_NE(endless_text.str().find("baked 30 fps:   more frames than a double can count"), std::string::npos)
      << endless_text.str();

  // A render layout whose bind normals split vertex 0 into the two sides of a hard edge.
  DeformAsset seamed = *asset_;
  for (std::uint32_t i = 0; i < v; ++i) seamed.render.topology_of_render.push_back(i);
  seamed.render.topology_of_render.push_back(0);
  seamed.render.faces = seamed.faces;
  seamed.render.faces.indices[0] = static_cast<std::uint32_t>(v);
  seamed.render.normals.assign(v + 1, Vec3(0.0, 0.0, 1.0));
  seamed.render.normals.back() = Vec3(1.0, 0.0, 0.0);
  const AssetStats h = assetStats(seamed, bytes);
  EXPECT_EQ(h.render_vertices, v + 1);
  EXPECT_EQ(h.hard_edge_vertices, 1u);
  std::ostringstream hard_text;
  printAssetStats(hard_text, "seamed.odsk", h);
  EXPECT_NE(hard_text.str().find("(" + std::to_string(v + 1) + " render vertices, 1 on hard edges)"), std::string::npos)
      << hard_text.str();
  // With the input's texture coordinates and its two primitives.
  seamed.render.uvs.assign(v + 1, Vec2(0.5));
  const auto faces = static_cast<std::uint32_t>(seamed.render.faces.faceCount());
  seamed.render.primitives = {{faces / 2, 0}, {faces, 1}};
  const AssetStats dressed = assetStats(seamed, bytes);
  EXPECT_TRUE(dressed.texcoords);
  EXPECT_EQ(dressed.primitives, 2u);
  std::ostringstream dressed_text;
  printAssetStats(dressed_text, "dressed.odsk", dressed);
  EXPECT_NE(dressed_text.str().find("; with the input's TEXCOORD_0; 2 glTF primitives with their materials"),
            std::string::npos)
      << dressed_text.str();
}

class CliOnGpu : public testing::GpuTest {};

TEST_F(CliOnGpu, CpuAndVulkanOutputsAgree) {
  Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
  ASSERT_TRUE(arm.ok());
  FitOptions fit;
  fit.materials = {skinMaterial()};
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, fit);
  ASSERT_TRUE(asset.ok());
  const fs::path dir = scratch("backends");
  ASSERT_TRUE(saveAsset(dir / "arm.odsk", *asset).ok());
  PlayOptions o;
  o.asset = dir / "arm.odsk";
  o.fps = 5.0;
  o.output = (dir / "cpu" / "%d.obj").string();
  o.playback.backend = Backend::kCpu;
  o.playback.validation = true;
  Captured io;
  PlayReport cpu;
  ASSERT_EQ(runPlayCommand(o, io.console, &cpu), kExitOk) << io.err.str();
  EXPECT_NE(io.err.str().find("note: --validation checks Vulkan calls, and --backend cpu without --png makes none"),
            std::string::npos)
      << io.err.str();
  o.output = (dir / "vulkan" / "%d.obj").string();
  o.playback.backend = Backend::kVulkan;
  PlayReport gpu;
  ASSERT_EQ(runPlayCommand(o, io.console, &gpu), kExitOk) << io.err.str();
  EXPECT_EQ(gpu.device.rfind("vulkan: ", 0), 0u) << gpu.device;
  ASSERT_EQ(cpu.files.size(), 6u);
  ASSERT_EQ(gpu.files.size(), cpu.files.size());
  const double box = longestBoxSide(arm->end_positions);
  for (std::size_t f = 0; f < cpu.files.size(); ++f) {
    EXPECT_LE(maxDistance(readPositions(cpu.files[f]), readPositions(gpu.files[f])), kBackendTolerance * box) << f;
  }
}

TEST(FramePattern, AcceptsExactlyOneIntegerConversion) {
  const std::pair<const char*, const char*> good[] = {{"a_%d.obj", "a_7.obj"},       {"a_%04d.obj", "a_0007.obj"},
                                                      {"%3i.obj", "  7.obj"},         {"100%%_%u.obj", "100%_7.obj"},
                                                      {"dir_%02d/m.obj", "dir_07/m.obj"}};
  for (const auto& [pattern, expected] : good) {
    Result<FramePattern> p = FramePattern::parse(pattern);
    ASSERT_TRUE(p.ok()) << pattern << ": " << p.status().toString();
    EXPECT_EQ(p->format(7), expected);
  }
  EXPECT_EQ(FramePattern::parse("f%02d.obj")->format(1234), "f1234.obj");  // width is a minimum
  for (const char* bad : {"a.obj", "a_%%.obj", "%d_%d.obj", "%s.obj", "%.2f.obj", "%-4d.obj", "%x.obj", "a_%",
                          "%99d.obj", "%ld.obj"}) {
    const Result<FramePattern> p = FramePattern::parse(bad);
    EXPECT_EQ(p.status().code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_NE(p.status().message().find(bad), std::string::npos) << p.status().message();
  }
}

TEST(SequenceSeconds, IncludesBothEnds) {
  EXPECT_EQ(sequenceSeconds(30.0, 1.0).size(), 31u);
  EXPECT_EQ(sequenceSeconds(30.0, 0.0).size(), 1u);
  EXPECT_EQ(sequenceSeconds(10.0, 0.3).size(), 4u);  // 0.3 * 10 is 2.9999999999999996
  EXPECT_EQ(sequenceSeconds(3.0, 1.0).size(), 4u);
  EXPECT_DOUBLE_EQ(sequenceSeconds(3.0, 1.0).back(), 1.0);
  EXPECT_TRUE(sequenceSeconds(1e6, 1e3).empty());  // over the frame limit
}

TEST(MaterialOptions, Presets) {
  const Material skin = *parseMaterial("skin");
  EXPECT_EQ(skin.rho, skinMaterial().rho);
  EXPECT_EQ(skin.xi, skinMaterial().xi);
  EXPECT_EQ(parseMaterial("static")->zeta, staticMaterial().zeta);
  const Result<Material> numbers = parseMaterial("1050,0.619,1e4,2.5e-6");
  ASSERT_TRUE(numbers.ok()) << numbers.status().toString();
  EXPECT_EQ(numbers->rho, 1050.0);
  EXPECT_EQ(numbers->eta, 0.619);
  EXPECT_EQ(numbers->zeta, 1e4);
  EXPECT_EQ(numbers->xi, 2.5e-6);
  EXPECT_EQ(numbers->bending, BendingSign::kThesis);
  const Result<Material> spaced = parseMaterial("1050, 0.619 ,1e4,\t1e-320");
  ASSERT_TRUE(spaced.ok()) << spaced.status().toString();
  EXPECT_EQ(spaced->eta, 0.619);
  EXPECT_EQ(spaced->xi, 1e-320);
  for (const char* bad : {"", "rubber", "1,2,3", "1,2,3,4,5", "1,2,x,4", "1,,3,4", "1,2,3,inf", "1,2,3,4 x", "1e999,0,1,0",
                          "0x10,1,1,1", "1, ,3,4"}) {
    const Result<Material> m = parseMaterial(bad);
    EXPECT_EQ(m.status().code(), StatusCode::kInvalidArgument) << "'" << bad << "'";
  }
}

TEST(MaterialOptions, PartsJson) {
  const Result<MaterialChoice> choice = parseMaterialsJson(R"({
      "default": "static",
      "parts": {"forearm": "skin", "1": {"rho": 1, "eta": 2, "zeta": 3, "xi": 4, "bending": "stiffening"},
                "hand": "5,6,7,8"}})",
                                                           "parts.json");
  ASSERT_TRUE(choice.ok()) << choice.status().toString();
  EXPECT_EQ(choice->default_material.zeta, staticMaterial().zeta);
  EXPECT_EQ(choice->default_material.rho, staticMaterial().rho);
  ASSERT_EQ(choice->parts.size(), 3u);
  EXPECT_EQ(choice->parts.at("forearm").rho, skinMaterial().rho);
  const Material& one = choice->parts.at("1");
  EXPECT_EQ(one.rho, 1.0);
  EXPECT_EQ(one.eta, 2.0);
  EXPECT_EQ(one.zeta, 3.0);
  EXPECT_EQ(one.xi, 4.0);
  EXPECT_EQ(one.bending, BendingSign::kStiffening);
  EXPECT_EQ(choice->parts.at("hand").xi, 8.0);
  // Without "default", the fallback (the --material value) stays.
  const Result<MaterialChoice> fallback = parseMaterialsJson(R"({"parts": {}})", "p", staticMaterial());
  ASSERT_TRUE(fallback.ok());
  EXPECT_EQ(fallback->default_material.zeta, staticMaterial().zeta);
  EXPECT_TRUE(fallback->parts.empty());

  EXPECT_EQ(parseMaterialsJson("{\"parts\": ", "broken.json").status().code(), StatusCode::kParseError);
  const std::pair<const char*, const char*> bad[] = {
      {R"([1, 2])", "expected an object"},
      {R"({"defaults": "skin"})", "unknown key \"defaults\""},
      {R"({"default": "rubber"})", "rubber"},
      {R"({"default": 3})", "a material is"},
      {R"({"parts": []})", "\"parts\" must be an object"},
      {R"({"parts": {"": "skin"}})", "empty name"},
      {R"({"parts": {"arm": {"rho": 1, "eta": 2, "zeta": 3}}})", "\"xi\" is missing"},
      {R"({"parts": {"arm": {"rho": 1, "eta": 2, "zeta": 3, "xi": "4"}}})", "\"xi\" must be a finite number"},
      {R"({"parts": {"arm": {"rho": 1, "eta": 2, "zeta": 3, "xi": 4, "nu": 5}}})", "unknown key \"nu\""},
      {R"({"parts": {"arm": {"rho": 1, "eta": 2, "zeta": 3, "xi": 4, "bending": "soft"}}})", "bending"},
  };
  for (const auto& [text, message] : bad) {
    const Result<MaterialChoice> r = parseMaterialsJson(text, "parts.json");
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << text;
    EXPECT_EQ(r.status().message().rfind("parts.json: ", 0), 0u) << r.status().message();
    EXPECT_NE(r.status().message().find(message), std::string::npos) << r.status().message();
  }
  // A repeated key is refused, not the last copy taken (nlohmann keeps the last).
  const Result<MaterialChoice> twice = parseMaterialsJson(R"({"parts": {"arm": "skin", "arm": "static"}})", "parts.json");
  EXPECT_EQ(twice.status().code(), StatusCode::kParseError);
  EXPECT_EQ(twice.status().message(), "parts.json: parts: \"arm\" appears twice in one object");
  EXPECT_EQ(parseMaterialsJson(R"({"default": "skin", "default": "static"})", "p.json").status().message(),
            "p.json: (top level): \"default\" appears twice in one object");
  const fs::path dir = scratch("materials");
  EXPECT_EQ(readMaterialsJson(dir / "absent.json").status().code(), StatusCode::kIoError);
  std::ofstream(dir / "parts.json") << R"({"default": "static"})";
  const Result<MaterialChoice> read = readMaterialsJson(dir / "parts.json");
  ASSERT_TRUE(read.ok()) << read.status().toString();
  EXPECT_EQ(read->default_material.zeta, staticMaterial().zeta);
}

FitCommandOptions objFit() {
  FitCommandOptions o;
  o.inputs = {"a.obj", "b.OBJ", "c.obj"};
  o.output = "out.odsk";
  return o;
}

TEST(FitOptions, InputKinds) {
  std::string problem;
  FitCommandOptions o = objFit();
  EXPECT_EQ(fitInputKind(o, &problem), FitInputKind::kObj);
  EXPECT_TRUE(problem.empty()) << problem;
  EXPECT_EQ(fitUsageProblem(o), "");
  o.bind = "rest.obj";
  o.rig = "auto";
  o.bones = 4;
  EXPECT_EQ(fitUsageProblem(o), "");
  o.rig = "curves";
  o.bones = 0;
  o.up = "-z";
  EXPECT_EQ(fitUsageProblem(o), "");
  o = objFit();
  o.rig = "skeleton.tgf";
  o.bind = "rest.obj";
  o.weights = "w.dmat";
  o.transforms = {"1.Tmat", "2.Tmat", "3.Tmat"};
  EXPECT_EQ(fitInputKind(o, &problem), FitInputKind::kLibigl);
  EXPECT_EQ(fitUsageProblem(o), "");
  o = FitCommandOptions{};
  o.inputs = {"walk.glb"};
  o.output = "walk.odsk";
  o.times = {0.0, 0.5};
  o.animation = "Walk";
  EXPECT_EQ(fitInputKind(o, &problem), FitInputKind::kGltf);
  EXPECT_EQ(fitUsageProblem(o), "");
  o.times.clear();
  o.targets = {0, 1};
  EXPECT_EQ(fitUsageProblem(o), "");
}

TEST(FitOptions, UsageProblems) {
  struct Case {
    std::function<void(FitCommandOptions&)> change;
    std::string message;
  };
  const Case cases[] = {
      {[](FitCommandOptions& o) { o.inputs.clear(); }, "no example poses"},
      {[](FitCommandOptions& o) { o.inputs.resize(1); }, "at least 2 example poses, got 1"},
      {[](FitCommandOptions& o) { o.output.clear(); }, "-o ASSET is required"},
      {[](FitCommandOptions& o) { o.terms = 0; }, "--terms 0 is outside 1..64"},
      {[](FitCommandOptions& o) { o.terms = 65; }, "--terms 65 is outside 1..64"},
      {[](FitCommandOptions& o) { o.key_tolerance = -1e-3; }, "--key-tolerance"},
      {[](FitCommandOptions& o) { o.key_tolerance = 0.0; }, "--key-tolerance must be a positive fraction of the box, got 0"},
      {[](FitCommandOptions& o) { o.segment_seconds = 0.0; }, "--segment-seconds must be positive"},
      {[](FitCommandOptions& o) { o.segment_seconds = 1e-320; }, "--segment-seconds 9.99989e-321 is outside [0.0001, 1e+06]"},
      {[](FitCommandOptions& o) { o.segment_seconds = 1e300; }, "--segment-seconds 1e+300 is outside"},
      {[](FitCommandOptions& o) { o.key_tolerance = 1e-320; }, "--key-tolerance 9.99989e-321 is outside [1e-12, 0.1] of the box"},
      {[](FitCommandOptions& o) { o.key_tolerance = 2.0; }, "--key-tolerance 2 is outside"},
      {[](FitCommandOptions& o) { o.output = "d.obj"; }, "-o d.obj: the asset is written as .odsk"},
      {[](FitCommandOptions& o) { o.bones = -2; }, "--bones must be >= 0"},
      {[](FitCommandOptions& o) { o.material = "rubber"; }, "--material: material 'rubber'"},
      {[](FitCommandOptions& o) {
         o.material = "static";
         o.materials_json = "parts.json";
       },
       "not both"},
      {[](FitCommandOptions& o) { o.rig = "skeleton.bvh"; }, "--rig takes auto or a libigl skeleton"},
      {[](FitCommandOptions& o) { o.rig = "skeleton.tgf"; }, "needs --bind REST.obj"},
      {[](FitCommandOptions& o) {
         o.rig = "skeleton.tgf";
         o.bind = "rest.obj";
         o.transforms = {"1.Tmat"};
       },
       "1 --transforms files for 3 poses"},
      {[](FitCommandOptions& o) {
         o.rig = "skeleton.tgf";
         o.bones = 3;
       },
       "--bones applies to the automatic rig"},
      {[](FitCommandOptions& o) { o.weights = "w.dmat"; }, "need --rig SKELETON.tgf"},
      {[](FitCommandOptions& o) { o.up = "-z"; }, "--up applies to --rig curves"},
      {[](FitCommandOptions& o) {
         o.rig = "curves";
         o.up = "w";
       },
       "--up 'w' must be x, y, z, -x, -y or -z"},
      {[](FitCommandOptions& o) { o.times = {0.5}; }, "apply to a .gltf/.glb input"},
      {[](FitCommandOptions& o) { o.inputs.push_back("d.ply"); }, "d.ply: unknown input format '.ply'"},
      {[](FitCommandOptions& o) { o.inputs.push_back("walk.glb"); }, "not both or several"},
      {[](FitCommandOptions& o) { o.inputs = {"walk.gltf"}; }, "needs --times a,b,... or --targets"},
      {[](FitCommandOptions& o) {
         o.inputs = {"walk.gltf"};
         o.times = {1.0};
         o.bind = "rest.obj";
       },
       "--bind applies to OBJ poses"},
      {[](FitCommandOptions& o) {
         o.inputs = {"walk.glb"};
         o.targets = {0};
         o.rig = "skeleton.tgf";
       },
       "a glTF file brings its own skin"},
      {[](FitCommandOptions& o) {
         o.inputs = {"walk.glb"};
         o.times = {1.0};
         o.weights = "w.dmat";
       },
       "--weights and --transforms apply to OBJ poses with --rig SKELETON.tgf"},
      {[](FitCommandOptions& o) {
         o.inputs = {"walk.glb"};
         o.times = {1.0};
         o.transforms = {"1.Tmat"};
       },
       "--weights and --transforms apply to OBJ poses"},
  };
  for (const Case& c : cases) {
    FitCommandOptions o = objFit();
    c.change(o);
    const std::string problem = fitUsageProblem(o);
    EXPECT_EQ(problem.rfind("fit: ", 0), 0u) << c.message << ": " << problem;
    EXPECT_NE(problem.find(c.message), std::string::npos) << problem;
  }
  FitCommandOptions o = objFit();
  EXPECT_EQ(fitMaterialText(o), "skin");
  o.material = "1,2,3,4";
  EXPECT_EQ(fitMaterialText(o), "1,2,3,4");
}

TEST(Progress, SilentWhenDisabledRedrawnInPlaceWhenEnabled) {
  std::ostringstream quiet;
  {
    ProgressBar bar(quiet, "play", 10, false);
    for (std::size_t i = 1; i <= 10; ++i) bar.step(i);
    bar.fraction("fit", 0.5);
  }
  EXPECT_TRUE(quiet.str().empty());

  std::ostringstream shown;
  ProgressBar bar(shown, "play", 4, true);
  bar.step(1);
  const std::string first = shown.str();
  EXPECT_EQ(first.rfind("\rplay [", 0), 0u) << first;
  EXPECT_NE(first.find("1/4"), std::string::npos) << first;
  EXPECT_NE(first.find("ETA"), std::string::npos) << first;
  bar.step(4);  // the last step always draws
  EXPECT_NE(shown.str().find("4/4"), std::string::npos) << shown.str();
  EXPECT_EQ(shown.str().find('\n'), std::string::npos);  // never scrolls
  bar.finish();
  EXPECT_EQ(shown.str().back(), '\r');
  bar.fraction("curves", 0.25);
  EXPECT_NE(shown.str().find("curves ["), std::string::npos);
  EXPECT_NE(shown.str().find(" 25%"), std::string::npos) << shown.str();
}

TEST(Progress, Durations) {
  EXPECT_EQ(formatDuration(1.5), "1.5 s");
  EXPECT_EQ(formatDuration(125.0), "2 min 05 s");
  EXPECT_EQ(formatDuration(3725.0), "1 h 02 min");
  EXPECT_EQ(formatDuration(-1.0), "?");
}

}  // namespace
}  // namespace odeskin

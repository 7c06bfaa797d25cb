// SPDX-License-Identifier: MIT
// The benchmark harness's parts: tiling keeps every vertex's deformation, subdivision keeps the poses
// one mesh, the timer returns medians and failures, the reports keep the issue's JSON layout, and
// the cases verify every backend (Vulkan under the validation layer) before timing it.
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/harness/bench_plot.hpp"
#include "bench/harness/bench_report.hpp"
#include "bench/harness/deform_cases.hpp"
#include "scratch_dir.hpp"  // tests/
#include "bench/harness/device_bandwidth.hpp"
#include "bench/harness/frame_timer.hpp"
#include "bench/harness/frame_traffic.hpp"
#include "bench/harness/subdivided_examples.hpp"
#include "bench/harness/tiled_asset.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "host/gpu_test_support.hpp"

namespace odeskin::bench {
namespace {

namespace fs = std::filesystem;

// The procedural arm (two poses, one segment), small enough to fit in milliseconds.
DeformAsset armAsset(int modes) {
  ArmOptions arm_options;
  arm_options.rings = 9;
  Result<ProceduralArm> arm = makeProceduralArm(arm_options);
  EXPECT_TRUE(arm.ok()) << arm.status().toString();
  FitOptions options;
  options.modes = modes;
  options.materials = {skinMaterial()};
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, options);
  EXPECT_TRUE(asset.ok()) << asset.status().toString();
  return std::move(asset).value();
}

std::vector<Vec3> play(const DeformAsset& asset, double t) {
  Result<DeformPlayer> player = DeformPlayer::create(asset);
  EXPECT_TRUE(player.ok());
  const auto [segment, tau] = player->locate(t);
  std::vector<Vec3> out(asset.vertexCount());
  EXPECT_TRUE(player->play(asset, segment, tau, out).ok());
  return out;
}

TEST(TileDeformAsset, EveryTiledVertexDeformsExactlyAsItsSource) {
  const DeformAsset source = armAsset(5);
  const std::size_t v = source.vertexCount();
  for (std::size_t count : {std::size_t{7}, v, 3 * v + 5}) {
    Result<DeformAsset> tiled = tileDeformAsset(source, count);
    ASSERT_TRUE(tiled.ok()) << tiled.status().toString();
    ASSERT_EQ(tiled->vertexCount(), count);
    EXPECT_TRUE(validateDeformAsset(*tiled).ok());
    const std::vector<Vec3> expected = play(source, 0.37);
    const std::vector<Vec3> actual = play(*tiled, 0.37);
    for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(actual[i], expected[i % v]) << "vertex " << i;
  }
}

TEST(TileDeformAsset, RejectsEmptyInputs) {
  EXPECT_EQ(tileDeformAsset(DeformAsset{}, 10).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(tileDeformAsset(armAsset(3), 0).status().code(), StatusCode::kInvalidArgument);
}

TEST(SubdivideMidpoint, SplitsEveryTriangleInFourInEveryPose) {
  ExampleSet ex;
  ex.rest_positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  ex.faces.indices = {0, 1, 2, 2, 1, 3};
  ex.faces.face_offsets = {0, 3, 6};
  ex.poses = {ex.rest_positions, {{0, 0, 1}, {2, 0, 1}, {0, 2, 1}, {2, 2, 1}}};
  Rig rig;
  rig.skeleton.heads = rig.skeleton.tails = {{0, 0, 0}, {1, 1, 0}};
  rig.skeleton.parents = {-1, 0};
  rig.skeleton.names = {"a", "b"};
  rig.influences.offsets = {0, 1, 2, 3, 4};
  rig.influences.bones = {0, 0, 1, 1};
  rig.influences.weights = {1, 1, 1, 1};
  ex.rig = rig;
  Result<ExampleSet> out = subdivideMidpoint(ex);
  ASSERT_TRUE(out.ok()) << out.status().toString();
  EXPECT_EQ(out->rest_positions.size(), 4u + 5u);  // five edges
  EXPECT_EQ(out->faces.faceCount(), 8u);
  ASSERT_EQ(out->poses.size(), 2u);
  // Vertex 4 is the first new edge's midpoint (edge 0-1) in every pose.
  EXPECT_EQ(out->rest_positions[4], Vec3(0.5, 0, 0));
  EXPECT_EQ(out->poses[1][4], Vec3(1, 0, 1));
  const Influences& w = out->rig->influences;
  ASSERT_EQ(w.vertexCount(), 9u);
  EXPECT_TRUE(validateInfluences(w, 9, 2).ok());
  // Edge 1-2 joins a bone-0 vertex and a bone-1 vertex: half each.
  for (std::size_t i = 4; i < 9; ++i) {
    double sum = 0.0;
    for (std::uint32_t k = w.offsets[i]; k < w.offsets[i + 1]; ++k) sum += w.weights[k];
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
}

TEST(SubdivideMidpoint, RejectsPolygons) {
  ExampleSet ex;
  ex.rest_positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  ex.faces.indices = {0, 1, 2, 3};
  ex.faces.face_offsets = {0, 4};
  const Result<ExampleSet> out = subdivideMidpoint(ex);
  EXPECT_EQ(out.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(out.status().message().find("face 0 is not a triangle"), std::string::npos);
}

TEST(TimeFrames, ReturnsTheMedianAndStopsOnFailure) {
  int calls = 0;
  Result<FrameTiming> t = timeFrames([&](double& gpu) {
    ++calls;
    gpu = 2.0;
    return okStatus();
  }, 0.0, 5);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->frames, 5);
  EXPECT_EQ(calls, 6);  // one warm-up frame
  EXPECT_EQ(t->gpu_seconds, 2.0);
  calls = 0;
  Result<FrameTiming> failed = timeFrames([&](double&) { return ++calls == 3 ? internalError("frame 3") : okStatus(); },
                                          1.0);
  EXPECT_EQ(failed.status().message(), "frame 3");
}

// A GPU case is warmed up for a time, not a frame count: its clocks take that long to rise.
TEST(TimeFrames, WarmsUpForTheGivenTimeBeforeTiming) {
  int calls = 0;
  const auto start = std::chrono::steady_clock::now();
  Result<FrameTiming> t = timeFrames([&](double&) {
    ++calls;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    return okStatus();
  }, 0.0, 3, 100000, 0.05);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->frames, 3);
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.05);
  EXPECT_GT(calls - 3, 1);  // 50 ms of 2 ms frames: the warm-up ran several, not the one it used to
}

// Busy for `seconds` of steady-clock time (a sleep could oversleep by more than a short frame).
void spin(double seconds) {
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds) {
  }
}

TEST(TimePairedFrames, AlternatesTheOrderAndTakesTheMedianRatio) {
  std::string order;
  Result<PairedTiming> t = timePairedFrames(
      [&](double& gpu) {
        order += 'a';
        gpu = 3.0;
        spin(2e-3);
        return okStatus();
      },
      [&](double& gpu) {
        order += 'b';
        gpu = 1.5;
        spin(1e-3);
        return okStatus();
      },
      0.0, 9);
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->pairs, 9);
  EXPECT_EQ(order.substr(0, 8), "ab" "ab" "ba" "ab");  // the warm-up pair, then pairs 1, 2, 3
  EXPECT_EQ(t->gpu_ratio, 2.0);
  // 2 ms against 1 ms of spinning; a preempted pair moves its own ratio, not the median.
  EXPECT_NEAR(t->ratio, 2.0, 0.25);
}

TEST(TimePairedFrames, NeedsBothGpuTimesAndStopsOnFailure) {
  Result<PairedTiming> cpu = timePairedFrames([](double&) { return okStatus(); },
                                              [](double& gpu) {
                                                gpu = 1.0;
                                                return okStatus();
                                              },
                                              0.0, 3);
  ASSERT_TRUE(cpu.ok());
  EXPECT_EQ(cpu->gpu_ratio, 0.0);  // `a` reports no GPU time
  int calls = 0;
  Result<PairedTiming> failed = timePairedFrames([](double&) { return okStatus(); },
                                                 [&](double&) { return ++calls == 4 ? internalError("frame 4") : okStatus(); },
                                                 1.0);
  EXPECT_EQ(failed.status().message(), "frame 4");
}

BenchReport sampleReport() {
  BenchReport r;
  r.device = "test device";
  r.records.push_back({"odeskin", "cpu_fast", 1, 1000, 9, 3e-3, 0.0, 0.0, 10, 1e-7});
  r.records.push_back({"lbs", "cpu_fast", 1, 1000, 0, 1e-3, 0.0, 0.0, 10, 1e-7});
  r.records.push_back({"odeskin", "vulkan", 1, 1000, 9, 4e-3, 3e-3, 0.1, 10, 1e-7, 2e5});
  return r;
}

TEST(BenchReport, JsonKeepsTheIssueLayout) {
  const nlohmann::json j = nlohmann::json::parse(toJson(sampleReport()));
  EXPECT_EQ(j["device"], "test device");
  EXPECT_EQ(j["validation"], false);
  EXPECT_FALSE(j.contains("shader_inputs"));  // no Vulkan device in this report
  ASSERT_EQ(j["records"].size(), 3u);
  for (const auto& r : j["records"]) {
    for (const char* key : {"case", "backend", "threads", "vertices", "terms", "seconds_per_frame", "vertices_per_second"}) {
      EXPECT_TRUE(r.contains(key)) << key;
    }
  }
  EXPECT_DOUBLE_EQ(j["records"][0]["vertices_per_second"].get<double>(), 1000 / 3e-3);
  EXPECT_DOUBLE_EQ(j["records"][0]["odeskin_over_lbs"].get<double>(), 3.0);
  EXPECT_FALSE(j["records"][2].contains("odeskin_over_lbs"));  // no vulkan lbs record
  EXPECT_DOUBLE_EQ(j["records"][2]["gpu_seconds_per_frame"].get<double>(), 3e-3);
  EXPECT_DOUBLE_EQ(j["records"][2]["bytes_per_frame"].get<double>(), 2e5);
  EXPECT_DOUBLE_EQ(j["records"][2]["bytes_per_second"].get<double>(), 2e5 / 4e-3);
  EXPECT_EQ(j["device_copy"]["note"], "");  // not measured in this report
  const std::string csv = toCsv(sampleReport());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_EQ(csv.rfind("case,backend,threads,vertices,terms,seconds_per_frame,vertices_per_second", 0), 0u);
}

// A real GPU's wall time at small sizes is mostly submit-and-wait latency, so the report also gives
// the ratio of the timestamp-query times, and only where both records have one.
TEST(BenchReport, GpuRatioComesFromTheTimestampTimes) {
  BenchReport r = sampleReport();
  r.shader_inputs = "storage buffers";
  r.records.push_back({"lbs", "vulkan", 1, 1000, 0, 3.5e-3, 1e-3, 0.1, 10, 1e-7, 1e5});
  const nlohmann::json j = nlohmann::json::parse(toJson(r));
  EXPECT_EQ(j["shader_inputs"], "storage buffers");
  EXPECT_DOUBLE_EQ(j["records"][2]["odeskin_over_lbs"].get<double>(), 4e-3 / 3.5e-3);
  EXPECT_DOUBLE_EQ(j["records"][2]["gpu_odeskin_over_lbs"].get<double>(), 3.0);
  EXPECT_FALSE(j["records"][0].contains("gpu_odeskin_over_lbs"));  // cpu_fast has no GPU time
  const std::string csv = toCsv(r);
  EXPECT_NE(csv.find(",gpu_odeskin_over_lbs,paired_odeskin_over_lbs,paired_gpu_odeskin_over_lbs\n"), std::string::npos);
  EXPECT_NE(csv.find(",200000,50000000,3,,\n"), std::string::npos);  // the vulkan odeskin line's GPU ratio, no pairing
}

// The frame-against-frame ratios are the odeskin record's own, written only where measured.
TEST(BenchReport, PairedRatiosAreWrittenWhereMeasured) {
  BenchReport r = sampleReport();
  r.records[0].paired_over_lbs = 2.25;
  r.records[2].paired_over_lbs = 1.5;
  r.records[2].paired_gpu_over_lbs = 2.5;
  const nlohmann::json j = nlohmann::json::parse(toJson(r));
  EXPECT_DOUBLE_EQ(j["records"][0]["paired_odeskin_over_lbs"].get<double>(), 2.25);
  EXPECT_DOUBLE_EQ(j["records"][0]["odeskin_over_lbs"].get<double>(), 3.0);  // the separate cases' ratio stays
  EXPECT_FALSE(j["records"][0].contains("paired_gpu_odeskin_over_lbs"));
  EXPECT_FALSE(j["records"][1].contains("paired_odeskin_over_lbs"));  // lbs
  EXPECT_DOUBLE_EQ(j["records"][2]["paired_gpu_odeskin_over_lbs"].get<double>(), 2.5);
  const std::string csv = toCsv(r);
  EXPECT_NE(csv.find(",0,2.25,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",1.5,2.5\n"), std::string::npos) << csv;
}

TEST(BenchPlot, WritesAPngAndRefusesAnEmptyReport) {
  const fs::path dir = odeskin::testing::scratchDir("bench_plot");
  ASSERT_TRUE(writePlot(dir / "plot.png", sampleReport()).ok());
  std::ifstream in(dir / "plot.png", std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  EXPECT_EQ(writePlot(dir / "empty.png", BenchReport{}).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  fs::remove_all(dir);
}

TEST(BenchPlot, FitPlotDrawsTheSubdividedSeriesOnly) {
  const fs::path dir = odeskin::testing::scratchDir("fit_plot");
  BenchReport report;
  report.cpu = "test cpu";
  FitStageRecord other;
  other.dataset = "cat-poses 00-01";
  other.vertices = 7207;
  other.curve_identification = 0.01;
  report.fit_stages.push_back(other);
  EXPECT_EQ(writeFitPlot(dir / "none.png", report).code(), StatusCode::kInvalidArgument);  // no scaling series
  EXPECT_FALSE(fs::exists(dir / "none.png"));
  for (int level = 0; level < 3; ++level) {
    FitStageRecord f;
    f.dataset = "cat-poses 00-01, given rig, subdivided x" + std::to_string(level);
    f.vertices = 7207u << (2 * level);
    f.curve_identification = 0.005 * (1 << (2 * level));
    f.geometric_transform = 0.0005 * (1 << (2 * level));
    f.fourier_and_deformation = 0.002 * (1 << (2 * level));
    f.analytic_solve = 0.001 * (1 << (2 * level));
    report.fit_stages.push_back(f);
  }
  ASSERT_TRUE(writeFitPlot(dir / "fit.png", report).ok());
  std::ifstream in(dir / "fit.png", std::ios::binary);
  char signature[8] = {};
  in.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  fs::remove_all(dir);
}

// A hand-sized asset: 3 vertices in 4 slots, 2 bones, 1 curve of N = 1 (M = 4), 2 segments with
// rates, 1 material; segment 1 gives vertex 2 a remainder.
PackedDeformData smallPacked() {
  PackedDeformData d;
  d.vertex_count = 3;
  d.modes = 1;
  d.curve_count = 1;
  d.material_count = 1;
  d.bone_count = 2;
  d.segment_count = 2;
  d.influence_layout = 4;
  d.rest_positions.resize(3);
  d.bindings.resize(3);
  d.segment_vertices.assign(6, gpu::SegmentVertex{0, 0, 0, gpu::kNoRemainder});
  d.segment_vertices[5].remainder_index = 0;
  d.remainders.resize(1);
  d.remainder_base = {0, 0};
  d.curve_materials = {0};
  d.coefficients.resize(8);
  d.rates.resize(8);
  d.influences.resize(12);
  return d;
}

TEST(FrameTraffic, CountsEachArrayOfTheFrameOnce) {
  PackedDeformData d = smallPacked();
  // Skinning: rest in and positions out (2 x 3 x 16), 12 influences x 8, 2 bones x 48.
  const std::size_t skin = 96 + 96 + 96;
  EXPECT_EQ(frameBytes(d, 0, false), skin);
  // odeskin adds bindings and the segment's correctives (3 x 32), the segment's coefficients and
  // rates (2 x 4 x 16), one material (4) and 1 x (N + 1) + 1 = 3 basis entries (3 x 8).
  const std::size_t deform = skin + 96 + 128 + 4 + 24;
  EXPECT_EQ(frameBytes(d, 0, true), deform);
  EXPECT_EQ(frameBytes(d, 1, true), deform + 16);  // vertex 2's remainder in segment 1
  d.rates.clear();
  EXPECT_EQ(frameBytes(d, 0, true), deform - 64);
  d.skinning = SkinningMode::kDualQuaternion;  // the bones' dual quaternions too
  EXPECT_EQ(frameBytes(d, 0, false), skin + 64);
  d.influence_layout = ODESKIN_INFLUENCES_SPARSE;
  d.influences.resize(5);
  d.influence_offsets = {0, 2, 3, 5};
  EXPECT_EQ(frameBytes(d, 0, false), 96 + 40 + 16 + 96 + 64);
}

class DeformCases : public testing::GpuTest {};

// A probe's result: `bytes` copied at a finite rate above 1 MB/s.
void expectCopyRate(const Result<CopyBandwidth>& copy, VkDeviceSize bytes) {
  ASSERT_TRUE(copy.ok()) << copy.status().toString();
  EXPECT_EQ(copy->bytes, bytes);
  EXPECT_GT(copy->bytes_per_second, 1e6);
  EXPECT_TRUE(std::isfinite(copy->bytes_per_second));
}

TEST_F(DeformCases, TheDeviceCopyRateIsMeasured) {
  expectCopyRate(deviceCopyBandwidth(device(), VkDeviceSize{4} << 20, 3), VkDeviceSize{4} << 20);
  EXPECT_EQ(deviceCopyBandwidth(device(), 0).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(deviceCopyBandwidth(device(), 16, 0).status().code(), StatusCode::kInvalidArgument);
}

// The shader copy (copy_probe.comp) moves its bytes, and refuses sizes it cannot copy whole.
TEST_F(DeformCases, TheShaderCopyRateIsMeasured) {
  expectCopyRate(shaderCopyBandwidth(device(), VkDeviceSize{1} << 20, 2), VkDeviceSize{1} << 20);
  EXPECT_EQ(shaderCopyBandwidth(device(), 24).status().code(), StatusCode::kInvalidArgument);
  const VkDeviceSize too_big = VkDeviceSize{device().limits().maxStorageBufferRange} + 16;
  EXPECT_EQ(shaderCopyBandwidth(device(), too_big).status().code(), StatusCode::kInvalidArgument);
}

TEST_F(DeformCases, VerifiesAndTimesEveryBackendAndKernel) {
  std::map<int, DeformAsset> sources;
  sources[3] = armAsset(3);
  sources[5] = armAsset(5);
  DeformCaseOptions options;
  options.sizes = {500, 2500};
  options.terms = {3, 5};
  options.all_threads = 2;
  options.min_seconds = 0.0;
  options.time = 0.6;
  options.vulkan = device_.has_value();
  options.device = device_ ? &device() : nullptr;
  std::vector<BenchRecord> records;
  const Status status = runDeformCases(sources, options, records);
  ASSERT_TRUE(status.ok()) << status.toString();
  // Per size: odeskin for each N, then lbs and dqs, each on cpu_ref, cpu_fast 1 and 2 threads (+ vulkan).
  const std::size_t backends = options.vulkan ? 4 : 3;
  EXPECT_EQ(records.size(), std::size_t{2} * (2 + 2) * backends);
  for (const BenchRecord& r : records) {
    EXPECT_GT(r.seconds_per_frame, 0.0) << r.kernel << " " << r.backend;
    EXPECT_LE(r.max_error, kVerifyTolerance) << r.kernel << " " << r.backend;
    EXPECT_EQ(r.terms == 0, r.kernel != "odeskin");
    EXPECT_GE(r.frames, 3);
    // At least the positions in and out, and never more than a few hundred bytes per vertex.
    EXPECT_GE(r.bytes_per_frame, 32.0 * static_cast<double>(r.vertices));
    EXPECT_LE(r.bytes_per_frame, 1000.0 * static_cast<double>(r.vertices));
    if (r.backend == "vulkan") {
      EXPECT_GT(r.gpu_seconds_per_frame, 0.0);
    }
    // odeskin on the timed fast paths is also paired with LBS frame against frame.
    const bool paired = r.kernel == "odeskin" && r.backend != "cpu_ref";
    EXPECT_EQ(r.paired_over_lbs > 0.0, paired) << r.kernel << " " << r.backend;
    EXPECT_EQ(r.paired_gpu_over_lbs > 0.0, paired && r.backend == "vulkan") << r.kernel << " " << r.backend;
  }
}

TEST(DeformCasesOptions, RejectsMissingSourcesAndDevices) {
  std::map<int, DeformAsset> sources;
  sources[3] = armAsset(3);
  std::vector<BenchRecord> records;
  DeformCaseOptions options;
  options.sizes = {100};
  options.terms = {9};
  options.vulkan = false;
  EXPECT_EQ(runDeformCases(sources, options, records).code(), StatusCode::kInvalidArgument);
  options.terms = {3};
  options.vulkan = true;
  EXPECT_EQ(runDeformCases(sources, options, records).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(records.empty());
}

}  // namespace
}  // namespace odeskin::bench

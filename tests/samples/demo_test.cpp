// SPDX-License-Identifier: MIT
// `odeskin demo` end to end: the files it writes reproduce the example poses at the first and last
// frame, and the CPU and Vulkan backends write the same frames.
#include "samples/odeskin/demo.hpp"

#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>

#include <gtest/gtest.h>

#include "host/gpu_test_support.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

constexpr double kEndTolerance = 1e-5;  // of the longest bounding-box side

std::vector<Vec3> readObjVertices(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<Vec3> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream fields(line.substr(2));
    Vec3 p;
    fields >> p.x >> p.y >> p.z;
    out.push_back(p);
  }
  return out;
}

double maxError(std::span<const Vec3> a, std::span<const Vec3> b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
  return worst;
}

std::filesystem::path scratch(const std::string& name) {
  // The demo makes the folder itself.
  std::filesystem::path dir = odeskin::testing::processScratchRoot() / ("demo_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

DemoResult runOrFail(const DemoOptions& options) {
  std::ostringstream log;
  Result<DemoResult> result = runDemo(options, log);
  EXPECT_TRUE(result.ok()) << result.status().toString() << "\n" << log.str();
  return result.ok() ? std::move(result).value() : DemoResult{};
}

TEST(Demo, WrittenFilesReproduceTheExamplePoses) {
  DemoOptions options;
  options.output_dir = scratch("cpu");
  options.frames = 7;
  options.backend = Backend::kCpu;
  const DemoResult result = runOrFail(options);
  const auto start = readObjVertices(options.output_dir / "start.obj");
  const auto end = readObjVertices(options.output_dir / "end.obj");
  const auto first = readObjVertices(options.output_dir / "frame_0000.obj");
  const auto last = readObjVertices(options.output_dir / "frame_0006.obj");
  ASSERT_FALSE(start.empty());
  EXPECT_TRUE(std::filesystem::exists(options.output_dir / "frame_0003.obj"));
  EXPECT_FALSE(std::filesystem::exists(options.output_dir / "frame_0007.obj"));
  EXPECT_LE(maxError(first, start), kEndTolerance * result.box_side);
  EXPECT_LE(maxError(last, end), kEndTolerance * result.box_side);
  // The in-betweens really move: the middle frame is neither pose.
  const auto middle = readObjVertices(options.output_dir / "frame_0003.obj");
  EXPECT_GT(maxError(middle, start), 0.05 * result.box_side);
  EXPECT_GT(maxError(middle, end), 0.05 * result.box_side);
}

TEST(Demo, RejectsTooFewFramesAndUnknownMaterial) {
  std::ostringstream log;
  DemoOptions options;
  options.output_dir.clear();
  options.frames = 1;
  EXPECT_EQ(runDemo(options, log).status().code(), StatusCode::kInvalidArgument);
  options.frames = 3;
  options.material = "rubber";
  EXPECT_EQ(runDemo(options, log).status().code(), StatusCode::kInvalidArgument);
}

class DemoOnGpu : public testing::GpuTest {};

TEST_F(DemoOnGpu, CpuAndVulkanFramesAgree) {
  DemoOptions options;
  options.output_dir.clear();
  options.frames = 6;
  options.validation = true;
  options.backend = Backend::kCpu;
  const DemoResult cpu = runOrFail(options);
  options.backend = Backend::kVulkan;
  const DemoResult gpu = runOrFail(options);
  ASSERT_EQ(cpu.frames.size(), gpu.frames.size());
  EXPECT_NE(gpu.device.find("vulkan"), std::string::npos) << gpu.device;
  for (std::size_t f = 0; f < cpu.frames.size(); ++f) {
    EXPECT_LE(maxError(cpu.frames[f], gpu.frames[f]), kEndTolerance * cpu.box_side) << "frame " << f;
  }
  EXPECT_LE(gpu.last_frame_error, kEndTolerance);
  EXPECT_GT(gpu.mean_gpu_seconds, 0.0);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin demo`: fit the procedural arm's two poses and play the in-betweens on the CPU or on
// Vulkan, writing start.obj, end.obj and one OBJ per frame. The README's main job at this stage.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "engine/core/result.hpp"
#include "engine/core/types.hpp"

namespace odeskin {

enum class Backend { kAuto, kCpu, kVulkan };

struct DemoOptions {
  std::filesystem::path output_dir = "odeskin-demo";  // empty: write nothing
  int frames = 30;                 // >= 2: frame 0 at t = 0, the last at t = 1
  Backend backend = Backend::kAuto;
  std::string device = "auto";     // Vulkan device selector (index or name substring)
  int modes = 9;                   // N
  std::string material = "skin";   // skin | static
  ResidualSpace residual_space = ResidualSpace::kBind;
  unsigned threads = 0;            // CPU worker threads, 0 = all
  bool validation = false;         // Khronos validation layer (when installed)
  std::filesystem::path asset_path;  // non-empty: also save the fitted arm as a .odsk asset there
};

struct DemoResult {
  std::string device;              // "cpu (N threads)" or the Vulkan device name
  std::vector<std::vector<Vec3>> frames;
  std::vector<Vec3> start_positions;
  std::vector<Vec3> end_positions;
  double box_side = 0.0;           // longest bounding-box side of the end pose
  double first_frame_error = 0.0;  // max |frame 0 - start| / box_side
  double last_frame_error = 0.0;   // max |last frame - end| / box_side
  double mean_frame_seconds = 0.0; // wall time per frame (deformation only, no file writing)
  double mean_gpu_seconds = 0.0;   // timestamp-query time per frame (Vulkan only)
};

// Runs the demo, printing progress to `log`. Errors: kInvalidArgument (frames < 2, unknown
// material), kUnavailable (Vulkan requested but no device), fit and I/O errors naming the file.
Result<DemoResult> runDemo(const DemoOptions& options, std::ostream& log);

}  // namespace odeskin

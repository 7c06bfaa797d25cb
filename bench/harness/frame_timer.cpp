// SPDX-License-Identifier: MIT
#include "frame_timer.hpp"

#include <algorithm>
#include <vector>

#include "engine/core/result.hpp"

namespace odeskin::bench {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid)));
}

}  // namespace

Result<FrameTiming> timeFrames(const FrameBody& body, double min_seconds, int min_frames, int max_frames,
                               double warmup_seconds) {
  using Clock = std::chrono::steady_clock;
  double gpu = 0.0;
  // Warm-up: caches, lazy driver work, page faults of the output, and a GPU's clocks.
  const Clock::time_point warmup = Clock::now();
  do {
    ODESKIN_TRY(body(gpu));
  } while (std::chrono::duration<double>(Clock::now() - warmup).count() < warmup_seconds);
  std::vector<double> wall;
  std::vector<double> gpu_times;
  double total = 0.0;
  while (static_cast<int>(wall.size()) < max_frames &&
         (total < min_seconds || static_cast<int>(wall.size()) < min_frames)) {
    gpu = 0.0;
    const Clock::time_point start = Clock::now();
    ODESKIN_TRY(body(gpu));
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    wall.push_back(seconds);
    gpu_times.push_back(gpu);
    total += seconds;
  }
  FrameTiming timing;
  timing.frames = static_cast<int>(wall.size());
  timing.seconds = median(std::move(wall));
  timing.gpu_seconds = median(std::move(gpu_times));
  return timing;
}

}  // namespace odeskin::bench

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

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// One frame of `body`: its wall time into `seconds`, the GPU time it reports into `gpu_seconds`.
Status timeFrame(const FrameBody& body, double& seconds, double& gpu_seconds) {
  gpu_seconds = 0.0;
  const Clock::time_point start = Clock::now();
  ODESKIN_TRY(body(gpu_seconds));
  seconds = secondsSince(start);
  return okStatus();
}

}  // namespace

Result<PairedTiming> timePairedFrames(const FrameBody& a, const FrameBody& b, double min_seconds, int min_pairs,
                                      int max_pairs, double warmup_seconds) {
  double gpu = 0.0;
  const Clock::time_point warmup = Clock::now();
  do {
    ODESKIN_TRY(a(gpu));
    ODESKIN_TRY(b(gpu));
  } while (secondsSince(warmup) < warmup_seconds);
  std::vector<double> ratios;
  std::vector<double> gpu_ratios;
  bool every_gpu = true;
  int pairs = 0;
  double total = 0.0;
  while (pairs < max_pairs && (total < min_seconds || pairs < min_pairs)) {
    double a_seconds = 0.0, b_seconds = 0.0, a_gpu = 0.0, b_gpu = 0.0;
    if (pairs % 2 == 0) {
      ODESKIN_TRY(timeFrame(a, a_seconds, a_gpu));
      ODESKIN_TRY(timeFrame(b, b_seconds, b_gpu));
    } else {
      ODESKIN_TRY(timeFrame(b, b_seconds, b_gpu));
      ODESKIN_TRY(timeFrame(a, a_seconds, a_gpu));
    }
    ++pairs;
    total += a_seconds + b_seconds;
    // A clock too coarse for an empty frame can read 0: such a pair gives no ratio.
    if (b_seconds > 0.0) ratios.push_back(a_seconds / b_seconds);
    every_gpu = every_gpu && a_gpu > 0.0 && b_gpu > 0.0;
    if (every_gpu) gpu_ratios.push_back(a_gpu / b_gpu);
  }
  PairedTiming timing;
  timing.pairs = pairs;
  timing.ratio = median(std::move(ratios));
  timing.gpu_ratio = every_gpu ? median(std::move(gpu_ratios)) : 0.0;
  return timing;
}

Result<FrameTiming> timeFrames(const FrameBody& body, double min_seconds, int min_frames, int max_frames,
                               double warmup_seconds) {
  double gpu = 0.0;
  // Warm-up: caches, lazy driver work, page faults of the output, and a GPU's clocks.
  const Clock::time_point warmup = Clock::now();
  do {
    ODESKIN_TRY(body(gpu));
  } while (secondsSince(warmup) < warmup_seconds);
  std::vector<double> wall;
  std::vector<double> gpu_times;
  double total = 0.0;
  while (static_cast<int>(wall.size()) < max_frames &&
         (total < min_seconds || static_cast<int>(wall.size()) < min_frames)) {
    double seconds = 0.0;
    ODESKIN_TRY(timeFrame(body, seconds, gpu));
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

// SPDX-License-Identifier: MIT
// Per-frame timing for the harness: every frame is timed on its own and the median is reported,
// because the machines are shared and a mean takes in every hiccup of the neighbours.
#pragma once

#include <chrono>
#include <functional>

#include "engine/core/result.hpp"

namespace odeskin::bench {

struct FrameTiming {
  double seconds = 0.0;      // median wall time of one frame
  double gpu_seconds = 0.0;  // median GPU time (timestamp queries) where the frame reports one, else 0
  int frames = 0;            // frames timed (after the untimed warm-up)
};

// One frame: returns its status and may set `gpu_seconds`.
using FrameBody = std::function<Status(double& gpu_seconds)>;

// Runs `body` untimed once and until `warmup_seconds` have passed, then until `min_seconds` of
// frames have run and at least `min_frames` frames are timed (at most `max_frames`). The first
// failing frame's status is returned.
Result<FrameTiming> timeFrames(const FrameBody& body, double min_seconds, int min_frames = 3, int max_frames = 100000,
                               double warmup_seconds = 0.0);

}  // namespace odeskin::bench

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

// Two kernels' cost ratio measured frame against frame. On a shared machine two cases timed one
// after the other can see different neighbours: the same 32,185-vertex cat gave odeskin / LBS from
// 1.17 to 2.21 in four runs here. Frames of `a` and `b` alternate (a b, then b a, so neither always
// runs on the other's warm caches), and each pair gives one ratio; the median of those is robust to
// what a pair's neighbours did.
struct PairedTiming {
  double ratio = 0.0;      // median over pairs of a's wall time / b's
  double gpu_ratio = 0.0;  // the same over the GPU times the bodies report; 0 where either reports none
  int pairs = 0;
};

// Warms up both as timeFrames does (one frame each, then until `warmup_seconds`), then times pairs
// until `min_seconds` of frames have run and at least `min_pairs` are timed (at most `max_pairs`).
// The first failing frame's status is returned.
Result<PairedTiming> timePairedFrames(const FrameBody& a, const FrameBody& b, double min_seconds, int min_pairs = 3,
                                      int max_pairs = 100000, double warmup_seconds = 0.0);

}  // namespace odeskin::bench

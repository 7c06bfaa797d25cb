// SPDX-License-Identifier: MIT
// `odeskin play ASSET --t T -o OUT.obj` writes the deformation at global time T in [0, K-1] (integer
// T: example pose T; T = 1.5: the middle of the second segment). `odeskin play ASSET --fps F
// [--seconds S] -o OUT_%04d.obj` writes a sequence: frame f at f / F seconds, t = seconds /
// segment_seconds (clamped to [0, K-1]); S defaults to the asset's length.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "asset_playback.hpp"
#include "console.hpp"

namespace odeskin {

// An output name with exactly one printf-style integer conversion for the frame number: %d, %i,
// %u, %Nd or %0Nd (width N <= 32); "%%" stands for '%'.
class FramePattern {
 public:
  // kInvalidArgument naming the pattern: no conversion, two, or one that is not an integer.
  static Result<FramePattern> parse(std::string_view pattern);
  std::string format(std::size_t frame) const;

 private:
  std::string prefix_;
  std::string suffix_;
  std::size_t width_ = 0;
  bool zero_pad_ = false;
};

struct PlayOptions {
  std::filesystem::path asset;
  std::optional<double> t;        // one frame at global time t
  std::optional<double> fps;      // a sequence at this frame rate
  std::optional<double> seconds;  // sequence length; default: (K-1) x segment_seconds
  std::string output;             // .obj file (--t) or .obj pattern (--fps)
  PlaybackOptions playback;
};

struct PlayReport {
  std::vector<std::filesystem::path> files;  // written, in frame order
  std::vector<double> times;                 // global t of each file
  std::string device;
  double mean_frame_seconds = 0.0;           // deformation only, not file writing
};

// Frame times in seconds of a sequence: 0, 1/fps, ... up to `seconds` (inclusive, within 1e-9 of
// a frame), so 1 s at 30 fps is 31 frames.
std::vector<double> sequenceSeconds(double fps, double seconds);

// Exit status as console.hpp: usage (2) for option errors, including T outside [0, K-1]; failure
// (1) for a missing or corrupt asset (the message starts with its path) and write errors.
int runPlayCommand(const PlayOptions& options, Console& console, PlayReport* report = nullptr);

}  // namespace odeskin

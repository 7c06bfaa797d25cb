// SPDX-License-Identifier: MIT
// `odeskin play ASSET --t T -o OUT.obj` writes the deformation at global time T in [0, K-1] (integer
// T: example pose T; T = 1.5: the middle of the second segment). `odeskin play ASSET --fps F
// [--seconds S] -o OUT_%04d.obj` writes a sequence: frame f at f / F seconds, t = seconds /
// segment_seconds (clamped to [0, K-1]); S defaults to the asset's length. `--png DIR` (with or
// without -o) also draws every frame to DIR/frame_%04d.png with one fixed camera, and a contact
// sheet of up to 12 evenly spaced frames to DIR/strip.png as a quick preview. `-o OUT.glb` bakes
// every frame into one GLB; `-o OUT.pc2` or `-o OUT.mdd` writes them as one point cache
// (point_cache.hpp), sample k at scene frame k, for the mesh `--t 0 -o BASE.obj` writes.
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
  std::string output;             // .obj file (--t) or .obj pattern (--fps), .glb, .pc2 or .mdd; may be empty with png_dir
  std::filesystem::path materials;  // .glb only: a glTF whose materials dress it (gltf_materials.hpp)
  bool quantize = false;            // .glb only: KHR_mesh_quantization (gltf_quantized.hpp)
  PlaybackOptions playback;
  std::filesystem::path png_dir;  // --png DIR: pictures of the frames (Vulkan; lavapipe works)
  std::string png_size = "640x480";
  bool png_curves = false;        // draw the asset's iso-parametric curves on the pictures
  double png_azimuth_deg = 30.0;  // camera as `odeskin render --azimuth/--elevation` (up: +y)
  double png_elevation_deg = 15.0;
};

struct PlayReport {
  std::vector<std::filesystem::path> files;  // meshes written, in frame order
  std::vector<std::filesystem::path> pictures;  // --png: frame pictures, in frame order, then the strip
  std::vector<double> times;                 // global t of each file
  std::string device;
  double mean_frame_seconds = 0.0;           // deformation only, not file writing
};

// Frame times in seconds of a sequence: 0, 1/fps, ... up to `seconds` (inclusive, within 1e-9 of
// a frame), so 1 s at 30 fps is 31 frames.
std::vector<double> sequenceSeconds(double fps, double seconds);

// Exit status as console.hpp: usage (2) for option errors, including T outside [0, K-1]; failure
// (1) for a missing or corrupt asset (the message starts with its path), write errors, and --png
// without a Vulkan device.
int runPlayCommand(const PlayOptions& options, Console& console, PlayReport* report = nullptr);

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin render INPUT... -o OUT.png`: meshes (OBJ, glTF/GLB, .odsk assets) drawn to PNG without a
// display by the Vulkan offscreen renderer (lavapipe works). Several inputs are drawn side by side
// with one camera and scale; --heat REF colours each panel by its per-vertex distance to REF over
// REF's box diagonal, with a colour bar; --curves draws an asset's iso-parametric curves over its
// surface; --turntable N writes N frames turning about the up axis.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "console.hpp"
#include "engine/core/result.hpp"

namespace odeskin {

struct RenderOptions {
  std::vector<std::filesystem::path> inputs;  // >= 1
  std::string output;                         // .png; with --turntable a pattern (%03d) or a base name
  std::optional<double> t;                    // asset: global time in [0, K-1]; glTF: seconds
  std::string size;                           // "WxH" of the whole picture; empty: 720 x 540 per panel
  std::optional<std::filesystem::path> heat;  // reference mesh for the heat map
  std::optional<double> heat_max;             // top of the colour bar, a fraction of REF's diagonal
  bool curves = false;                        // draw assets' iso-curves
  bool lbs = false;                           // each asset also drawn skin-only, in a panel before it
  std::size_t turntable = 0;                  // frames; 0: one still picture
  std::string strip;                          // turntable: also a contact sheet of the frames
  double azimuth_deg = 30.0;
  double elevation_deg = 15.0;
  double fov_deg = 30.0;
  std::string up = "y";
  std::vector<std::string> labels;            // replace the file names under the panels
  bool no_labels = false;
  std::string background = "f7f7f9";
  std::uint32_t samples = 4;                  // multisampling
  std::string device = "auto";
  bool validation = false;                    // Khronos validation layer; fail on any message
};

struct RenderReport {
  std::vector<std::filesystem::path> files;  // pictures written, in order (strip last)
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::size_t panels = 0;
  double mean_frame_seconds = 0.0;           // draw + read back + compose, per picture
  std::optional<double> heat_max;
  std::vector<double> max_errors;            // per panel with a heat map, in panel order
  std::string device;
  std::uint32_t samples = 0;                 // per pixel, as drawn: --samples lowered to what the device offers
};

class RenderSession;

// The Vulkan session runRenderCommand draws with for `options` (their --device, --validation,
// --background and --samples): a caller that draws many pictures with one look opens it once.
// kInvalidArgument for a bad --background; RenderSession::open's errors.
Result<RenderSession> openRenderSession(const RenderOptions& options);

// Exit status as console.hpp: usage (2) for option errors (a malformed --size, an asset time out of
// range, --curves without an asset...); failure (1) for unreadable inputs, a --heat reference
// whose vertex count differs from a panel's, no Vulkan device, validation messages, write errors.
// Pictures are written atomically; on failure none is left half-written. `session`: one that
// openRenderSession made for options with the same look, or null to open one for this call.
int runRenderCommand(const RenderOptions& options, Console& console, RenderReport* report = nullptr,
                     RenderSession* session = nullptr);

}  // namespace odeskin

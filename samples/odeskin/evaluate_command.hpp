// SPDX-License-Identifier: MIT
// `odeskin evaluate FRAMES... --keys i,j[,k...] --methods all --pose-source truth|keys --json OUT.json`
// (issue 5 point 2): fits every method on the key frames, plays them at the other frames inside
// the keys' span and reports per frame and method the Maximum Vertex Error and the mean error
// (fractions of the ground truth's longest box side) and the time per frame: a table on stdout,
// the full numbers as JSON in the layout.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "console.hpp"

namespace odeskin {

struct EvaluateCommandOptions {
  std::vector<std::filesystem::path> frames;  // OBJ ground-truth frames of one mesh
  std::vector<int> keys;                      // indices into frames, strictly increasing, >= 2
  std::string methods = "all";                // all, or a comma list of method names
  std::string pose_source = "truth";          // truth | keys
  std::filesystem::path json;                 // OUT.json (required)
  std::vector<double> times;                  // one per frame, or empty: uniform in frame index
  int terms = 9;                              // Fourier terms N of the odeskin fit
  std::string rig;                            // empty or "auto": automatic rig; "curves": from iso-curves; else a .tgf
  std::filesystem::path bind;                 // rest mesh, with a .tgf rig
  std::filesystem::path weights;              // .dmat, with a .tgf rig
  int bones = 0;                              // automatic rig: bone count, 0 = chosen from the mesh
  std::string up;                             // --rig curves: the mesh's up axis (parseUpAxis); empty: y
  std::filesystem::path png_dir;              // --png DIR: a heat-map picture per in-between frame
  std::string skeleton_fit = "rigid";         // rigid (per-bone) | lbs (SSDR, the rig's own); evaluation.hpp
};

// Exit status as console.hpp: usage (2) for option errors (unknown method or protocol, bad keys or
// times for the frame count), failure (1) for unreadable or mismatched frames (naming the file),
// a failed fit or method, or an unwritable JSON (nothing is left at `json` then). --png DIR writes
// DIR/frame_NNNN.png per in-between frame (one panel per method, coloured by its per-vertex error
// against the ground truth, `odeskin render --heat`) and the deformed meshes as DIR/obj/*.obj; it
// needs a Vulkan device (lavapipe works). `device` as the global --device.
int runEvaluateCommand(const EvaluateCommandOptions& options, Console& console, const std::string& device = "auto");

}  // namespace odeskin

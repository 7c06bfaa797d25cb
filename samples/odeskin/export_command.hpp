// SPDX-License-Identifier: MIT
// `odeskin export ASSET -o OUT.glb [--bake [--fps F]] [--tolerance T] [--no-target-normals]
// [--materials SOURCE.glb]`: a .odsk asset as one glTF 2.0 binary that any viewer plays with the
// player's motion (exportGltf, engine/export/).
#pragma once

#include <filesystem>
#include <optional>

#include "console.hpp"
#include "engine/export/gltf_export.hpp"

namespace odeskin {

struct ExportCommandOptions {
  std::filesystem::path asset;
  std::filesystem::path output;        // .glb
  bool bake = false;                   // one morph target per frame even when the compact form works
  std::optional<double> fps;           // frames per second of a bake (default 30)
  double tolerance = 1e-5;             // of the box: error budget of the weight keys and of the skeleton keys
  std::string interpolation = "cubic";  // of the compact form's keys: cubic (CUBICSPLINE) or linear
  bool target_normals = true;          // NORMAL deltas in the compact form's morph targets
  bool quantize = false;               // KHR_mesh_quantization
  std::filesystem::path materials;     // a glTF whose materials dress the output, or empty
};

// Exit status as console.hpp: usage (2) for option errors, failure (1) for a missing or corrupt
// asset (the message starts with its path) and for write errors (nothing is left at the output).
// The summary goes to console.out; a bake fallback's reason and progress go to console.err.
int runExportCommand(const ExportCommandOptions& options, Console& console, GltfExportReport* report = nullptr);

}  // namespace odeskin

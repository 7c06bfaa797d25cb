// SPDX-License-Identifier: MIT
// `odeskin fit POSES... -o ASSET`: example poses in, a .odsk asset out (runFitPipeline, saveAsset).
// Inputs: K >= 2 OBJ poses of one mesh (optionally --bind REST.obj), or one .gltf/.glb with
// --times / --targets, or OBJ poses with a libigl rig (--rig SKELETON.tgf --bind REST.obj
// [--weights W.dmat] [--transforms P1.Tmat,...]).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "console.hpp"
#include "engine/core/types.hpp"

namespace odeskin {

struct FitCommandOptions {
  std::vector<std::filesystem::path> inputs;       // OBJ poses, or one .gltf/.glb
  std::filesystem::path output;                    // the .odsk to write
  std::string rig;                                 // empty: the input's rig, else automatic; "auto": always
                                                   // automatic; else a libigl .tgf skeleton
  std::filesystem::path bind;                      // rest mesh (.obj); required with a .tgf rig
  std::filesystem::path weights;                   // .dmat, with a .tgf rig
  std::vector<std::filesystem::path> transforms;   // one .Tmat per pose, with a .tgf rig
  std::string mesh;                                // glTF: mesh node name (empty: the first skinned mesh)
  std::string animation;                           // glTF: animation name or index (empty: the first)
  std::vector<double> times;                       // glTF: seconds, one example pose each
  std::vector<int> targets;                        // glTF: morph targets as example poses
  int terms = 9;                                   // N, 1..kMaxFourierModes
  std::string material;                            // skin | static | rho,eta,zeta,xi; empty: skin
  std::filesystem::path materials_json;            // per-part overrides (material_options.hpp)
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  double key_tolerance = 1e-4;                     // x longest bounding-box side
  bool pure_fourier = false;
  int bones = 0;                                   // automatic rig: bone count, 0 = chosen
  double segment_seconds = 1.0;
  bool timings = false;                            // print the thesis Table 6.3 stage breakdown
};

// Exit status as console.hpp: usage (2) for option errors, failure (1) for unreadable inputs, a
// failed fit or an unwritable output (nothing is left at `output` then).
int runFitCommand(const FitCommandOptions& options, Console& console);

}  // namespace odeskin

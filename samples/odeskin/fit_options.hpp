// SPDX-License-Identifier: MIT
// The options of `odeskin fit` and the checks that need no file: which reader the inputs call for
// and whether the options fit together (usage errors, exit status 2, before any work is done).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/types.hpp"

namespace odeskin {

// The ranges fit accepts: --key-tolerance as a fraction of the box, --segment-seconds in seconds.
constexpr double kMinKeyTolerance = 1e-12, kMaxKeyTolerance = 0.1;
constexpr double kMinSegmentSeconds = 1e-4, kMaxSegmentSeconds = 1e6;

struct FitCommandOptions {
  std::vector<std::filesystem::path> inputs;       // OBJ poses, or one .gltf/.glb
  std::filesystem::path output;                    // the .odsk to write
  std::string rig;                                 // empty: the input's rig, else automatic; "auto": always
                                                   // automatic (from motion); "curves": always from the
                                                   // bind mesh's iso-curves; else a libigl .tgf skeleton
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
  double key_tolerance = 1e-4;                     // x longest bounding-box side, [kMinKeyTolerance, kMaxKeyTolerance]
  bool pure_fourier = false;
  int bones = 0;                                   // automatic rig: bone count, 0 = chosen
  std::string up;                                  // --rig curves: the mesh's up axis (parseUpAxis); empty: y
  double segment_seconds = 1.0;                    // [kMinSegmentSeconds, kMaxSegmentSeconds]
  bool timings = false;                            // print the thesis Table 6.3 stage breakdown
};

enum class FitInputKind {
  kObj,     // K >= 2 OBJ poses, optional --bind
  kGltf,    // one .gltf/.glb with --times and/or --targets
  kLibigl,  // OBJ poses with --rig SKELETON.tgf and --bind REST.obj
};

// Which reader the inputs call for; *problem is set (else left empty) when the inputs and the
// input options do not fit together.
FitInputKind fitInputKind(const FitCommandOptions& options, std::string* problem);

// The first usage problem of `options` ("fit: ..."), or empty when they are usable.
std::string fitUsageProblem(const FitCommandOptions& options);

// The --material text in effect (empty means skin).
std::string fitMaterialText(const FitCommandOptions& options);

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// Example poses in, DeformAsset out (thesis ch. 6, PIPELINE.md): resolve the rig (given, Kabsch
// transforms, distance weights, or automatic), identify iso-parametric curves and bind every
// vertex, fit the per-segment residual series, and play the keys back to measure their error.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "../core/result.hpp"
#include "../io/example_set.hpp"
#include "../offline/deform_asset.hpp"
#include "../offline/residual_fit.hpp"

namespace odeskin {

struct PipelineOptions {
  int modes = 9;                                  // N, --terms
  ResidualSpace residual_space = ResidualSpace::kBind;
  SkinningMode skinning = SkinningMode::kLinear;
  Material material = staticMaterial();           // every part unless overridden
  std::map<std::string, Material> part_materials; // part (bone name or index as text) -> material
  std::string part_materials_source = "materials";  // where part_materials came from, for messages
  double key_tolerance = 1e-4;                    // x longest bounding-box side
  bool pure_fourier = false;
  bool force_auto_rig = false;                    // ignore a rig in the input
  bool curve_rig = false;                         // the automatic rig from iso-curves (rig/curve_rig.hpp), not from motion
  Vec3 curve_rig_up{0.0, 1.0, 0.0};               // curve_rig: the mesh's up axis, for the skeleton templates
  int auto_bones = 0;                             // automatic rig: bone count, 0 = chosen from the mesh
  double segment_seconds = 1.0;
  // Called with a stage name and its completed fraction in [0, 1] (for progress bars).
  std::function<void(std::string_view stage, double fraction)> progress;
};

// Seconds per stage, in the order of thesis Table 6.3.
struct StageTimings {
  double rig = 0.0;                  // bones, weights and key transforms (given, Kabsch, or automatic)
  double curve_identification = 0.0; // parts, plane cuts, bindings
  double geometric_transform = 0.0;  // the blended linear parts at every key (conditioning), LBS of the
                                     // bind mesh at every key and the bind-space residuals
  double fourier_and_deformation = 0.0;  // per-curve Fourier fits and remainders for every segment
  double analytic_solve = 0.0;       // time bases, rate chaining, and playing every key with the skin deformer
  double total = 0.0;
};

struct PipelineResult {
  DeformAsset asset;
  FitReport report;
  StageTimings timings;
  std::string rig_summary;           // e.g. "auto: 18 bones from 10 poses (fit error 2.1e-3 of the box)"
  std::size_t part_count = 0;
  std::vector<std::string> warnings;  // what a user should hear of and the fit went on past
};

Result<PipelineResult> runFitPipeline(const ExampleSet& examples, const PipelineOptions& options);

}  // namespace odeskin

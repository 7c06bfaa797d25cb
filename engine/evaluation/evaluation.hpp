// SPDX-License-Identifier: MIT
// In-between error against ground truth (issue 5 point 2): a sequence of F ground-truth frames, K
// of them chosen as keys; every method is built from the keys (one fitted DeformAsset, one rig)
// and played at the remaining frames inside the keys' span, which are scored by vertexError (MVE
// and mean error, fractions of the truth's longest box side) and timed per evaluate() call.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "../baselines/baseline.hpp"
#include "../baselines/baseline_factory.hpp"
#include "../baselines/baseline_rig.hpp"
#include "../core/result.hpp"
#include "../io/example_set.hpp"
#include "../pipeline/fit_pipeline.hpp"

namespace odeskin {

// Where each in-between frame's skeleton comes from (issue 5's two protocols).
enum class PoseSource : std::uint32_t {
  kTruth = 0,  // fitted to the ground-truth frame (BaselineRig::fitFrameBones); only the skeleton
  kKeys,       // interpolated from the key poses alone (C1 across keys)
};
std::string_view poseSourceName(PoseSource source);       // "truth", "keys"
bool parsePoseSource(std::string_view name, PoseSource* source);

struct EvaluationOptions {
  PipelineOptions pipeline;   // how the keys are fitted (modes = --terms, rig, ...)
  BaselineOptions baselines;  // PSD, FD and the odeskin materials
  // How every skeleton is fitted to its frame, the keys' (the asset's key transforms) and, under
  // the truth protocol, the in-betweens' alike, so that the keys and the frames between them come
  // from one animation system. kLbsOptimal: the rig's own transforms (SSDR sweeps minimising each
  // frame's LBS error: the best LBS the rig allows, which leaks the surface into the skeleton).
  // kPerBoneRigid: per-bone rigid fits (issue 5's "per-bone rigid fit on the rig's vertices"); the
  // automatic rig's bones and weights are kept, only the transforms are refitted.
  SkeletonFit skeleton_fit = SkeletonFit::kPerBoneRigid;
  // Called after each scored evaluation (outside the timing) with the in-between frame's index, the
  // method and its deformed positions (valid during the call), e.g. to draw heat maps; an error
  // stops the evaluation and is returned.
  std::function<Status(std::uint32_t frame, BaselineMethod method, std::span<const Vec3> deformed)> on_frame;
};

struct MethodFrameScore {
  double mve = 0.0;           // max vertex error / Lbox
  double mean = 0.0;          // mean vertex error / Lbox
  double ms_per_frame = 0.0;  // wall time of the evaluate() call (steady_clock)
};

struct EvaluatedFrame {
  std::uint32_t frame = 0;              // index into the frames
  double t = 0.0;                       // global time: segment + tau (key k at t = k)
  std::uint32_t segment = 0;
  double tau = 0.0;
  std::vector<MethodFrameScore> scores; // one per method, in EvaluationResult::methods order
};

struct MethodSummary {
  double mve_max = 0.0;       // over the in-between frames
  double mean_mean = 0.0;     // mean over the in-between frames of the per-frame mean error
  double ms_per_frame = 0.0;  // mean over the in-between frames
  double setup_ms = 0.0;      // makeBaseline
};

struct EvaluationResult {
  PoseSource pose_source = PoseSource::kTruth;
  std::vector<BaselineMethod> methods;
  std::vector<std::uint32_t> keys;
  std::vector<EvaluatedFrame> frames;   // the in-betweens, in frame order (keys are not listed)
  std::vector<MethodSummary> summary;   // one per method
  std::string rig_summary;              // runFitPipeline's
  std::uint32_t bone_count = 0;
  std::size_t curve_count = 0;
  int modes = 0;
  double fit_seconds = 0.0;
  std::vector<std::string> notes;       // what a method did that its numbers do not say
};

// The in-between frames of `keys` and their (segment, tau): every frame strictly between the first
// and last key that is not a key. `times` empty: tau uniform in frame index within each segment;
// else one time per frame (any unit, strictly increasing), tau = (t_f - t_key_s) / (t_key_s+1 - t_key_s).
// Errors (kInvalidArgument): fewer than 2 keys, keys not strictly increasing or not below
// `frame_count`, a times list of the wrong length, not finite or not strictly increasing.
struct InBetween {
  std::uint32_t frame = 0;
  std::uint32_t segment = 0;
  double tau = 0.0;
};
Result<std::vector<InBetween>> inBetweenFrames(std::size_t frame_count, std::span<const std::uint32_t> keys,
                                               std::span<const double> times);

// What every method of an evaluation is built from: the key frames alone as an ExampleSet (without
// a rig in the input the bind mesh is the first key; a given rig keeps its bind mesh and the keys'
// transforms) and the asset fitted on them with options.pipeline, its key transforms refitted per
// bone rigidly when options.skeleton_fit says so. Exposed so that other comparisons (static vs
// dynamic, reversibility, variants of a method) start from exactly the asset runEvaluation scores.
struct KeyFit {
  ExampleSet key_set;
  PipelineResult fit;
  double seconds = 0.0;  // wall time of the fit(s)
};
// Errors: kInvalidArgument for keys out of range or not increasing, frames of different sizes
// (naming the file), and those of runFitPipeline and fitRigidBoneTransforms.
Result<KeyFit> fitEvaluationKeys(const ExampleSet& frames, std::span<const std::uint32_t> keys,
                                 const EvaluationOptions& options = {});

// The rig of a fitted asset (its bone pivots as heads and tails, parents, influences) with the
// transforms of `keys`' poses refitted per bone rigidly (fitRigidBoneTransforms), as
// EvaluationOptions::skeleton_fit kPerBoneRigid hands it to the second fit. Errors: those of
// fitRigidBoneTransforms.
Result<Rig> perBoneRigidRig(const DeformAsset& asset, const ExampleSet& keys);

// `frames`: F ground-truth frames of one mesh (poses, F x V, with pose_labels naming their files;
// faces as read). Fits the keys (bind = the first key; options.pipeline), builds each method
// (makeBaseline) and scores it at every in-between frame under `source`. Errors: those of
// inBetweenFrames, kInvalidArgument for an empty method list, a repeated method, or a frame whose
// vertex count differs from the first (naming its label), and those of the fit and the methods
// (prefixed with the method's name).
Result<EvaluationResult> runEvaluation(const ExampleSet& frames, std::span<const std::uint32_t> keys,
                                       std::span<const BaselineMethod> methods, PoseSource source,
                                       std::span<const double> times, const EvaluationOptions& options = {});

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "../baselines/baseline_rig.hpp"
#include "../baselines/pose_space_deformation.hpp"
#include "../baselines/vertex_error.hpp"
#include "../core/number_text.hpp"
#include "../rig/kabsch.hpp"

namespace odeskin {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string frameLabel(const ExampleSet& frames, std::size_t f) {
  if (f < frames.pose_labels.size() && !frames.pose_labels[f].empty()) return frames.pose_labels[f];
  return "frame " + std::to_string(f);
}

// PSD averages the correctives of keys whose skeletons nearly coincide (pose_space_rbf.hpp); which
// keys, or "" when none.
std::string groupedKeys(const RbfInterpolator& rbf, std::span<const std::uint32_t> keys) {
  std::string text;
  for (std::uint32_t g = 0; g < rbf.groupCount(); ++g) {
    std::string members;
    std::size_t count = 0;
    for (std::size_t k = 0; k < rbf.exampleCount(); ++k) {
      if (rbf.groupOf(k) == g) members += (count++ > 0 ? ", " : "") + std::to_string(keys[k]);
    }
    if (count > 1) text += (text.empty() ? "" : "; ") + std::string("key frames ") + members;
  }
  if (text.empty()) return text;
  return text + ": skeletons within " + messageNumber(RbfInterpolator::kMergeRelative) +
         " of the keys' spread in pose space, so their correctives are averaged";
}

}  // namespace

std::string_view poseSourceName(PoseSource source) {
  return source == PoseSource::kTruth ? "truth" : "keys";
}

bool parsePoseSource(std::string_view name, PoseSource* source) {
  if (name == "truth") {
    *source = PoseSource::kTruth;
  } else if (name == "keys") {
    *source = PoseSource::kKeys;
  } else {
    return false;
  }
  return true;
}

Result<std::vector<InBetween>> inBetweenFrames(std::size_t frame_count, std::span<const std::uint32_t> keys,
                                               std::span<const double> times) {
  if (keys.size() < 2) {
    return invalidArgument("evaluate: " + std::to_string(keys.size()) + " key(s); at least 2 are needed");
  }
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (keys[k] >= frame_count) {
      return invalidArgument("evaluate: key " + std::to_string(keys[k]) + " is out of range (" +
                             std::to_string(frame_count) + " frames, indices from 0)");
    }
    if (k > 0 && keys[k] <= keys[k - 1]) {
      return invalidArgument("evaluate: keys must be strictly increasing (" + std::to_string(keys[k - 1]) + " then " +
                             std::to_string(keys[k]) + ")");
    }
  }
  if (!times.empty()) {
    if (times.size() != frame_count) {
      return invalidArgument("evaluate: " + std::to_string(times.size()) + " times for " +
                             std::to_string(frame_count) + " frames (one per frame)");
    }
    for (std::size_t f = 0; f < times.size(); ++f) {
      if (!std::isfinite(times[f])) return invalidArgument("evaluate: the time of frame " + std::to_string(f) + " is not finite");
      if (f > 0 && times[f] <= times[f - 1]) {
        return invalidArgument("evaluate: times must be strictly increasing (frame " + std::to_string(f) + ")");
      }
    }
  }
  std::vector<InBetween> out;
  for (std::uint32_t s = 0; s + 1 < keys.size(); ++s) {
    const std::uint32_t a = keys[s];
    const std::uint32_t b = keys[s + 1];
    for (std::uint32_t f = a + 1; f < b; ++f) {
      const double tau = times.empty() ? static_cast<double>(f - a) / static_cast<double>(b - a)
                                       : (times[f] - times[a]) / (times[b] - times[a]);
      out.push_back({f, s, tau});
    }
  }
  return out;
}

Result<Rig> perBoneRigidRig(const DeformAsset& asset, const ExampleSet& keys) {
  Rig rig;
  rig.skeleton.heads = asset.bone_pivots;
  rig.skeleton.tails = asset.bone_pivots;
  rig.skeleton.names.assign(asset.bone_pivots.size(), std::string());
  rig.skeleton.parents =
      asset.bone_parents.empty() ? std::vector<std::int32_t>(asset.bone_pivots.size(), -1) : asset.bone_parents;
  rig.influences = asset.influences;
  ODESKIN_ASSIGN_OR_RETURN(rig.key_poses, fitRigidBoneTransforms(keys.rest_positions, keys.poses, rig.influences, rig.skeleton));
  return rig;
}

Result<KeyFit> fitEvaluationKeys(const ExampleSet& frames, std::span<const std::uint32_t> keys,
                                 const EvaluationOptions& options) {
  if (keys.size() < 2) return invalidArgument("evaluate: " + std::to_string(keys.size()) + " key(s); at least 2 are needed");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (keys[k] >= frames.poses.size() || (k > 0 && keys[k] <= keys[k - 1])) {
      return invalidArgument("evaluate: keys must be strictly increasing frame indices below " +
                             std::to_string(frames.poses.size()));
    }
  }
  const std::size_t vertex_count = frames.poses.front().size();
  for (std::size_t f = 1; f < frames.poses.size(); ++f) {
    if (frames.poses[f].size() != vertex_count) {
      return invalidArgument("evaluate: " + frameLabel(frames, f) + ": " + std::to_string(frames.poses[f].size()) +
                             " vertices but " + frameLabel(frames, 0) + " has " + std::to_string(vertex_count));
    }
  }

  // The keys alone are what every method may learn from. Without a rig in the input the bind mesh
  // is the first key, as `odeskin fit` of those files would choose; a given rig keeps its own bind
  // mesh and the keys' transforms.
  KeyFit out;
  ExampleSet& key_set = out.key_set;
  key_set.rest_positions = frames.rig ? frames.rest_positions : frames.poses[keys.front()];
  key_set.faces = frames.faces;
  key_set.render = frames.render;
  key_set.rig = frames.rig;
  if (key_set.rig) key_set.rig->key_poses.clear();
  for (const std::uint32_t k : keys) {
    key_set.poses.push_back(frames.poses[k]);
    key_set.pose_labels.push_back(frameLabel(frames, k));
    if (frames.rig && k < frames.rig->key_poses.size()) key_set.rig->key_poses.push_back(frames.rig->key_poses[k]);
  }
  if (key_set.rig && key_set.rig->key_poses.size() != keys.size()) key_set.rig->key_poses.clear();
  const auto fit_start = std::chrono::steady_clock::now();
  ODESKIN_ASSIGN_OR_RETURN(out.fit, runFitPipeline(key_set, options.pipeline));
  if (options.skeleton_fit == SkeletonFit::kPerBoneRigid) {
    PipelineResult& fit = out.fit;
    // Keep the fitted rig's bones and weights; refit the keys' transforms rigidly and fit again, so
    // that the residual is measured against the same kind of skeleton the in-betweens get.
    ODESKIN_ASSIGN_OR_RETURN(Rig rig, perBoneRigidRig(fit.asset, key_set));
    const std::string first_rig = fit.rig_summary;
    key_set.rig = std::move(rig);
    PipelineOptions rigid = options.pipeline;
    rigid.force_auto_rig = false;
    ODESKIN_ASSIGN_OR_RETURN(fit, runFitPipeline(key_set, rigid));
    fit.rig_summary = first_rig + "; transforms refitted per bone rigidly";
  }
  out.seconds = secondsSince(fit_start);
  return out;
}

Result<EvaluationResult> runEvaluation(const ExampleSet& frames, std::span<const std::uint32_t> keys,
                                       std::span<const BaselineMethod> methods, PoseSource source,
                                       std::span<const double> times, const EvaluationOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(std::vector<InBetween> inbetweens, inBetweenFrames(frames.poses.size(), keys, times));
  if (methods.empty()) return invalidArgument("evaluate: no methods");
  for (std::size_t m = 0; m < methods.size(); ++m) {
    if (std::find(methods.begin(), methods.begin() + static_cast<std::ptrdiff_t>(m), methods[m]) !=
        methods.begin() + static_cast<std::ptrdiff_t>(m)) {
      return invalidArgument("evaluate: method " + std::string(baselineMethodName(methods[m])) + " is listed twice");
    }
  }
  ODESKIN_ASSIGN_OR_RETURN(KeyFit keys_fit, fitEvaluationKeys(frames, keys, options));
  const ExampleSet& key_set = keys_fit.key_set;
  const PipelineResult& fit = keys_fit.fit;
  const std::size_t vertex_count = frames.poses.front().size();

  EvaluationResult result;
  result.fit_seconds = keys_fit.seconds;
  result.pose_source = source;
  result.methods.assign(methods.begin(), methods.end());
  result.keys.assign(keys.begin(), keys.end());
  result.rig_summary = fit.rig_summary;
  result.bone_count = fit.asset.bone_count;
  result.curve_count = fit.asset.curveCount();
  result.modes = fit.asset.modes;
  result.summary.resize(methods.size());

  std::vector<std::unique_ptr<Baseline>> deformers;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const auto start = std::chrono::steady_clock::now();
    Result<std::unique_ptr<Baseline>> built = makeBaseline(methods[m], key_set.poses, fit.asset, options.baselines);
    if (!built.ok()) {
      return Status(built.status().code(), std::string(baselineMethodName(methods[m])) + ": " + built.status().message());
    }
    result.summary[m].setup_ms = 1e3 * secondsSince(start);
    if (const auto* psd = dynamic_cast<const PoseSpaceDeformation*>(built->get())) {
      const std::string grouped = groupedKeys(psd->interpolator(), keys);
      if (!grouped.empty()) result.notes.push_back(std::string(baselineMethodName(methods[m])) + ": " + grouped);
    }
    deformers.push_back(std::move(*built));
  }
  ODESKIN_ASSIGN_OR_RETURN(BaselineRig rig, BaselineRig::fromAsset(fit.asset));

  std::vector<Vec3> out(vertex_count);
  for (const InBetween& ib : inbetweens) {
    const std::vector<Vec3>& truth = frames.poses[ib.frame];
    std::vector<BoneTransform> bones;  // empty: the keys protocol
    if (source == PoseSource::kTruth) {
      Result<std::vector<BoneTransform>> fitted = rig.fitFrameBones(truth, options.skeleton_fit);
      if (!fitted.ok()) {
        return Status(fitted.status().code(), frameLabel(frames, ib.frame) + ": " + fitted.status().message());
      }
      bones = std::move(*fitted);
    }
    EvaluatedFrame row;
    row.frame = ib.frame;
    row.segment = ib.segment;
    row.tau = ib.tau;
    row.t = static_cast<double>(ib.segment) + ib.tau;
    for (std::size_t m = 0; m < deformers.size(); ++m) {
      const auto start = std::chrono::steady_clock::now();
      const Status st = deformers[m]->evaluate({ib.segment, ib.tau, bones}, out);
      const double ms = 1e3 * secondsSince(start);
      if (!st.ok()) {
        return Status(st.code(), std::string(baselineMethodName(methods[m])) + " at " + frameLabel(frames, ib.frame) +
                                     ": " + st.message());
      }
      Result<VertexError> e = vertexError(out, truth);
      if (!e.ok()) {
        return Status(e.status().code(), std::string(baselineMethodName(methods[m])) + " at " +
                                             frameLabel(frames, ib.frame) + ": " + e.status().message());
      }
      if (options.on_frame) ODESKIN_TRY(options.on_frame(ib.frame, methods[m], out));
      row.scores.push_back({e->mve, e->mean, ms});
      MethodSummary& s = result.summary[m];
      s.mve_max = std::max(s.mve_max, e->mve);
      s.mean_mean += e->mean / static_cast<double>(inbetweens.size());
      s.ms_per_frame += ms / static_cast<double>(inbetweens.size());
    }
    result.frames.push_back(std::move(row));
  }
  return result;
}

}  // namespace odeskin

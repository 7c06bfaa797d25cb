// SPDX-License-Identifier: MIT
#include "fit_pipeline.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>

#include "../core/number_text.hpp"
#include "../core/position_box.hpp"
#include "../curves/iso_curves.hpp"
#include "../rig/auto_rig.hpp"
#include "../rig/curve_rig.hpp"
#include "../rig/distance_weights.hpp"
#include "../rig/kabsch.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

Status checkExamples(const ExampleSet& ex) {
  const std::size_t v_count = ex.rest_positions.size();
  if (v_count == 0) return invalidArgument("fit: the mesh has no vertices");
  if (ex.poses.size() < 2) {
    return invalidArgument("fit: needs at least 2 example poses, got " + std::to_string(ex.poses.size()));
  }
  for (std::size_t k = 0; k < ex.poses.size(); ++k) {
    const std::string label = k < ex.pose_labels.size() ? ex.pose_labels[k] : "pose " + std::to_string(k);
    if (ex.poses[k].size() != v_count) {
      return invalidArgument("fit: " + label + " has " + std::to_string(ex.poses[k].size()) + " vertices, the bind mesh " +
                             std::to_string(v_count));
    }
    ODESKIN_TRY(checkedPositionBox(ex.poses[k], "fit: " + label).status());
  }
  ODESKIN_TRY(checkedPositionBox(ex.rest_positions, "fit: the bind mesh").status());
  for (std::uint32_t index : ex.faces.indices) {
    if (index >= v_count) return invalidArgument("fit: a face uses vertex " + std::to_string(index) + " of " + std::to_string(v_count));
  }
  return okStatus();
}

// Automatic rigs of the data's meshes skin to within 1-3% of the box on average; a given rig ten
// times further off has most likely been given with another take's transforms.
constexpr double kFarRigError = 0.1;

// The rig the fit uses: the input's, completed (weights by distance, transforms by Kabsch), or automatic.
Result<Rig> resolveRig(const ExampleSet& ex, const PipelineOptions& opt, std::string* summary,
                       std::vector<std::string>* warnings) {
  const std::size_t k_count = ex.poses.size();
  if ((!ex.rig || opt.force_auto_rig) && opt.curve_rig) {
    CurveRigOptions curve_options;
    curve_options.animation.up = opt.curve_rig_up;
    return curveRigForPoses(ex.rest_positions, ex.faces, ex.poses, summary, curve_options);
  }
  if (!ex.rig || opt.force_auto_rig) {
    AutoRigOptions auto_options;
    auto_options.bones = opt.auto_bones;
    AutoRigReport report;
    Result<Rig> rig = autoRig(ex.rest_positions, ex.faces, ex.poses, auto_options, &report);
    if (!rig.ok()) {
      // autoRig names itself ("auto rig: ..."); say so once.
      const std::string& message = rig.status().message();
      return message.starts_with("auto rig: ") ? rig.status() : Status(rig.status().code(), "auto rig: " + message);
    }
    *summary = "auto: " + std::to_string(report.bones) + " bones";
    // Clusters too small or too flat for a bone are dropped: say so when fewer came than were asked for.
    if (opt.auto_bones > report.bones) {
      *summary += " (" + std::to_string(opt.auto_bones) + " asked for; the poses' motion separates no more)";
    }
    *summary += " from " + std::to_string(k_count) + " poses (LBS error mean " + scientific(report.mean_error) + ", max " +
                scientific(report.max_error) + " of the box)";
    return rig;
  }
  Rig rig = *ex.rig;
  ODESKIN_TRY(validateRig(rig, ex.rest_positions.size(), k_count));
  std::string weights = "given weights";
  if (rig.influences.vertexCount() == 0) {
    Result<Influences> influences = distanceWeights(ex.rest_positions, ex.faces, rig.skeleton);
    if (!influences.ok()) return Status(influences.status().code(), "distance weights: " + influences.status().message());
    rig.influences = std::move(*influences);
    weights = "distance weights";
  }
  std::string transforms = "given transforms";
  if (rig.key_poses.empty()) {
    Result<std::vector<std::vector<RigidTransform>>> fitted =
        fitBoneTransforms(ex.rest_positions, ex.poses, rig.influences, rig.skeleton);
    if (!fitted.ok()) return Status(fitted.status().code(), "bone transforms: " + fitted.status().message());
    rig.key_poses = std::move(*fitted);
    transforms = "Kabsch transforms";
  }
  *summary = "given skeleton: " + std::to_string(rig.skeleton.boneCount()) + " bones, " + weights + ", " + transforms;
  // As the automatic rig reports it: transforms of other poses than these (.Tmat files of another
  // take) fit anyway, the residual and remainders absorbing up to a quarter of the box unseen.
  double box = 0.0;
  for (const std::vector<Vec3>& pose : ex.poses) box = std::max(box, longestBoxSide(pose));
  const double scale = box > 0.0 ? box : 1.0;
  const SkinningError lbs = skinningError(ex.rest_positions, ex.poses, rig);
  const double mean = lbs.sum / static_cast<double>(std::max<std::size_t>(lbs.samples, 1)) / scale;
  *summary += " (LBS error mean " + scientific(mean) + ", max " + scientific(lbs.max / scale) + " of the box)";
  if (mean > kFarRigError) {
    warnings->push_back("the given rig skins the bind mesh " + percentText(mean) +
                        " of the box from the poses on average: do its weights and transforms belong to these poses?");
  }
  return rig;
}

// Material 0 is the default; each overridden part adds one. Part keys are bone names or indices.
Status assignMaterials(const PipelineOptions& opt, const Skeleton& skeleton, const CurveSet& curves, FitOptions& fit) {
  fit.materials = {opt.material};
  std::vector<std::int64_t> part_material(skeleton.boneCount(), 0);
  std::vector<const std::string*> part_key(skeleton.boneCount(), nullptr);  // the key that set it
  for (const auto& [key, material] : opt.part_materials) {
    std::int64_t bone = -1;
    for (std::size_t b = 0; b < skeleton.names.size(); ++b) {
      if (skeleton.names[b] == key) bone = static_cast<std::int64_t>(b);
    }
    if (bone < 0 && !key.empty() && key.find_first_not_of("0123456789") == std::string::npos && key.size() < 10) {
      bone = std::stoll(key);
    }
    if (bone < 0 || bone >= static_cast<std::int64_t>(skeleton.boneCount())) {
      return invalidArgument(opt.part_materials_source + ": part '" + key +
                             "' is neither a bone name nor a bone index below " + std::to_string(skeleton.boneCount()));
    }
    // Two spellings of one bone ("0" and its name, "0" and "00") would leave one material unused.
    if (const std::string* other = part_key[static_cast<std::size_t>(bone)]) {
      return invalidArgument(opt.part_materials_source + ": parts '" + *other + "' and '" + key + "' both name bone " +
                             std::to_string(bone) + "; give each bone one material");
    }
    part_key[static_cast<std::size_t>(bone)] = &key;
    part_material[static_cast<std::size_t>(bone)] = static_cast<std::int64_t>(fit.materials.size());
    fit.materials.push_back(material);
  }
  fit.curve_materials.clear();
  for (const IsoCurve& curve : curves.curves) {
    const std::size_t part = curve.part < part_material.size() ? curve.part : 0;
    fit.curve_materials.push_back(static_cast<std::uint32_t>(part_material[part]));
  }
  return okStatus();
}

}  // namespace

Result<PipelineResult> runFitPipeline(const ExampleSet& ex, const PipelineOptions& opt) {
  const Clock::time_point start = Clock::now();
  auto progress = [&](std::string_view stage, double fraction) {
    if (opt.progress) opt.progress(stage, fraction);
  };
  ODESKIN_TRY(checkExamples(ex));
  if (!(opt.segment_seconds > 0.0) || !std::isfinite(opt.segment_seconds)) {
    return invalidArgument("fit: segment length must be a positive number of seconds");
  }
  PipelineResult result;
  // Two equal keys in a row (glTF --times 1,1, or a frame given twice) make a segment that holds still.
  for (std::size_t k = 1; k < ex.poses.size(); ++k) {
    if (ex.poses[k] == ex.poses[k - 1]) {
      const bool labelled = ex.pose_labels.size() == ex.poses.size();
      result.warnings.push_back("key poses " + std::to_string(k - 1) + " and " + std::to_string(k) +
                                (labelled ? " (" + ex.pose_labels[k - 1] + ", " + ex.pose_labels[k] + ")" : std::string()) +
                                " are the same shape, so the segment between them holds still");
    }
  }

  progress("rig", 0.0);
  Clock::time_point stage = Clock::now();
  ODESKIN_ASSIGN_OR_RETURN(Rig rig, resolveRig(ex, opt, &result.rig_summary, &result.warnings));
  result.timings.rig = secondsSince(stage);

  progress("curves", 0.25);
  stage = Clock::now();
  Result<CurveSet> curves = buildIsoCurves(ex.rest_positions, ex.faces, rig.skeleton, rig.influences);
  if (!curves.ok() && curves.status().code() == StatusCode::kDegenerate) {
    // Low-poly meshes: accept short curves (the fit then uses the few modes they determine).
    CurveOptions short_curves;
    short_curves.min_points = 3;
    curves = buildIsoCurves(ex.rest_positions, ex.faces, rig.skeleton, rig.influences, short_curves);
  }
  if (!curves.ok()) return curves.status();
  result.timings.curve_identification = secondsSince(stage);
  std::set<std::uint32_t> parts;
  for (const IsoCurve& curve : curves->curves) parts.insert(curve.part);
  result.part_count = parts.size();

  FitOptions fit;
  fit.modes = opt.modes;
  fit.residual_space = opt.residual_space;
  fit.skinning = opt.skinning;
  fit.key_tolerance = opt.key_tolerance;
  fit.pure_fourier = opt.pure_fourier;
  ODESKIN_TRY(assignMaterials(opt, rig.skeleton, *curves, fit));

  FitInput input;
  input.rest_positions = ex.rest_positions;
  input.faces = ex.faces;
  input.poses = ex.poses;
  input.influences = rig.influences;
  input.bone_count = static_cast<std::uint32_t>(rig.skeleton.boneCount());
  input.bone_pivots = rig.skeleton.heads;
  input.key_poses = rig.key_poses;
  input.curves = curves->curves;
  input.bindings = curves->bindings;

  progress("fit", 0.5);
  Result<DeformAsset> asset = fitDeformAsset(input, fit, &result.report);
  if (!asset.ok()) return asset.status();
  result.asset = std::move(*asset);
  result.asset.skinning = opt.skinning;
  result.asset.segment_seconds = opt.segment_seconds;
  result.asset.render = ex.render;
  result.asset.bone_parents = rig.skeleton.parents;
  result.asset.bone_names = rig.skeleton.names;
  ODESKIN_TRY(validateDeformAsset(result.asset));
  result.timings.geometric_transform = result.report.seconds_geometric;
  result.timings.fourier_and_deformation = result.report.seconds_fourier;
  result.timings.analytic_solve = result.report.seconds_solve;
  result.timings.total = secondsSince(start);
  progress("done", 1.0);
  return result;
}

}  // namespace odeskin

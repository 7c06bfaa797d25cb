// SPDX-License-Identifier: MIT
#include "fit_sources.hpp"

#include <algorithm>
#include <cstdio>

#include "engine/io/obj_reader.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "subdivided_examples.hpp"
#include "numbered_paths.hpp"

namespace odeskin::bench {
namespace {

namespace fs = std::filesystem;

Result<PipelineResult> fit(const ExampleSet& examples, int modes) {
  PipelineOptions options;
  options.modes = modes;
  options.material = skinMaterial();
  return runFitPipeline(examples, options);
}

FitStageRecord stageRecord(std::string dataset, const ExampleSet& ex, const PipelineResult& r) {
  FitStageRecord f;
  f.dataset = std::move(dataset);
  f.vertices = ex.rest_positions.size();
  f.poses = ex.poses.size();
  f.rig = ex.rig ? "given" : "auto";
  f.rig_seconds = r.timings.rig;
  f.curve_identification = r.timings.curve_identification;
  f.geometric_transform = r.timings.geometric_transform;
  f.fourier_and_deformation = r.timings.fourier_and_deformation;
  f.analytic_solve = r.timings.analytic_solve;
  f.total = r.timings.total;
  return f;
}

// The fitted asset's rig as a given rig, so later fits of the same poses skip the automatic rig.
Rig rigOf(const DeformAsset& asset) {
  Rig rig;
  rig.skeleton.heads = asset.bone_pivots;
  rig.skeleton.tails = asset.bone_pivots;
  rig.skeleton.parents = asset.bone_parents.empty() ? std::vector<std::int32_t>(asset.bone_count, -1) : asset.bone_parents;
  rig.skeleton.names = asset.bone_names.empty() ? std::vector<std::string>(asset.bone_count) : asset.bone_names;
  rig.influences = asset.influences;
  rig.key_poses = asset.key_poses;
  return rig;
}

Result<FitSources> armSources(std::span<const int> terms) {
  ArmOptions arm_options;
  arm_options.ring_vertices = 64;  // >= 2N+1 for N = 17
  ODESKIN_ASSIGN_OR_RETURN(const ProceduralArm arm, makeProceduralArm(arm_options));
  FitSources s;
  s.mesh = "procedural arm (" + std::to_string(arm.fit_input.rest_positions.size()) + " vertices; cat-poses not found)";
  for (int n : terms) {
    FitOptions options;
    options.modes = n;
    options.materials = {skinMaterial()};
    ODESKIN_ASSIGN_OR_RETURN(s.assets[n], fitDeformAsset(arm.fit_input, options));
  }
  return s;
}

}  // namespace

Result<FitSources> fitSources(const fs::path& data_dir, std::span<const int> terms) {
  const fs::path cat = data_dir / "cat-poses";
  if (!fs::exists(cat / "cat-00.obj")) return armSources(terms);
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet ex, readObjSequence(numbered(cat, "cat-%02d.obj", {0, 1, 2})));
  FitSources s;
  s.mesh = "cat-poses 00-02 (" + std::to_string(ex.rest_positions.size()) + " vertices, automatic rig, skin material, "
           "frame at t = 1.5: segment 1 with rates carried in), tiled to each size";
  for (int n : terms) {
    ODESKIN_ASSIGN_OR_RETURN(PipelineResult r, fit(ex, n));
    s.fits.push_back(stageRecord("cat-poses 00-02, N = " + std::to_string(n), ex, r));
    if (!ex.rig) ex.rig = rigOf(r.asset);  // one automatic rig for every N
    s.assets[n] = std::move(r.asset);
  }
  return s;
}

Result<std::vector<FitStageRecord>> timeFitStages(const fs::path& data_dir, const FitStageOptions& options) {
  const fs::path cat = data_dir / "cat-poses";
  const fs::path horse = data_dir / "horse-gallop";
  if (!fs::exists(cat / "cat-00.obj")) return ioError(cat.string() + ": cat-poses not found (give --data DIR)");
  std::vector<FitStageRecord> out;
  auto timed = [&](const std::string& name, const ExampleSet& ex) -> Result<PipelineResult> {
    if (options.progress) options.progress("fit " + name);
    ODESKIN_ASSIGN_OR_RETURN(PipelineResult r, fit(ex, 9));
    FitStageRecord record = stageRecord(name, ex, r);
    const int repeats = !options.quick && ex.rest_positions.size() < options.repeat_below_vertices ? options.repeats : 1;
    for (int k = 1; k < repeats; ++k) {
      ODESKIN_ASSIGN_OR_RETURN(const PipelineResult again, fit(ex, 9));
      const FitStageRecord next = stageRecord(name, ex, again);
      record.rig_seconds = std::min(record.rig_seconds, next.rig_seconds);
      record.curve_identification = std::min(record.curve_identification, next.curve_identification);
      record.geometric_transform = std::min(record.geometric_transform, next.geometric_transform);
      record.fourier_and_deformation = std::min(record.fourier_and_deformation, next.fourier_and_deformation);
      record.analytic_solve = std::min(record.analytic_solve, next.analytic_solve);
      record.total = std::min(record.total, next.total);
    }
    out.push_back(record);
    return r;
  };
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet cat2, readObjSequence(numbered(cat, "cat-%02d.obj", {0, 1})));
  ODESKIN_ASSIGN_OR_RETURN(const PipelineResult cat2_fit, timed("cat-poses 00-01", cat2));
  if (!options.quick) {
    ODESKIN_ASSIGN_OR_RETURN(const ExampleSet cat10,
                             readObjSequence(numbered(cat, "cat-%02d.obj", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9})));
    ODESKIN_TRY(timed("cat-poses 00-09", cat10).status());
    ODESKIN_ASSIGN_OR_RETURN(const ExampleSet horse2, readObjSequence(numbered(horse, "horse-%02d.obj", {1, 9})));
    ODESKIN_TRY(timed("horse-gallop 01, 09", horse2).status());
    ODESKIN_ASSIGN_OR_RETURN(const ExampleSet horse7,
                             readObjSequence(numbered(horse, "horse-%02d.obj", {1, 5, 9, 13, 17, 21, 25})));
    ODESKIN_TRY(timed("horse-gallop 01-25 every 4", horse7).status());
  }
  // The scaling curve: the same two cat poses, subdivided, with the first fit's rig given so the
  // curve shows the stages that run per vertex rather than the automatic rig's search.
  ExampleSet level = cat2;
  level.rig = rigOf(cat2_fit.asset);
  const int levels = options.quick ? 1 : options.max_subdivisions;
  for (int l = 0; l <= levels; ++l) {
    if (l > 0) {
      ODESKIN_ASSIGN_OR_RETURN(level, subdivideMidpoint(level));
    }
    ODESKIN_TRY(timed("cat-poses 00-01, given rig, subdivided x" + std::to_string(l), level).status());
  }
  return out;
}

}  // namespace odeskin::bench

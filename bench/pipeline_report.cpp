// SPDX-License-Identifier: MIT
// Measures the fitting pipeline on the datasets of ../shared/data and prints the tables of
// docs/pipeline.md (issue 3, point 7): the Fourier representation error for N = 3, 5, 9 (the
// thesis's Table 6.2 analogue), asset bytes against the key tolerance, and the time per stage
// (the thesis's Table 6.3 analogue).
// Datasets: cylinder, horse-gallop (2 and 7 keys), cat-poses, cheburashka and face-poses (--quick:
// the first two only; --only TEXT: those whose name contains TEXT).
//   odeskin_pipeline_report [DATA_DIR] [--quick] [--only TEXT]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engine/io/asset_file.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "bench/harness/numbered_paths.hpp"
#include "samples/main_guard.hpp"

namespace {

using namespace odeskin;
namespace fs = std::filesystem;
using odeskin::bench::numbered;

struct Dataset {
  std::string name;
  ExampleSet examples;
};

Result<std::vector<Dataset>> loadDatasets(const fs::path& data, bool quick, const std::string& only) {
  std::vector<Dataset> sets;
  const fs::path cyl = data / "cylinder";
  std::vector<fs::path> cyl_poses, cyl_tmats;
  for (int k = 1; k <= 4; ++k) {
    cyl_poses.push_back(cyl / "poses-1" / ("cylinder-" + std::to_string(k) + ".obj"));
    cyl_tmats.push_back(cyl / "poses-1" / ("cylinder-" + std::to_string(k) + ".Tmat"));
  }
  const fs::path weights = cyl / "cylinder.DMAT";
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet cylinder, readLibiglExamples(cyl / "cylinder.obj", cyl_poses, cyl / "cylinder.tgf",
                                                                   &weights, cyl_tmats));
  sets.push_back({"cylinder (given rig, 4 poses)", std::move(cylinder)});
  const auto horse_pair = numbered(data / "horse-gallop", "horse-%02d.obj", {1, 9});
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet horse2, readObjSequence(horse_pair));
  sets.push_back({"horse-gallop frames 1, 9 (auto rig)", std::move(horse2)});
  if (!quick) {
    const auto horse_keys = numbered(data / "horse-gallop", "horse-%02d.obj", {1, 5, 9, 13, 17, 21, 25});
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet horse7, readObjSequence(horse_keys));
    sets.push_back({"horse-gallop frames 1-25 every 4 (auto rig)", std::move(horse7)});
    const auto cat = numbered(data / "cat-poses", "cat-%02d.obj", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet cat10, readObjSequence(cat));
    sets.push_back({"cat-poses 00-09 (auto rig)", std::move(cat10)});
    // Every cheburashka pose (poses-1, poses-2, poses-3) with its libigl rig and transforms.
    const fs::path che = data / "cheburashka";
    std::vector<fs::path> che_poses, che_tmats;
    auto addPose = [&](const fs::path& stem) {
      che_poses.push_back(stem.string() + ".obj");
      che_tmats.push_back(stem.string() + ".Tmat");
    };
    addPose(che / "poses-1" / "cheburashka-1");
    for (const fs::path& p : numbered(che / "poses-2", "cheburashka-%02d", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11})) addPose(p);
    for (const fs::path& p : numbered(che / "poses-3", "cheburashka-%d", {1, 2, 3, 4})) addPose(p);
    const fs::path che_weights = che / "cheburashka.DMAT";
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet cheburashka, readLibiglExamples(che / "cheburashka.obj", che_poses,
                                                                        che / "cheburashka.tgf", &che_weights, che_tmats));
    sets.push_back({"cheburashka (given rig, 16 poses)", std::move(cheburashka)});
    const auto face = numbered(data / "face-poses", "face-%02d.obj", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet face10, readObjSequence(face));
    sets.push_back({"face-poses 00-09 (auto rig)", std::move(face10)});
  }
  if (!only.empty()) {
    std::erase_if(sets, [&](const Dataset& set) { return set.name.find(only) == std::string::npos; });
    if (sets.empty()) return invalidArgument("--only " + only + " names no dataset");
  }
  return sets;
}

Result<PipelineResult> fit(const ExampleSet& ex, int modes, double tolerance) {
  PipelineOptions options;
  options.modes = modes;
  options.key_tolerance = tolerance;
  options.material = skinMaterial();
  return runFitPipeline(ex, options);
}

std::size_t assetBytes(const DeformAsset& asset) {
  Result<std::string> bytes = encodeAsset(asset);
  return bytes.ok() ? bytes->size() : 0;
}

}  // namespace

static int run(int argc, char** argv) {
  std::string data_text = ODESKIN_DATA_DIR;
  bool quick = false;
  std::string only;
  CLI::App app("odeskin_pipeline_report: Fourier error and fitting stages per dataset and N (thesis Tables 6.2, 6.3)");
  app.add_option("data", data_text, "The shared data folder (default " ODESKIN_DATA_DIR ")");
  app.add_flag("--quick", quick, "Fewer datasets");
  app.add_option("--only", only, "Only the datasets whose name contains TEXT");
  CLI11_PARSE(app, argc, argv);
  const fs::path data = data_text;
  Result<std::vector<Dataset>> sets = loadDatasets(data, quick, only);
  if (!sets.ok()) {
    std::fprintf(stderr, "odeskin_pipeline_report: error: %s\n", sets.status().toString().c_str());
    return 1;
  }
  std::printf("## Fourier representation error (before remainders), per dataset and N\n\n");
  std::printf("| dataset | vertices | curves | N | vector coefficients per segment | max error / box | rms error / box | curves with fewer modes |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Dataset& set : *sets) {
    for (int n : {3, 5, 9}) {
      Result<PipelineResult> r = fit(set.examples, n, 1e-4);
      if (!r.ok()) {
        std::fprintf(stderr, "odeskin_pipeline_report: %s: %s\n", set.name.c_str(), r.status().toString().c_str());
        return 1;
      }
      const std::size_t curves = r->asset.curveCount();
      std::printf("| %s | %zu | %zu | %d | %zu | %.2e | %.2e | %zu |\n", set.name.c_str(), r->asset.vertexCount(), curves, n,
                  curves * static_cast<std::size_t>(2 * n + 2), r->report.max_series_error, r->report.rms_series_error,
                  r->report.reduced_curves);
    }
  }
  std::printf("\n## Asset bytes against the key tolerance (N = 9, skin material)\n\n");
  std::printf("| dataset | key tolerance / box | remainders | worst key error / box | asset bytes | all poses (float32) bytes |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const Dataset& set : *sets) {
    const std::size_t pose_bytes = set.examples.poses.size() * set.examples.rest_positions.size() * 3 * sizeof(float);
    for (double tol : {1e-2, 1e-3, 1e-4, 1e-5}) {
      Result<PipelineResult> r = fit(set.examples, 9, tol);
      if (!r.ok()) return 1;
      double worst = 0.0;
      for (double e : r->report.key_error) worst = std::max(worst, e);
      std::printf("| %s | %.0e | %zu | %.2e | %zu | %zu |\n", set.name.c_str(), tol, r->report.remainder_count, worst,
                  assetBytes(r->asset), pose_bytes);
    }
  }
  std::printf("\n## Time per stage (N = 9, seconds, one run)\n\n");
  std::printf("| dataset | rig | curve identification | geometric transform | Fourier + deformation | analytic solve + skin deformer | total |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const Dataset& set : *sets) {
    Result<PipelineResult> r = fit(set.examples, 9, 1e-4);
    if (!r.ok()) return 1;
    const StageTimings& t = r->timings;
    std::printf("| %s | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", set.name.c_str(), t.rig, t.curve_identification,
                t.geometric_transform, t.fourier_and_deformation, t.analytic_solve, t.total);
  }
  return 0;
}

int main(int argc, char** argv) { return odeskin::runGuarded("odeskin_pipeline_report", run, argc, argv); }

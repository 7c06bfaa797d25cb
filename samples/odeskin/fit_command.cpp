// SPDX-License-Identifier: MIT
#include "fit_command.hpp"

#include <algorithm>
#include <cstdio>
#include <system_error>

#include "engine/core/number_text.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/time_basis.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "material_options.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "up_axis.hpp"

namespace odeskin {
namespace {

Result<ExampleSet> readExamples(const FitCommandOptions& o) {
  std::string ignored;
  switch (fitInputKind(o, &ignored)) {
    case FitInputKind::kGltf: {
      GltfPoseRequest request;
      request.mesh = o.mesh;
      request.animation = o.animation;
      request.times = o.times;
      request.morph_targets = o.targets;
      return readGltfExamples(o.inputs.front(), request);
    }
    case FitInputKind::kLibigl: {
      const std::filesystem::path* weights = o.weights.empty() ? nullptr : &o.weights;
      return readLibiglExamples(o.bind, o.inputs, o.rig, weights, o.transforms);
    }
    case FitInputKind::kObj:
      break;
  }
  return readObjSequence(o.inputs, o.bind.empty() ? nullptr : &o.bind);
}

// Every mode's time basis of `material` exists (not resonant, not degenerate), checked before the
// poses are read so a bad --material fails at once and names where it came from (`where`).
Status checkMaterialModes(const Material& material, int terms, const std::string& where) {
  for (int n = 0; n <= terms; ++n) {
    Result<ModeTimeBasis> basis = ModeTimeBasis::create(material, n);
    if (!basis.ok()) return Status(basis.status().code(), where + ": " + basis.status().message());
  }
  return okStatus();
}

void printSummary(std::ostream& out, const FitCommandOptions& o, const ExampleSet& examples,
                  const PipelineResult& result, std::uintmax_t bytes) {
  const DeformAsset& a = result.asset;
  out << "fitted " << examples.poses.size() << " poses: " << a.vertexCount() << " vertices, " << a.faces.faceCount()
      << " faces";
  if (!a.render.empty()) out << " (" << a.render.topology_of_render.size() << " render vertices)";
  out << "\nrig: " << result.rig_summary << "\n";
  out << "curves: " << a.curveCount() << " in " << result.part_count << " part" << (result.part_count == 1 ? "" : "s")
      << ", N = " << a.modes << ", " << a.materials.size() << " material" << (a.materials.size() == 1 ? "" : "s") << "\n";
  double worst = 0.0;
  for (double e : result.report.key_error) worst = std::max(worst, e);
  out << "key error: max " << scientific(worst) << " of the box";
  if (result.report.key_error.size() <= 12) {
    out << " (";
    for (std::size_t k = 0; k < result.report.key_error.size(); ++k) {
      out << (k ? ", " : "") << scientific(result.report.key_error[k]);
    }
    out << ")";
  }
  out << (o.pure_fourier ? ", pure Fourier" : "") << "\n";
  out << "remainders: " << result.report.remainder_count << " (series error before them: max "
      << scientific(result.report.max_series_error) << ", rms " << scientific(result.report.rms_series_error)
      << " of the box)\n";
  if (result.report.ill_conditioned > 0) {
    out << "rigid: " << result.report.ill_conditioned << " vertices whose skinning is near singular at a key "
        << "(nearly opposed bones) follow their dominant bone\n";
  }
  out << "wrote " << o.output.string() << " (" << bytes << " bytes)\n";
}

void printTimings(std::ostream& out, const StageTimings& t) {
  struct Row {
    const char* stage;
    double seconds;
  };
  // The stages of the thesis's Table 6.3, in its order, after the rig (not a stage there).
  const Row rows[] = {{"rig (bones, weights, key transforms)", t.rig},
                      {"curve identification", t.curve_identification},
                      {"geometric transform", t.geometric_transform},
                      {"Fourier representation + deformation calculation", t.fourier_and_deformation},
                      {"analytic solve + skin deformer", t.analytic_solve},
                      {"total", t.total}};
  out << "stage timings (thesis Table 6.3):\n";
  for (const Row& row : rows) {
    char line[128];
    std::snprintf(line, sizeof line, "  %-50s %10.3f ms\n", row.stage, 1e3 * row.seconds);
    out << line;
  }
}

}  // namespace

int runFitCommand(const FitCommandOptions& o, Console& console) {
  if (const std::string problem = fitUsageProblem(o); !problem.empty()) return reportUsage(console, problem);

  PipelineOptions pipeline;
  pipeline.modes = o.terms;
  pipeline.residual_space = o.residual_space;
  pipeline.skinning = o.skinning;
  pipeline.material = *parseMaterial(fitMaterialText(o));
  if (!o.materials_json.empty()) {
    Result<MaterialChoice> choice = readMaterialsJson(o.materials_json, pipeline.material);
    if (!choice.ok()) return reportFailure(console, choice.status());
    pipeline.material = choice->default_material;
    pipeline.part_materials = choice->parts;
    pipeline.part_materials_source = o.materials_json.string();
  }
  const std::string material_source =
      o.materials_json.empty() ? "--material '" + fitMaterialText(o) + "'" : o.materials_json.string();
  if (Status s = checkMaterialModes(pipeline.material, o.terms, material_source); !s.ok()) {
    return reportError(console, "fit: " + s.message(), kExitFailure);
  }
  // MATH.md 5.4: eta/rho < 0 is accepted (the vectors use it) but is not physical; say so once.
  if (!console.quiet && ModeTimeBasis::create(pipeline.material, 0)->negativeDamping()) {
    console.err << "warning: fit: " << material_source << ": eta/rho < 0 (negative damping): motion grows instead of settling\n";
  }
  for (const auto& [part, material] : pipeline.part_materials) {
    if (Status s = checkMaterialModes(material, o.terms, material_source + ": part \"" + part + "\""); !s.ok()) {
      return reportError(console, "fit: " + s.message(), kExitFailure);
    }
  }
  pipeline.key_tolerance = o.key_tolerance;
  pipeline.pure_fourier = o.pure_fourier;
  pipeline.force_auto_rig = o.rig == "auto" || o.rig == "curves";
  pipeline.curve_rig = o.rig == "curves";
  pipeline.curve_rig_up = *curveRigUp(o.rig, o.up);  // fitUsageProblem has checked it
  pipeline.auto_bones = o.bones;
  pipeline.segment_seconds = o.segment_seconds;

  Result<ExampleSet> examples = readExamples(o);
  if (!examples.ok()) return reportFailure(console, examples.status());
  if (o.bones > 0 && examples->rig && !pipeline.force_auto_rig) {
    return reportUsage(console, "fit: --bones applies to the automatic rig, and " + o.inputs.front().string() +
                                    " brings its own skin; add --rig auto to derive the bones from the poses instead");
  }
  if (!console.quiet) {
    for (const std::string& w : examples->warnings) console.err << "warning: fit: " << w << "\n";
  }

  ProgressBar bar(console.err, "fit", 0, !console.quiet && console.interactive);
  pipeline.progress = [&bar](std::string_view stage, double fraction) { bar.fraction(stage, fraction); };
  Result<PipelineResult> result = runFitPipeline(*examples, pipeline);
  bar.finish();
  if (!result.ok()) {
    // Most fit errors name their file; one about the poses together (an automatic rig that finds
    // no motion, say) is given the poses' names so the line still says which input is at fault.
    const std::string& message = result.status().message();
    if (!o.materials_json.empty() && message.rfind(o.materials_json.string() + ": ", 0) == 0) {
      return reportError(console, "fit: " + message, kExitFailure);  // a --materials part no bone has
    }
    const bool named = std::any_of(examples->pose_labels.begin(), examples->pose_labels.end(), [&](const std::string& label) {
      return message.find(label) != std::string::npos;
    });
    if (named || examples->pose_labels.empty()) return reportFailure(console, result.status());
    const std::vector<std::string>& labels = examples->pose_labels;
    const std::string poses = labels.size() == 1 ? labels.front()
                              : labels.size() == 2 ? labels.front() + ", " + labels.back()
                                                   : labels.front() + " ... " + labels.back() + " (" +
                                                         std::to_string(labels.size()) + " poses)";
    return reportError(console, "fit: " + poses + ": " + message, kExitFailure);
  }

  if (!console.quiet) {
    for (const std::string& w : result->warnings) console.err << "warning: fit: " << w << "\n";
  }
  if (Status s = createParentFolder(o.output); !s.ok()) return reportFailure(console, s);
  if (Status saved = saveAsset(o.output, result->asset); !saved.ok()) return reportFailure(console, saved);
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(o.output, ec);
  if (!console.quiet) printSummary(console.out, o, *examples, *result, ec ? 0 : bytes);
  if (o.timings) printTimings(console.out, result->timings);
  return kExitOk;
}

}  // namespace odeskin

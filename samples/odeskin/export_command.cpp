// SPDX-License-Identifier: MIT
#include "export_command.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <system_error>

#include "engine/core/number_text.hpp"
#include "engine/io/asset_file.hpp"
#include "file_extension.hpp"
#include "material_warning.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "quantization_summary.hpp"

namespace odeskin {
namespace {

std::string usageProblem(const ExportCommandOptions& o) {
  if (o.output.empty()) return "export: -o OUT.glb is required";
  const std::string ext = lowerExtension(o.output);
  if (ext == ".gltf") return "export: " + o.output.string() + ": write .glb (one self-contained binary file)";
  if (ext != ".glb") return "export: " + o.output.string() + ": unknown output format '" + ext + "' (expected .glb)";
  if (const std::filesystem::path inputs[] = {o.asset, o.materials}; overwritesInput(o.output, inputs)) {
    return "export: " + o.output.string() + " is an input; it would be overwritten";
  }
  if (!(o.tolerance >= 1e-8 && o.tolerance <= 0.01)) {
    return "export: --tolerance must be in [1e-8, 0.01] (a fraction of the bounding box), got " + numberText(o.tolerance);
  }
  if (o.fps && !(std::isfinite(*o.fps) && *o.fps > 0.0 && *o.fps <= 1000.0)) {
    return "export: --fps must be in (0, 1000], got " + numberText(*o.fps);
  }
  if (!parseKeyInterpolation(o.interpolation)) {
    return "export: --interpolation must be cubic or linear, got '" + o.interpolation + "'";
  }
  return {};
}

// Overall progress of the compact export's stages (their own fractions are coarse).
double stageStart(std::string_view stage) {
  if (stage == "target normals") return 0.2;
  if (stage == "weight keys") return 0.3;
  if (stage == "skeleton keys") return 0.5;
  if (stage == "writing") return 0.8;
  return 0.0;
}

void printMaterials(std::ostream& out, const ExportCommandOptions& o, const GltfExportReport& r) {
  if (o.materials.empty()) return;
  out << "glTF materials: " << r.materials << " with " << r.images << " image" << (r.images == 1 ? "" : "s") << " from "
      << o.materials.string() << "\n";
}

void printQuantization(std::ostream& out, const GltfExportReport& r) {
  if (!r.quantized) return;
  const QuantizationCost relative{r.quantization_step, r.quantization_error, r.normal_quantization_p99_degrees,
                                  r.normal_quantization_max_degrees, r.float_deltas};
  printQuantization(out, relative, 1.0, r.baked ? "frames" : "weight keys");
}

void printSummary(std::ostream& out, const ExportCommandOptions& o, const DeformAsset& asset, const GltfExportReport& r,
                  double fps) {
  const std::size_t segments = asset.segments.size();
  if (r.baked) {
    out << "baked " << o.asset.filename().string() << " -> " << o.output.string() << " (" << r.bytes << " bytes): "
        << r.frames << " frames at " << numberText(fps) << " fps, " << r.vertices
        << " vertices, one morph target per frame, LINEAR cross-fades\n";
    printQuantization(out, r);
    printMaterials(out, o, r);
    return;
  }
  out << "exported " << o.asset.filename().string() << " -> " << o.output.string() << " (" << r.bytes << " bytes): "
      << r.vertices << " vertices, " << r.joints << " joints, " << segments << " segment" << (segments == 1 ? "" : "s")
      << ", N = " << asset.modes << ", " << asset.materials.size() << " material" << (asset.materials.size() == 1 ? "" : "s")
      << "\n";
  out << "morph targets: " << r.morph_targets << " (" << r.sparse_targets << " sparse";
  if (r.merged_fields > 0) out << "; " << r.merged_fields << " mode fields merged into targets with the same curve";
  out << ")\n";
  if (r.target_normals) {
    out << "target normals: exact at the keys; between them, from the exact bind-space normals: mean "
        << fixedText(r.normal_mean_degrees, 2) << " degrees, 99% of vertices within " << fixedText(r.normal_p99_degrees, 2)
        << ", at most " << fixedText(r.normal_max_degrees, 1) << "\n";
  } else {
    out << "target normals: none (viewers shade the skinned base shape)\n";
  }
  const std::string_view keys = gltfInterpolationName(r.interpolation);
  out << "weight keys: " << r.weight_keys << " " << keys << ", max weight error " << scientific(r.max_weight_error)
      << " (position error <= " << scientific(r.weight_position_error) << " of the box)\n";
  out << "skeleton keys: " << r.skeleton_keys << " " << keys << ", position error <= "
      << scientific(r.skeleton_position_error) << " of the box\n";
  out << "mid-segment deviation from the player: <= " << scientific(r.player_deviation)
      << " of the box (key corrections where the fit stored no remainder)\n";
  printQuantization(out, r);
  printMaterials(out, o, r);
  if (r.pruned_vertices == 0) {
    out << "influences: at most " << r.max_influences << " per vertex, written as they are\n";
  } else {
    out << "influences: up to " << r.max_influences << " per vertex; " << r.pruned_vertices
        << " vertices pruned to their 4 largest (LBS error <= " << scientific(r.prune_error) << " of the box at the keys)\n";
  }
}

}  // namespace

int runExportCommand(const ExportCommandOptions& o, Console& console, GltfExportReport* report) {
  if (const std::string problem = usageProblem(o); !problem.empty()) return reportUsage(console, problem);
  Result<DeformAsset> loaded = loadAsset(o.asset);
  if (!loaded.ok()) return reportFailure(console, loaded.status());
  const DeformAsset& asset = *loaded;

  GltfExportOptions options;
  options.bake = o.bake;
  options.bake_fps = o.fps.value_or(30.0);
  options.tolerance = o.tolerance;
  options.target_normals = o.target_normals;
  options.materials = o.materials;
  options.interpolation = *parseKeyInterpolation(o.interpolation);
  options.quantize = o.quantize;
  const std::string reason = compactExportProblem(asset);
  if (reason.empty() && !o.bake && o.fps && !console.quiet) {
    console.err << "note: --fps applies to bakes only; " << o.asset.string()
                << " is exported with per-mode morph targets (add --bake for frames)\n";
  }
  if (!reason.empty() && !o.bake && !console.quiet) {
    console.err << "note: " << o.asset.string() << " cannot be exported with per-mode morph targets: " << reason
                << "; baking one morph target per frame at " << numberText(options.bake_fps) << " fps\n";
  }

  if (Status s = createParentFolder(o.output); !s.ok()) return reportFailure(console, s);
  ProgressBar bar(console.err, "export", 0, !console.quiet && console.interactive);
  options.progress = [&bar](std::string_view stage, double fraction) {
    bar.fraction(stage, stage == "bake" ? fraction : stageStart(stage) + 0.2 * fraction);
  };
  Result<GltfExportReport> result = exportGltf(asset, o.output, options);
  bar.finish();
  if (!result.ok()) {
    // Write errors name the output already; the others are about the asset.
    const Status& s = result.status();
    return reportFailure(console, s.code() == StatusCode::kIoError ? s : Status(s.code(), o.asset.string() + ": " + s.message()));
  }
  if (!console.quiet) {
    printSummary(console.out, o, asset, *result, options.bake_fps);
    warnOfDroppedTextures(console.err, o.asset, o.materials, result->untextured_materials);
  }
  if (report) *report = *result;
  return kExitOk;
}

}  // namespace odeskin

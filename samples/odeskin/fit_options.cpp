// SPDX-License-Identifier: MIT
#include "fit_options.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

#include "engine/core/number_text.hpp"
#include "engine/offline/fourier_fit.hpp"
#include "file_extension.hpp"
#include "material_options.hpp"
#include "output_paths.hpp"
#include "up_axis.hpp"

namespace odeskin {
std::string fitMaterialText(const FitCommandOptions& o) { return o.material.empty() ? "skin" : o.material; }

FitInputKind fitInputKind(const FitCommandOptions& o, std::string* problem) {
  const bool libigl_rig = !o.rig.empty() && o.rig != "auto" && o.rig != "curves";
  const bool gltf_options = !o.times.empty() || !o.targets.empty() || !o.animation.empty() || !o.mesh.empty();
  std::size_t gltf = 0;
  for (const std::filesystem::path& in : o.inputs) {
    const std::string ext = lowerExtension(in);
    if (isGltfFile(in)) {
      ++gltf;
    } else if (ext != ".obj") {
      *problem = "fit: " + in.string() + ": unknown input format '" + ext + "' (expected .obj, .gltf or .glb)";
      return FitInputKind::kObj;
    }
  }
  if (gltf > 0) {
    if (o.inputs.size() != 1) *problem = "fit: give one .gltf/.glb file, or OBJ poses, not both or several";
    else if (libigl_rig) *problem = "fit: --rig SKELETON.tgf applies to OBJ poses; a glTF file brings its own skin";
    else if (!o.bind.empty()) *problem = "fit: --bind applies to OBJ poses; a glTF file's bind mesh is its own";
    else if (!o.weights.empty() || !o.transforms.empty()) {
      *problem = "fit: --weights and --transforms apply to OBJ poses with --rig SKELETON.tgf; a glTF file brings its own skin";
    }
    else if (o.times.empty() && o.targets.empty()) *problem = "fit: a glTF input needs --times a,b,... or --targets i,j,...";
    return FitInputKind::kGltf;
  }
  if (gltf_options) {
    *problem = "fit: --times, --targets, --animation and --mesh apply to a .gltf/.glb input";
  } else if (o.inputs.size() < 2) {
    *problem = "fit: needs at least 2 example poses, got " + std::to_string(o.inputs.size());
  } else if (!libigl_rig && (!o.weights.empty() || !o.transforms.empty())) {
    *problem = "fit: --weights and --transforms need --rig SKELETON.tgf";
  } else if (libigl_rig && o.bind.empty()) {
    *problem = "fit: --rig SKELETON.tgf needs --bind REST.obj (the mesh the skeleton and weights belong to)";
  } else if (libigl_rig && !o.transforms.empty() && o.transforms.size() != o.inputs.size()) {
    *problem = "fit: " + std::to_string(o.transforms.size()) + " --transforms files for " +
               std::to_string(o.inputs.size()) + " poses: give one .Tmat per pose, in the same order";
  }
  return libigl_rig ? FitInputKind::kLibigl : FitInputKind::kObj;
}

std::string fitUsageProblem(const FitCommandOptions& o) {
  if (o.inputs.empty()) return "fit: no example poses given";
  if (o.output.empty()) return "fit: -o ASSET is required";
  if (o.terms < 1 || o.terms > kMaxFourierModes) {
    return "fit: --terms " + std::to_string(o.terms) + " is outside 1.." + std::to_string(kMaxFourierModes);
  }
  if (!(o.key_tolerance > 0.0) || !std::isfinite(o.key_tolerance)) {
    return "fit: --key-tolerance must be a positive fraction of the box, got " + numberText(o.key_tolerance);
  }
  // Below, double precision's own key error (~1e-16 of the box) may not meet it; above, no key is hit.
  if (o.key_tolerance < kMinKeyTolerance || o.key_tolerance > kMaxKeyTolerance) {
    return "fit: --key-tolerance " + numberText(o.key_tolerance) + " is outside [" + numberText(kMinKeyTolerance) + ", " +
           numberText(kMaxKeyTolerance) + "] of the box";
  }
  if (!(o.segment_seconds > 0.0) || !std::isfinite(o.segment_seconds)) return "fit: --segment-seconds must be positive";
  // glTF keeps times in float32, and play counts frames in them; outside this range neither works.
  if (o.segment_seconds < kMinSegmentSeconds || o.segment_seconds > kMaxSegmentSeconds) {
    return "fit: --segment-seconds " + numberText(o.segment_seconds) + " is outside [" + numberText(kMinSegmentSeconds) +
           ", " + numberText(kMaxSegmentSeconds) + "] seconds";
  }
  if (o.bones < 0) return "fit: --bones must be >= 0 (0: chosen from the mesh)";
  if (o.bones > 0 && !o.rig.empty() && o.rig != "auto") return "fit: --bones applies to the automatic rig (--rig auto)";
  if (!o.rig.empty() && o.rig != "auto" && o.rig != "curves" && lowerExtension(o.rig) != ".tgf") {
    return "fit: --rig takes auto or a libigl skeleton (.tgf), or curves, got '" + o.rig + "'";
  }
  if (Result<Vec3> up = curveRigUp(o.rig, o.up); !up.ok()) return "fit: " + up.status().message();
  if (!o.materials_json.empty() && !o.material.empty()) return "fit: give --material or --materials, not both";
  if (Result<Material> m = parseMaterial(fitMaterialText(o)); !m.ok()) return "fit: --material: " + m.status().message();
  std::vector<std::filesystem::path> inputs = o.inputs;
  inputs.insert(inputs.end(), o.transforms.begin(), o.transforms.end());
  for (const std::filesystem::path& p : {o.bind, o.weights, o.materials_json}) inputs.push_back(p);
  if (lowerExtension(o.rig) == ".tgf") inputs.emplace_back(o.rig);
  if (overwritesInput(o.output, inputs)) return "fit: " + o.output.string() + " is an input; it would be overwritten";
  if (const std::string why = folderNotFile(o.output); !why.empty()) return "fit: -o " + o.output.string() + " " + why;
  // A mesh meant as another pose (`fit a.obj b.obj -o c.obj`) would be replaced by the binary asset.
  if (lowerExtension(o.output) != ".odsk") return "fit: -o " + o.output.string() + ": the asset is written as .odsk";
  std::string problem;
  fitInputKind(o, &problem);
  return problem;
}

}  // namespace odeskin

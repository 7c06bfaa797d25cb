// SPDX-License-Identifier: MIT
#include "compare_command.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/core/number_text.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/ply_writer.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/visual/render_shading.h"
#include "engine/visual/vertex_error.hpp"
#include "file_extension.hpp"
#include "output_paths.hpp"
#include "render_inputs.hpp"

namespace odeskin {
namespace {

std::string usageProblem(const CompareOptions& o) {
  if (o.heat_max && !(std::isfinite(*o.heat_max) && *o.heat_max > 0.0)) {
    return "compare: --heat-max must be a positive fraction of the box, got " + numberText(*o.heat_max);
  }
  if (o.heat_max && o.ply.empty()) return "compare: --heat-max needs -o OUT.ply";
  if (o.t && !std::isfinite(*o.t)) return "compare: --t must be a number";
  if (o.t && lowerExtension(o.mesh) == ".obj") {
    return "compare: --t applies to a .odsk or .glb/.gltf MESH; " + o.mesh.string() + " is one pose";
  }
  if (!o.ply.empty() && lowerExtension(o.ply) != ".ply") {
    return "compare: " + o.ply.string() + ": write .ply (a mesh coloured by its error)";
  }
  if (!o.json.empty() && lowerExtension(o.json) != ".json") return "compare: --json " + o.json.string() + ": write .json";
  const std::filesystem::path inputs[] = {o.mesh, o.reference};
  for (const std::filesystem::path& out : {o.ply, o.json}) {
    if (overwritesInput(out, inputs)) return "compare: " + out.string() + " is an input; it would be overwritten";
    if (const std::string why = folderNotFile(out); !why.empty()) return "compare: " + out.string() + " " + why;
  }
  if (sameOutputFile(o.ply, o.json)) {
    return "compare: -o and --json name the same file";
  }
  return {};
}

// The percentile by nearest rank, so it is one of the errors.
double percentile(std::vector<double> errors, double p) {
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(errors.size())));
  const std::size_t k = std::min(errors.size() - 1, rank > 0 ? rank - 1 : 0);
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
  return errors[k];
}

std::array<std::uint8_t, 3> heatRgb(double s) {
  const glm::vec3 c = visual::shader::heatColour(static_cast<float>(s));
  auto byte = [](float x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0F, 1.0F) * 255.0F)); };
  return {byte(c.r), byte(c.g), byte(c.b)};
}

nlohmann::ordered_json toJson(const CompareOptions& o, const CompareReport& r) {
  nlohmann::ordered_json j;
  j["mesh"] = o.mesh.string();
  j["reference"] = o.reference.string();
  j["t"] = o.t ? nlohmann::ordered_json(*o.t) : nlohmann::ordered_json(nullptr);
  j["vertices"] = r.vertices;
  j["box"] = r.box;
  j["max"] = {{"relative", r.max_error}, {"absolute", r.max_error * r.box}, {"vertex", r.max_vertex}};
  j["mean"] = r.mean_error;
  j["rms"] = r.rms_error;
  j["p99"] = r.p99_error;
  if (!o.ply.empty()) j["ply"] = {{"file", o.ply.string()}, {"heat_max", r.heat_max}};
  return j;
}

}  // namespace

int runCompareCommand(const CompareOptions& o, Console& console, CompareReport* report) {
  if (const std::string problem = usageProblem(o); !problem.empty()) return reportUsage(console, problem);
  RenderInputOptions mesh_options;
  mesh_options.t = o.t;
  Result<RenderInput> mesh = loadRenderInput(o.mesh, mesh_options);
  if (!mesh.ok()) return reportFailure(console, mesh.status());
  Result<RenderInput> reference = loadRenderInput(o.reference, RenderInputOptions{});
  if (!reference.ok()) return reportFailure(console, reference.status());
  if (!console.quiet) {
    for (const RenderInput* input : {&*mesh, &*reference}) {
      for (const std::string& warning : input->warnings) console.err << "warning: " << warning << "\n";
    }
  }
  Result<std::vector<double>> errors = visual::relativeVertexErrors(mesh->positions, inVertexOrderOf(*mesh, *reference));
  if (!errors.ok()) {
    return reportError(console, "compare: " + o.mesh.string() + " against " + o.reference.string() + ": " +
                                    errors.status().message(), kExitFailure);
  }

  CompareReport r;
  r.vertices = errors->size();
  r.box = longestBoxSide(reference->positions);
  for (std::size_t i = 0; i < errors->size(); ++i) {
    if ((*errors)[i] > r.max_error) r.max_error = (*errors)[i], r.max_vertex = i;
  }
  // Sums of errors over the largest one: errors of a vertex far outside a small box are finite, yet
  // their squares (or their sum) would overflow.
  const double scale = r.max_error > 0.0 ? r.max_error : 1.0;
  double sum = 0.0, squares = 0.0;
  for (const double e : *errors) {
    sum += e / scale;
    squares += (e / scale) * (e / scale);
  }
  r.mean_error = scale * (sum / static_cast<double>(r.vertices));
  r.rms_error = scale * std::sqrt(squares / static_cast<double>(r.vertices));
  r.p99_error = percentile(*errors, 0.99);
  if (!std::isfinite(r.max_error * r.box)) {
    return reportError(console, "compare: " + o.mesh.string() + " against " + o.reference.string() + ": the box (" +
                                    numberText(r.box) + ") or the largest distance (vertex " + std::to_string(r.max_vertex) +
                                    ") is beyond double's range", kExitFailure);
  }

  for (const std::filesystem::path& out : {o.ply, o.json}) {
    if (Status s = createParentFolder(out); !s.ok()) return reportFailure(console, s);
  }
  WrittenOutputs written;
  if (!o.ply.empty()) {
    // A mesh equal to its reference still gets a usable range (every vertex at the bottom colour).
    r.heat_max = o.heat_max.value_or(std::max(r.max_error, 1e-9));
    std::vector<std::array<std::uint8_t, 3>> colours(r.vertices);
    std::vector<float> quality(r.vertices);
    for (std::size_t i = 0; i < r.vertices; ++i) {
      colours[i] = heatRgb((*errors)[i] / r.heat_max);
      quality[i] = static_cast<float>((*errors)[i]);
    }
    const std::string comment = "odeskin compare: colour = error / " + numberText(r.heat_max) +
                                " of the box (blue 0, red at or above it); quality = error / box";
    if (Status s = writePly(o.ply, mesh->positions, mesh->faces, PlyVertexData{colours, quality}, comment); !s.ok()) {
      return reportFailure(console, s);
    }
    written.add(o.ply);
  }
  if (!o.json.empty()) {
    if (Status s = writeFileAtomically(o.json, toJson(o, r).dump(2) + "\n"); !s.ok()) {
      return reportFailure(console, written.undo(s));
    }
  }
  if (!console.quiet) {
    console.out << mesh->label << " against " << reference->label << ": " << r.vertices << " vertices, box "
                << numberText(r.box) << " (longest side)\n";
    console.out << "max error (MVE): " << percentText(r.max_error) << " of the box (" << numberText(r.max_error * r.box)
                << ") at vertex " << r.max_vertex << "\n";
    console.out << "mean " << percentText(r.mean_error) << ", RMS " << percentText(r.rms_error) << ", 99% of vertices within "
                << percentText(r.p99_error) << "\n";
    if (!o.ply.empty()) {
      console.out << "wrote " << o.ply.string() << " (colours from 0 to " << percentText(r.heat_max) << " of the box)\n";
    }
  }
  if (report) *report = r;
  return kExitOk;
}

}  // namespace odeskin

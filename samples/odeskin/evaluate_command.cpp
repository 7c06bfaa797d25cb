// SPDX-License-Identifier: MIT
#include "evaluate_command.hpp"

#include <cstdio>
#include <optional>
#include <sstream>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/evaluation/evaluation.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/fourier_fit.hpp"
#include "output_paths.hpp"
#include "render_command.hpp"
#include "render_session.hpp"
#include "up_axis.hpp"

namespace odeskin {
namespace {

using Json = nlohmann::ordered_json;

// "all" or a comma list; *problem names the first unknown or repeated name.
std::vector<BaselineMethod> parseMethods(const std::string& text, std::string* problem) {
  std::vector<BaselineMethod> methods;
  if (text == "all") {
    for (std::uint32_t m = 0; m < kBaselineMethodCount; ++m) methods.push_back(static_cast<BaselineMethod>(m));
    return methods;
  }
  std::stringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    BaselineMethod method{};
    if (name.empty()) {
      *problem = "evaluate: --methods '" + text + "' has an empty name (a comma too many)";
      return {};
    }
    if (!parseBaselineMethod(name, &method)) {
      *problem = "evaluate: unknown method '" + name +
                 "' (all, or a comma list of linear, lbs, dqs, psd_lbs, psd_dqs, fd_curve, odeskin_static, "
                 "odeskin_dynamic)";
      return {};
    }
    for (const BaselineMethod seen : methods) {
      if (seen == method) {
        *problem = "evaluate: method '" + name + "' is listed twice";
        return {};
      }
    }
    methods.push_back(method);
  }
  if (methods.empty()) *problem = "evaluate: --methods names no method";
  return methods;
}

Json toJson(const EvaluationResult& r) {
  Json frames = Json::array();
  for (const EvaluatedFrame& f : r.frames) {
    Json methods = Json::object();
    for (std::size_t m = 0; m < r.methods.size(); ++m) {
      const MethodFrameScore& s = f.scores[m];
      methods[std::string(baselineMethodName(r.methods[m]))] = {{"mve", s.mve}, {"mean", s.mean},
                                                                {"ms_per_frame", s.ms_per_frame}};
    }
    frames.push_back({{"frame", f.frame}, {"t", f.t}, {"methods", std::move(methods)}});
  }
  Json summary = Json::object();
  for (std::size_t m = 0; m < r.methods.size(); ++m) {
    summary[std::string(baselineMethodName(r.methods[m]))] = {{"mve_max", r.summary[m].mve_max},
                                                              {"mean_mean", r.summary[m].mean_mean}};
  }
  return {{"pose_source", std::string(poseSourceName(r.pose_source))}, {"rig", r.rig_summary}, {"bones", r.bone_count},
          {"frames", std::move(frames)}, {"summary", std::move(summary)}, {"notes", r.notes}};
}

void printTable(std::ostream& out, const EvaluationResult& r) {
  char line[160];
  out << "rig: " << r.rig_summary << "\n";
  std::snprintf(line, sizeof line, "curves: %zu, N = %d, fit %.1f s; %zu in-between frames, pose source %s\n",
                r.curve_count, r.modes, r.fit_seconds, r.frames.size(), std::string(poseSourceName(r.pose_source)).c_str());
  out << line;
  std::snprintf(line, sizeof line, "%-16s %10s %10s %12s %12s\n", "method", "mean %", "MVE %", "ms/frame", "set-up ms");
  out << line;
  for (std::size_t m = 0; m < r.methods.size(); ++m) {
    const MethodSummary& s = r.summary[m];
    std::snprintf(line, sizeof line, "%-16s %10.4f %10.4f %12.3f %12.1f\n",
                  std::string(baselineMethodName(r.methods[m])).c_str(), 100.0 * s.mean_mean, 100.0 * s.mve_max,
                  s.ms_per_frame, s.setup_ms);
    out << line;
  }
  for (const std::string& note : r.notes) out << "note: " << note << "\n";
}

std::string frameName(std::uint32_t frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04u", frame);
  return name;
}

// One picture per in-between frame: a panel per method, heat = distance to the ground truth.
int drawHeatMaps(const EvaluateCommandOptions& o, const EvaluationResult& r, Console& console, const std::string& device,
                 RenderSession& session, WrittenOutputs& written) {
  for (const EvaluatedFrame& f : r.frames) {
    RenderOptions render;
    render.output = (o.png_dir / (frameName(f.frame) + ".png")).string();
    render.heat = o.frames[f.frame];
    render.device = device;
    for (std::size_t m = 0; m < r.methods.size(); ++m) {
      const std::string name(baselineMethodName(r.methods[m]));
      render.inputs.push_back(o.png_dir / "obj" / (frameName(f.frame) + "_" + name + ".obj"));
      render.labels.push_back(name);  // the panel adds its max and mean error (of the longest box side)
    }
    render.size = std::to_string(360 * r.methods.size()) + "x400";
    Console quiet{console.out, console.err, true, false};
    if (const int code = runRenderCommand(render, quiet, nullptr, &session); code != kExitOk) return code;
    written.add(render.output);
    if (!console.quiet) console.out << "wrote " << render.output << "\n";
  }
  return kExitOk;
}

}  // namespace

int runEvaluateCommand(const EvaluateCommandOptions& o, Console& console, const std::string& device) {
  std::string problem;
  const std::vector<BaselineMethod> methods = parseMethods(o.methods, &problem);
  // cppcheck-suppress knownConditionTrueFalse ; false positive: parseMethods sets problem through its pointer
  if (!problem.empty()) return reportUsage(console, problem);
  PoseSource source{};
  if (!parsePoseSource(o.pose_source, &source)) {
    return reportUsage(console, "evaluate: --pose-source must be truth or keys, not '" + o.pose_source + "'");
  }
  if (o.frames.size() < 2) return reportUsage(console, "evaluate: give at least 2 frames");
  if (o.skeleton_fit != "rigid" && o.skeleton_fit != "lbs") {
    return reportUsage(console, "evaluate: --skeleton-fit must be rigid or lbs, not '" + o.skeleton_fit + "'");
  }
  if (o.terms < 1 || o.terms > kMaxFourierModes) {
    return reportUsage(console, "evaluate: --terms must be in [1, " + std::to_string(kMaxFourierModes) + "]");
  }
  const bool libigl_rig = !o.rig.empty() && o.rig != "auto" && o.rig != "curves";
  if (libigl_rig && o.bind.empty()) return reportUsage(console, "evaluate: --rig SKELETON.tgf needs --bind REST.obj");
  if (!libigl_rig && (!o.bind.empty() || !o.weights.empty())) {
    return reportUsage(console, "evaluate: --bind and --weights apply to --rig SKELETON.tgf");
  }
  if (o.bones != 0 && !o.rig.empty() && o.rig != "auto") {
    return reportUsage(console, "evaluate: --bones applies to the automatic rig (--rig auto)");
  }
  const Result<Vec3> up = curveRigUp(o.rig, o.up);
  if (!up.ok()) return reportUsage(console, "evaluate: " + up.status().message());
  std::vector<std::filesystem::path> inputs = o.frames;
  inputs.push_back(o.bind);
  inputs.push_back(o.weights);
  if (libigl_rig) inputs.emplace_back(o.rig);
  if (overwritesInput(o.json, inputs)) {
    return reportUsage(console, "evaluate: " + o.json.string() + " is an input; it would be overwritten");
  }
  if (const std::string why = folderNotFile(o.json); !why.empty()) {
    return reportUsage(console, "evaluate: --json " + o.json.string() + " " + why);
  }
  std::vector<std::uint32_t> keys;
  for (const int k : o.keys) {
    if (k < 0) return reportUsage(console, "evaluate: key " + std::to_string(k) + " is negative");
    keys.push_back(static_cast<std::uint32_t>(k));
  }
  // Keys and times are checked against the frame count before any file is read.
  if (Result<std::vector<InBetween>> ib = inBetweenFrames(o.frames.size(), keys, o.times); !ib.ok()) {
    return reportUsage(console, ib.status().message());
  } else if (ib->empty()) {
    return reportUsage(console, "evaluate: the keys leave no in-between frame to score");
  }

  Result<ExampleSet> frames = [&]() -> Result<ExampleSet> {
    if (libigl_rig) {
      const std::filesystem::path* weights = o.weights.empty() ? nullptr : &o.weights;
      return readLibiglExamples(o.bind, o.frames, o.rig, weights, {});
    }
    return readObjSequence(o.frames);
  }();
  if (!frames.ok()) return reportFailure(console, frames.status());

  EvaluationOptions options;
  options.pipeline.modes = o.terms;
  options.pipeline.force_auto_rig = o.rig == "auto" || o.rig == "curves";
  options.pipeline.curve_rig = o.rig == "curves";
  options.pipeline.curve_rig_up = *up;
  options.pipeline.auto_bones = o.bones;
  options.skeleton_fit = o.skeleton_fit == "lbs" ? SkeletonFit::kLbsOptimal : SkeletonFit::kPerBoneRigid;
  std::optional<RenderSession> pictures;  // --png: opened once for every heat map
  WrittenOutputs written;                  // a failure part way removes the files already written
  if (!o.png_dir.empty()) {
    // The heat maps are drawn last; a missing device must fail before the JSON and OBJs are written.
    RenderOptions look;
    look.device = device;
    Result<RenderSession> session = openRenderSession(look);
    if (!session.ok()) {
      return reportFailure(console, Status(session.status().code(), "evaluate: --png: " + session.status().message()));
    }
    pictures.emplace(std::move(session).value());
    std::error_code made;
    std::filesystem::create_directories(o.png_dir / "obj", made);
    if (made) return reportFailure(console, ioError((o.png_dir / "obj").string() + ": cannot create directory: " + made.message()));
    const ExampleSet& topology = *frames;
    options.on_frame = [&o, &topology, &written](std::uint32_t frame, BaselineMethod method,
                                                 std::span<const Vec3> deformed) {
      const std::string name(baselineMethodName(method));
      const std::filesystem::path file = o.png_dir / "obj" / (frameName(frame) + "_" + name + ".obj");
      ODESKIN_TRY(writeObj(file, deformed, topology.faces, name + " at " + o.frames[frame].filename().string()));
      written.add(file);
      return okStatus();
    };
  }
  Result<EvaluationResult> result = runEvaluation(*frames, keys, methods, source, o.times, options);
  if (!result.ok()) return reportFailure(console, written.undo(result.status()));

  if (Status st = createParentFolder(o.json); !st.ok()) return reportFailure(console, written.undo(st));
  if (Status st = writeFileAtomically(o.json, toJson(*result).dump(2) + "\n"); !st.ok()) {
    return reportFailure(console, written.undo(st));
  }
  written.add(o.json);
  if (!console.quiet) {
    printTable(console.out, *result);
    console.out << "wrote " << o.json.string() << "\n";
  }
  if (pictures) {
    if (const int code = drawHeatMaps(o, *result, console, device, *pictures, written); code != kExitOk) {
      written.removeAll();
      return code;
    }
  }
  return kExitOk;
}

}  // namespace odeskin

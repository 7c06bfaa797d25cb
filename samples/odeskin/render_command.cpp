// SPDX-License-Identifier: MIT
#include "render_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <system_error>
#include <tuple>

#include "engine/core/number_text.hpp"
#include "engine/core/position_box.hpp"
#include "engine/visual/compose.hpp"
#include "engine/visual/png_writer.hpp"
#include "engine/visual/vertex_error.hpp"
#include "output_paths.hpp"
#include "play_command.hpp"
#include "progress.hpp"
#include "render_inputs.hpp"
#include "render_session.hpp"
#include "file_extension.hpp"
#include "up_axis.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxTurntable = 3600;
constexpr std::uint32_t kStripColumns = 6;
constexpr std::uint32_t kStripWidth = 1536;  // pixels across a contact sheet row at most
constexpr double kMinHeatMax = 1e-30;        // well inside float's normal range

bool hasPngExtension(const std::string& name) {
  return lowerExtension(name) == ".png";
}

// Checks that need no file; empty when the options are usable.
std::string usageProblem(const RenderOptions& o) {
  if (o.inputs.empty()) return "render: give at least one INPUT (.obj, .gltf, .glb or .odsk)";
  if (o.output.empty()) return "render: -o OUT.png is required";
  if (!hasPngExtension(o.output)) return "render: " + o.output + ": the output must be a .png file";
  if (!o.strip.empty() && !hasPngExtension(o.strip)) return "render: --strip " + o.strip + ": must be a .png file";
  if (!o.strip.empty() && o.turntable == 0) return "render: --strip needs --turntable N";
  if (o.turntable > kMaxTurntable) return "render: --turntable " + std::to_string(o.turntable) + " is above 3600 frames";
  if (o.t && !std::isfinite(*o.t)) return "render: --t must be a finite number";
  if (o.heat_max && !(std::isfinite(*o.heat_max) && *o.heat_max > 0.0)) {
    return "render: --heat-max must be positive (a fraction of the reference's longest box side, 0.01 = 1%)";
  }
  // The renderer scales in float: a denormal would become 0 there.
  if (o.heat_max && *o.heat_max < kMinHeatMax) {
    return "render: --heat-max " + numberText(*o.heat_max) + " is below " + numberText(kMinHeatMax) +
           " (a fraction of the reference's longest box side)";
  }
  if (o.heat_max && !o.heat) return "render: --heat-max needs --heat REF";
  if (o.samples == 0 || o.samples > 64) return "render: --samples must lie in [1, 64]";
  if (!o.size.empty()) {
    if (Result<std::pair<std::uint32_t, std::uint32_t>> s = parseImageSize(o.size); !s.ok()) {
      return "render: " + s.status().message();
    }
  }
  if (Result<visual::Rgba8> c = parseColour(o.background); !c.ok()) return "render: --background " + c.status().message();
  Result<Vec3> up = parseUpAxis(o.up);
  if (!up.ok()) return "render: " + up.status().message();
  visual::ViewSpec view;
  view.up = *up;
  view.azimuth_deg = o.azimuth_deg;
  view.elevation_deg = o.elevation_deg;
  view.fov_y_deg = o.fov_deg;
  if (Status s = visual::validateViewSpec(view); !s.ok()) return "render: " + s.message();
  bool any_asset = false, any_timed = false;
  for (const std::filesystem::path& input : o.inputs) {
    Result<RenderInputKind> kind = renderInputKind(input);
    if (!kind.ok()) return "render: " + kind.status().message();
    any_asset = any_asset || *kind == RenderInputKind::kAsset;
    any_timed = any_timed || *kind != RenderInputKind::kObj;
  }
  if (o.curves && !any_asset) return "render: --curves needs a .odsk input (only assets carry iso-parametric curves)";
  if (o.lbs && !any_asset) return "render: --lbs needs a .odsk input (the skinning of a fitted asset)";
  if (o.turntable > 0 && o.output.find('%') != std::string::npos) {
    if (Result<FramePattern> p = FramePattern::parse(o.output); !p.ok()) return "render: " + p.status().message();
  }
  if (o.turntable == 0 && FramePattern::parse(o.output).ok()) {
    return "render: -o " + o.output + " is a frame pattern: add --turntable N for frames, or name one picture";
  }
  if (o.t && !any_timed) {
    return "render: --t applies to a .odsk or .glb/.gltf input; the inputs are OBJ poses, which have no time";
  }
  return {};
}

// --turntable names: OUT as a pattern when it has a % conversion, else OUT's stem + _NNN.
std::vector<std::filesystem::path> frameNames(const std::string& output, std::size_t count) {
  std::vector<std::filesystem::path> names;
  if (output.find('%') != std::string::npos) {
    const FramePattern pattern = *FramePattern::parse(output);
    for (std::size_t f = 0; f < count; ++f) names.emplace_back(pattern.format(f));
    return names;
  }
  const std::filesystem::path path(output);
  for (std::size_t f = 0; f < count; ++f) {
    char number[32];
    std::snprintf(number, sizeof number, "_%03zu", f);
    names.push_back(path.parent_path() / (path.stem().string() + number + path.extension().string()));
  }
  return names;
}

// The first picture that would replace an input (or, for --strip, one of the frames); "" when none.
std::string outputClash(const RenderOptions& o) {
  std::vector<std::filesystem::path> inputs = o.inputs;
  if (o.heat) inputs.push_back(*o.heat);
  const std::vector<std::filesystem::path> files =
      o.turntable > 0 ? frameNames(o.output, o.turntable) : std::vector<std::filesystem::path>{o.output};
  for (const std::filesystem::path& file : files) {
    if (overwritesInput(file, inputs)) return file.string() + " is an input; it would be overwritten";
    if (sameOutputFile(file, o.strip)) return "--strip " + o.strip + " is also the name of a turntable frame";
  }
  if (overwritesInput(o.strip, inputs)) return o.strip + " is an input; it would be overwritten";
  return {};
}

Status writePicture(const std::filesystem::path& path, const visual::Image& image) {
  if (const std::filesystem::path parent = path.parent_path(); !parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) return ioError(parent.string() + ": cannot create directory: " + ec.message());
  }
  return visual::writePng(path, image);
}

bool samePath(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  const bool same = std::filesystem::equivalent(a, b, ec);
  return !ec && same;
}

struct Panels {
  std::vector<PanelGeometry> geometry;
  visual::Bounds bounds;
  std::vector<Vec3> points;  // every panel's vertices: the camera frames them all
  std::optional<double> heat_max;
  std::vector<double> max_errors;
  std::vector<std::string> warnings;  // the inputs' readers'
};

// Loads every input (with its skin-only twin under --lbs), computes heat values against --heat
// and the union box. Returns the exit code on failure through `code`.
Result<Panels> loadPanels(const RenderOptions& o, int& code) {
  code = kExitFailure;
  std::vector<RenderInput> inputs;
  std::vector<bool> skin_only_flags;
  std::vector<std::string> warnings;
  for (const std::filesystem::path& path : o.inputs) {
    RenderInputOptions options;
    options.t = o.t;
    const bool asset = *renderInputKind(path) == RenderInputKind::kAsset;
    for (bool skin_only : {true, false}) {
      if (skin_only && !(o.lbs && asset)) continue;
      options.skin_only = skin_only;
      Result<RenderInput> input = loadRenderInput(path, options);
      if (!input.ok()) {
        if (input.status().code() == StatusCode::kOutOfRange) code = kExitUsage;
        return input.status();
      }
      // Framing measures lengths: a mesh too large for them fails here, naming its file.
      ODESKIN_TRY(checkedPositionBox(input->positions, path.string()).status());
      if (!skin_only) warnings.insert(warnings.end(), input->warnings.begin(), input->warnings.end());
      inputs.push_back(std::move(input).value());
      skin_only_flags.push_back(skin_only);
    }
  }
  if (!o.labels.empty() && o.labels.size() != inputs.size()) {
    code = kExitUsage;
    return invalidArgument("--labels gives " + std::to_string(o.labels.size()) + " names for " +
                           std::to_string(inputs.size()) + " panels");
  }
  std::optional<RenderInput> reference;
  if (o.heat) {
    ODESKIN_ASSIGN_OR_RETURN(RenderInput ref, loadRenderInput(*o.heat, RenderInputOptions{o.t, false}));
    ODESKIN_TRY(checkedPositionBox(ref.positions, "--heat: " + o.heat->string()).status());
    for (const std::string& w : ref.warnings) {
      if (std::find(warnings.begin(), warnings.end(), w) == warnings.end()) warnings.push_back(w);
    }
    reference = std::move(ref);
  }

  Panels panels;
  panels.warnings = std::move(warnings);
  double worst = 0.0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    RenderInput& input = inputs[i];
    panels.bounds.add(visual::boundsOf(input.positions));
    panels.points.insert(panels.points.end(), input.positions.begin(), input.positions.end());
    std::vector<double> heat;
    std::string note;
    if (reference && !skin_only_flags[i] && samePath(input.path, *o.heat)) {
      note = "reference";
    } else if (reference) {
      Result<std::vector<double>> errors =
          visual::relativeVertexErrors(input.positions, inVertexOrderOf(input, *reference));
      if (!errors.ok()) {
        return invalidArgument("--heat: " + input.path.string() + ": " + errors.status().message() + " (" +
                               o.heat->string() + ")");
      }
      heat = std::move(errors).value();
      double sum = 0.0;
      double max = 0.0;
      for (double e : heat) {
        sum += e;
        max = std::max(max, e);
      }
      worst = std::max(worst, max);
      panels.max_errors.push_back(max);
      note = "max " + percentText(max) + "  mean " + percentText(heat.empty() ? 0.0 : sum / double(heat.size()));
    }
    Result<PanelGeometry> geometry =
        preparePanel(input.path.string(), std::move(input.positions), input.faces, o.curves ? &input.curves : nullptr);
    if (!geometry.ok()) return geometry.status();
    geometry->heat = std::move(heat);
    geometry->label = {o.labels.empty() ? input.label : o.labels[i]};
    if (!note.empty()) geometry->label.push_back(note);
    panels.geometry.push_back(std::move(geometry).value());
  }
  // A heat map of identical meshes still needs a scale: one millionth of the box side.
  if (reference) panels.heat_max = o.heat_max.value_or(std::max(worst, 1e-6));
  return panels;
}

Result<visual::PictureLayout> pictureLayout(const RenderOptions& o, const Panels& panels) {
  visual::PictureSpec spec;
  spec.width = 0;  // 720 per panel plus the colour bar
  spec.height = 540;
  if (!o.size.empty()) std::tie(spec.width, spec.height) = *parseImageSize(o.size);
  spec.panels = panels.geometry.size();
  spec.heat_max = panels.heat_max;
  const bool labelled = !o.no_labels && (panels.heat_max || panels.geometry.size() > 1 || !o.labels.empty());
  spec.label_lines = !labelled ? 0 : (panels.heat_max ? 2 : 1);
  return visual::layoutPicture(spec);
}

// One camera per picture. A still is framed as tightly as its view allows; a turntable keeps the
// model centred on its axis at one distance.
Result<std::vector<visual::Camera>> pictureCameras(const RenderOptions& o, const Panels& panels,
                                                   const visual::PictureLayout& layout) {
  visual::ViewSpec view;
  view.up = *parseUpAxis(o.up);
  view.azimuth_deg = o.azimuth_deg;
  view.elevation_deg = o.elevation_deg;
  view.fov_y_deg = o.fov_deg;
  const double aspect = double(layout.panel_width) / double(layout.panel_height);
  if (o.turntable > 0) {
    std::vector<double> azimuths;
    for (std::size_t f = 0; f < o.turntable; ++f) azimuths.push_back(360.0 * double(f) / double(o.turntable));
    return visual::turntableCameras(panels.points, aspect, view, azimuths);
  }
  ODESKIN_ASSIGN_OR_RETURN(visual::Camera still, visual::framePoints(panels.points, aspect, view));
  return std::vector<visual::Camera>{still};
}

void printSummary(const RenderOptions& o, const Panels& panels, const RenderReport& r, std::size_t frames,
                  std::ostream& out) {
  // A device without the asked count draws with the largest one below it; say so rather than hide it.
  char lowered[96] = "";
  if (r.samples < o.samples) {
    std::snprintf(lowered, sizeof lowered, " (%u asked; the most the device offers up to that)", o.samples);
  }
  char line[400];
  std::snprintf(line, sizeof line, "%u x %u, %zu panel%s, %u sample%s per pixel%s, %.1f ms per picture on %s\n", r.width,
                r.height, r.panels, r.panels == 1 ? "" : "s", r.samples, r.samples == 1 ? "" : "s", lowered,
                1e3 * r.mean_frame_seconds, r.device.c_str());
  out << (frames == 1 ? r.files.front().string()
                      : std::to_string(frames) + " frames: " + r.files.front().string() + " ... " +
                            r.files[frames - 1].string())
      << ": " << line;
  if (!o.strip.empty()) out << "strip: " << o.strip << "\n";
  if (panels.heat_max) {
    out << "heat: error / longest box side of " << o.heat->filename().string() << ", colour bar 0 to "
        << percentText(*panels.heat_max) << (panels.max_errors.empty() ? "" : ";");
    for (double e : panels.max_errors) out << " max " << percentText(e);
    out << "\n";
  }
}

}  // namespace

Result<RenderSession> openRenderSession(const RenderOptions& o) {
  ODESKIN_ASSIGN_OR_RETURN(const visual::Rgba8 background, parseColour(o.background));
  vk::PictureStyle style;
  style.background = background;
  style.samples = o.samples;
  return RenderSession::open(o.device, o.validation, style);
}

int runRenderCommand(const RenderOptions& o, Console& console, RenderReport* report, RenderSession* session) {
  if (const std::string problem = usageProblem(o); !problem.empty()) return reportUsage(console, problem);
  if (const std::string clash = outputClash(o); !clash.empty()) return reportUsage(console, "render: " + clash);

  int load_code = kExitFailure;
  Result<Panels> loaded = loadPanels(o, load_code);
  if (!loaded.ok()) return reportError(console, "render: " + loaded.status().message(), load_code);
  const Panels& panels = *loaded;
  if (!console.quiet) {
    for (const std::string& w : panels.warnings) console.err << "warning: render: " << w << "\n";
  }
  Result<visual::PictureLayout> layout = pictureLayout(o, panels);
  if (!layout.ok()) return reportUsage(console, "render: " + layout.status().message());
  Result<std::vector<visual::Camera>> cameras = pictureCameras(o, panels, *layout);
  if (!cameras.ok()) return reportUsage(console, "render: " + cameras.status().message());

  std::optional<RenderSession> own;  // when the caller gave none
  if (session == nullptr) {
    Result<RenderSession> opened = openRenderSession(o);
    if (!opened.ok()) return reportFailure(console, Status(opened.status().code(), "render: " + opened.status().message()));
    session = &own.emplace(std::move(opened).value());
  }

  std::vector<vk::PanelContent> contents;
  for (const PanelGeometry& g : panels.geometry) contents.push_back(g.content());
  const std::vector<std::filesystem::path> files =
      o.turntable > 0 ? frameNames(o.output, o.turntable) : std::vector<std::filesystem::path>{o.output};
  std::vector<visual::Image> frames;  // kept for --strip
  ProgressBar bar(console.err, "render", files.size(), !console.quiet && console.interactive && files.size() > 1);
  double draw_seconds = 0.0;
  WrittenOutputs written;  // a turntable that fails part way leaves none of its frames
  for (std::size_t f = 0; f < files.size(); ++f) {
    const Clock::time_point start = Clock::now();
    Result<visual::Image> picture = session->draw(*layout, (*cameras)[f], panels.bounds.diagonal(), contents);
    if (!picture.ok()) {
      return reportFailure(console, written.undo(Status(picture.status().code(), "render: " + picture.status().message())));
    }
    draw_seconds += std::chrono::duration<double>(Clock::now() - start).count();
    if (Status s = writePicture(files[f], *picture); !s.ok()) return reportFailure(console, written.undo(s));
    written.add(files[f]);
    if (!o.strip.empty()) frames.push_back(std::move(picture).value());
    bar.step(f + 1);
  }
  bar.finish();
  RenderReport result;
  result.files = files;
  if (!o.strip.empty()) {
    const std::uint32_t columns = visual::balancedColumns(frames.size(), kStripColumns);
    const std::uint32_t thumb = std::min(layout->width, kStripWidth / columns);
    const visual::Image sheet = visual::contactSheet(frames, columns, thumb, 4, *parseColour(o.background));
    if (Status s = writePicture(o.strip, sheet); !s.ok()) return reportFailure(console, written.undo(s));
    result.files.emplace_back(o.strip);
    written.add(o.strip);
  }
  if (Status s = session->checkValidation(); !s.ok()) return reportFailure(console, written.undo(s));

  result.width = layout->width;
  result.height = layout->height;
  result.panels = panels.geometry.size();
  result.mean_frame_seconds = draw_seconds / double(files.size());
  result.heat_max = panels.heat_max;
  result.max_errors = panels.max_errors;
  result.device = session->deviceName();
  result.samples = session->samples();
  if (!console.quiet) printSummary(o, panels, result, files.size(), console.out);
  if (report) *report = std::move(result);
  return kExitOk;
}

}  // namespace odeskin

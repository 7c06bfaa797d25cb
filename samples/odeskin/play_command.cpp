// SPDX-License-Identifier: MIT
#include "material_warning.hpp"
#include "output_paths.hpp"
#include "play_command.hpp"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "engine/core/number_text.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/io/gltf_baked_writer.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/point_cache.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/visual/compose.hpp"
#include "engine/visual/png_writer.hpp"
#include "file_extension.hpp"
#include "progress.hpp"
#include "quantization_summary.hpp"
#include "render_session.hpp"

namespace odeskin {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxFrames = 1000000;  // a typo like --fps 30000 --seconds 600 stops here
constexpr std::size_t kMaxPatternWidth = 32;

// --png DIR's picture of frame f. Not through FramePattern: a % in DIR is part of its name.
std::filesystem::path pngFrameName(const std::filesystem::path& png_dir, std::size_t frame) {
  std::string number = std::to_string(frame);
  if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
  return png_dir / ("frame_" + number + ".png");
}

// The option checks that need no asset; empty when the options are usable.
std::string usageProblem(const PlayOptions& o) {
  if (o.t.has_value() == o.fps.has_value()) return "play: give either --t T (one frame) or --fps F (a sequence)";
  if (o.seconds && !o.fps) return "play: --seconds needs --fps";
  if (o.output.empty() && o.png_dir.empty()) {
    return "play: -o OUT is required (.obj, .glb, .pc2 or .mdd), or --png DIR for pictures only";
  }
  if (o.t && !std::isfinite(*o.t)) return "play: --t must be a number in [0, K-1]";
  if (o.fps && !(std::isfinite(*o.fps) && *o.fps > 0.0)) return "play: --fps must be positive, got " + numberText(*o.fps);
  if (o.seconds && !(std::isfinite(*o.seconds) && *o.seconds >= 0.0)) {
    return "play: --seconds must be zero or positive, got " + numberText(*o.seconds);
  }
  if (!o.png_dir.empty()) {
    if (Result<std::pair<std::uint32_t, std::uint32_t>> size = parseImageSize(o.png_size); !size.ok()) {
      return "play: " + size.status().message();
    }
    visual::ViewSpec view;
    view.azimuth_deg = o.png_azimuth_deg;
    view.elevation_deg = o.png_elevation_deg;
    if (Status s = visual::validateViewSpec(view); !s.ok()) return "play: " + s.message();
  }
  if (!o.materials.empty() && lowerExtension(o.output) != ".glb") return "play: --materials needs -o OUT.glb";
  if (o.quantize && lowerExtension(o.output) != ".glb") return "play: --quantize needs -o OUT.glb";
  if (o.output.empty()) return {};
  const std::string ext = lowerExtension(o.output);
  if (ext == ".gltf") return "play: " + o.output + ": write .glb (one self-contained binary file), .obj, .pc2 or .mdd";
  if (ext != ".obj" && ext != ".glb" && ext != ".pc2" && ext != ".mdd") {
    return "play: " + o.output + ": unknown output format '" + ext + "' (expected .obj, .glb, .pc2 or .mdd)";
  }
  if (o.fps && ext == ".obj") {
    Result<FramePattern> pattern = FramePattern::parse(o.output);
    if (!pattern.ok()) return "play: " + pattern.status().message();
  }
  return {};
}

// The first output that would replace the asset or the --materials file (under another name, or
// through a link, as well); "" when none would.
std::string overwrittenInput(const PlayOptions& o, const std::vector<std::filesystem::path>& files, std::size_t frames) {
  const std::filesystem::path inputs[] = {o.asset, o.materials};
  for (std::size_t f = 0; f < files.size(); ++f) {
    // A .glb or point cache names its one file once per frame: it is checked once.
    if (f > 0 && files[f] == files[f - 1]) continue;
    if (overwritesInput(files[f], inputs)) return files[f].string();
  }
  if (o.png_dir.empty()) return {};
  const std::filesystem::path strip = o.png_dir / "strip.png";
  if (overwritesInput(strip, inputs)) return strip.string();
  for (std::size_t f = 0; f < frames; ++f) {
    if (overwritesInput(pngFrameName(o.png_dir, f), inputs)) return pngFrameName(o.png_dir, f).string();
  }
  return {};
}

Status ensureParentDirectory(const std::filesystem::path& file, std::filesystem::path& last_created) {
  const std::filesystem::path parent = file.parent_path();
  if (parent.empty() || parent == last_created) return okStatus();
  ODESKIN_TRY(createParentFolder(file));
  last_created = parent;
  return okStatus();
}

// --png: about this many vertices over all frames decide the pictures' camera, plus each frame's
// extreme vertices along every axis, so long sequences of big meshes stay cheap to frame.
constexpr std::size_t kFramingBudget = 500000;
constexpr std::size_t kStripFrames = 12;
constexpr std::uint32_t kStripColumns = 6;
constexpr std::uint32_t kStripWidth = 1536;

void addFramingPoints(const std::vector<Vec3>& positions, std::size_t frame_count, std::vector<Vec3>& framing) {
  if (positions.empty()) return;
  const std::size_t stride = std::max<std::size_t>(1, positions.size() * frame_count / kFramingBudget);
  for (std::size_t i = 0; i < positions.size(); i += stride) framing.push_back(positions[i]);
  for (int axis = 0; axis < 3; ++axis) {
    const auto [lo, hi] = std::minmax_element(positions.begin(), positions.end(),
                                              [axis](const Vec3& a, const Vec3& b) { return a[axis] < b[axis]; });
    framing.push_back(*lo);
    framing.push_back(*hi);
  }
}

// Draws every frame again (the playback is deterministic) with one camera that frames them all.
Status playPictures(const PlayOptions& o, const DeformAsset& asset, AssetPlayback& playback, RenderSession& session,
                    const std::vector<double>& times, const std::vector<Vec3>& framing, Console& console,
                    std::vector<std::filesystem::path>& pictures) {
  const auto [width, height] = *parseImageSize(o.png_size);
  visual::PictureSpec spec;
  spec.width = width;
  spec.height = height;
  ODESKIN_ASSIGN_OR_RETURN(const visual::PictureLayout layout, visual::layoutPicture(spec));
  visual::ViewSpec view;
  view.azimuth_deg = o.png_azimuth_deg;
  view.elevation_deg = o.png_elevation_deg;
  ODESKIN_ASSIGN_OR_RETURN(const visual::Camera camera,
                           visual::framePoints(framing, double(layout.panel_width) / layout.panel_height, view));
  const double scene_size = visual::boundsOf(framing).diagonal();
  std::vector<std::size_t> strip_frames;
  for (std::size_t k = 0; k < std::min(kStripFrames, times.size()); ++k) {
    strip_frames.push_back(times.size() <= kStripFrames ? k : k * (times.size() - 1) / (kStripFrames - 1));
  }
  std::vector<visual::Image> strip;
  std::vector<std::string> captions;
  ProgressBar bar(console.err, "pictures", times.size(), !console.quiet && console.interactive && times.size() > 1);
  std::vector<Vec3> positions;
  for (std::size_t f = 0; f < times.size(); ++f) {
    ODESKIN_TRY(playback.positionsAt(times[f], positions));
    ODESKIN_ASSIGN_OR_RETURN(PanelGeometry panel, preparePanel(o.asset.string(), positions, asset.faces,
                                                               o.png_curves ? &asset.curves : nullptr));
    const vk::PanelContent content = panel.content();
    ODESKIN_ASSIGN_OR_RETURN(visual::Image picture, session.draw(layout, camera, scene_size, {&content, 1}));
    pictures.push_back(pngFrameName(o.png_dir, f));
    ODESKIN_TRY(visual::writePng(pictures.back(), picture));
    if (std::find(strip_frames.begin(), strip_frames.end(), f) != strip_frames.end()) {
      strip.push_back(std::move(picture));
      captions.push_back("t = " + numberText(times[f]));
    }
    bar.step(f + 1);
  }
  bar.finish();
  const std::uint32_t columns = visual::balancedColumns(strip.size(), kStripColumns);
  const visual::Image sheet = visual::contactSheet(strip, columns, std::min(width, kStripWidth / columns), 4,
                                                   vk::PictureStyle{}.background, captions);
  pictures.push_back(o.png_dir / "strip.png");
  ODESKIN_TRY(visual::writePng(pictures.back(), sheet));
  return session.checkValidation();
}

// One frame as OBJ. An OBJ input's layout keeps its `v` lines in the input's order, each corner
// naming its `vt`; a glTF input's is written in render vertices, as its point caches are.
Status writeFrameObj(const std::filesystem::path& path, const DeformAsset& asset, std::span<const Vec3> positions,
                     const std::string& comment) {
  if (asset.render.obj_order) {
    return writeObj(path, positions, asset.render.faces, comment, asset.render.uvs, asset.render.topology_of_render);
  }
  return writeObj(path, outputPositions(asset, positions), outputFaces(asset), comment, asset.render.uvs);
}

}  // namespace

Result<FramePattern> FramePattern::parse(std::string_view pattern) {
  // Built with append: GCC 12's -Wrestrict misfires on "'" + std::string(...) here.
  std::string quoted(1, '\'');
  quoted.append(pattern).push_back('\'');
  FramePattern out;
  bool found = false;
  std::string* text = &out.prefix_;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') {
      *text += pattern[i];
      continue;
    }
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      *text += '%';
      ++i;
      continue;
    }
    if (found) return invalidArgument(quoted + " has more than one % conversion; use %% for a literal %");
    std::size_t j = i + 1;
    if (j < pattern.size() && pattern[j] == '0') {
      out.zero_pad_ = true;
      ++j;
    }
    std::size_t width = 0;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9') {
      width = width * 10 + static_cast<std::size_t>(pattern[j] - '0');
      if (width > kMaxPatternWidth) return invalidArgument(quoted + ": frame number width above 32");
      ++j;
    }
    if (j >= pattern.size() || (pattern[j] != 'd' && pattern[j] != 'i' && pattern[j] != 'u')) {
      return invalidArgument(quoted + ": the frame number must be an integer conversion such as %04d");
    }
    out.width_ = width;
    found = true;
    text = &out.suffix_;
    i = j;
  }
  if (!found) return invalidArgument(quoted + " needs a frame number such as %04d (e.g. out_%04d.obj)");
  return out;
}

std::string FramePattern::format(std::size_t frame) const {
  std::string number = std::to_string(frame);
  if (number.size() < width_) number.insert(0, width_ - number.size(), zero_pad_ ? '0' : ' ');
  return prefix_ + number + suffix_;
}

std::vector<double> sequenceSeconds(double fps, double seconds) {
  const double last = std::floor(seconds * fps + 1e-9);
  std::vector<double> times;
  if (!(last >= 0.0) || last >= static_cast<double>(kMaxFrames)) return times;
  const std::size_t count = static_cast<std::size_t>(last) + 1;
  times.reserve(count);
  for (std::size_t f = 0; f < count; ++f) times.push_back(static_cast<double>(f) / fps);
  return times;
}

int runPlayCommand(const PlayOptions& o, Console& console, PlayReport* report) {
  if (const std::string problem = usageProblem(o); !problem.empty()) return reportUsage(console, problem);
  if (o.playback.validation && o.playback.backend == Backend::kCpu && o.png_dir.empty() && !console.quiet) {
    console.err << "note: --validation checks Vulkan calls, and --backend cpu without --png makes none\n";
  }

  Result<DeformAsset> loaded = loadAsset(o.asset);
  if (!loaded.ok()) return reportFailure(console, loaded.status());
  const DeformAsset& asset = *loaded;
  const double t_end = static_cast<double>(asset.key_poses.size() - 1);

  // Frame names and global times.
  const bool write_meshes = !o.output.empty();
  std::vector<std::filesystem::path> files;
  std::vector<double> times;
  std::optional<double> held_after;  // --seconds past the asset's end
  if (o.t) {
    if (*o.t < 0.0 || *o.t > t_end) {
      return reportUsage(console, "play: --t " + messageNumber(*o.t) + " is outside [0, " + numberText(t_end) +
                                      "]: " + o.asset.string() + " has " + std::to_string(asset.key_poses.size()) +
                                      " key poses");
    }
    if (write_meshes) files.push_back(o.output);
    times.push_back(*o.t);
  } else {
    const double length = t_end * asset.segment_seconds;
    const double seconds = o.seconds.value_or(length);
    const std::vector<double> clock = sequenceSeconds(*o.fps, seconds);
    if (clock.empty()) {
      return reportUsage(console, "play: --fps " + numberText(*o.fps) + " for " + numberText(seconds) +
                                      " s is more than " + std::to_string(kMaxFrames) + " frames");
    }
    held_after = seconds > length ? std::optional<double>(seconds) : std::nullopt;
    const bool one_file = lowerExtension(o.output) != ".obj";
    const FramePattern pattern = one_file || !write_meshes ? FramePattern{} : *FramePattern::parse(o.output);
    for (std::size_t f = 0; f < clock.size(); ++f) {
      if (write_meshes) {
        files.emplace_back(one_file ? std::filesystem::path(o.output) : std::filesystem::path(pattern.format(f)));
      }
      times.push_back(std::clamp(clock[f] / asset.segment_seconds, 0.0, t_end));
    }
  }
  if (const std::string clash = overwrittenInput(o, files, times.size()); !clash.empty()) {
    return reportUsage(console, "play: " + clash + " is an input; it would be overwritten");
  }
  // Before the first frame is written: a folder in frame 3's place left frames 0-2 behind.
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (f > 0 && files[f] == files[f - 1]) continue;
    if (const std::string why = folderNotFile(files[f]); !why.empty()) {
      return reportUsage(console, "play: " + files[f].string() + " " + why);
    }
  }
  // .glb: every frame goes into one file (morph target per frame, STEP weights animation).
  const bool glb = lowerExtension(o.output) == ".glb";
  // .pc2, .mdd: every frame's positions in one point cache (point_cache.hpp), for the mesh --t 0 writes.
  const bool mdd = lowerExtension(o.output) == ".mdd";
  const bool point_cache = lowerExtension(o.output) == ".pc2" || mdd;
  if (glb && write_meshes) {
    if (Status s = checkBakedSize(times.size(), outputVertexCount(asset)); !s.ok()) {
      return reportUsage(console, "play: " + o.output + ": " + s.message() +
                                      "; lower --fps or --seconds, or write .obj frames");
    }
  }
  if (point_cache) {
    if (const std::string problem = pointCacheSizeProblem(times.size(), objVertexCount(asset)); !problem.empty()) {
      return reportUsage(console, "play: " + o.output + ": " + problem + "; lower --fps or --seconds");
    }
  }
  if (held_after && !console.quiet) {
    console.err << "note: --seconds " << numberText(*held_after) << " runs past " << o.asset.string() << "'s "
                << numberText(t_end * asset.segment_seconds) << " s; the frames after it hold the last key pose\n";
  }
  std::optional<PointCacheBuilder> cache;
  if (point_cache) cache.emplace(mdd ? PointCacheFormat::kMdd : PointCacheFormat::kPc2, objVertexCount(asset), times.size());
  std::optional<gltf::MaterialLibrary> materials;
  if (!o.materials.empty()) {
    Result<gltf::MaterialLibrary> library = gltf::readMaterialLibrary(o.materials);
    if (!library.ok()) return reportFailure(console, library.status());
    if (Status s = gltf::primitiveMaterials(*library, asset.render.primitives, 1).status(); !s.ok()) {
      return reportFailure(console, s);
    }
    materials = std::move(library).value();
    if (asset.render.uvs.empty()) {
      const std::size_t untextured = gltf::dropTextures(*materials);
      if (!console.quiet) warnOfDroppedTextures(console.err, o.asset, o.materials, untextured);
    }
  }
  std::vector<std::vector<Vec3>> baked, baked_normals;

  // --png: its folder is made and the device opened before anything is written, so a file in the
  // folder's way or a missing device fails early (and before the playback, which would otherwise
  // note a CPU fallback just before this error).
  std::optional<RenderSession> session;
  if (!o.png_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.png_dir, ec);
    if (ec) return reportFailure(console, ioError("play: --png " + o.png_dir.string() + ": cannot create directory: " + ec.message()));
    Result<RenderSession> opened = RenderSession::open(o.playback.device, o.playback.validation, vk::PictureStyle{});
    if (!opened.ok()) return reportFailure(console, Status(opened.status().code(), "play: " + opened.status().message()));
    session.emplace(std::move(opened).value());
  }

  Result<AssetPlayback> playback = AssetPlayback::create(asset, o.playback, console.quiet ? nullptr : &console.err);
  if (!playback.ok()) {
    // A Vulkan failure speaks for itself; anything else is about the asset's content.
    const StatusCode code = playback.status().code();
    const bool device = code == StatusCode::kUnavailable || code == StatusCode::kDeviceError;
    return reportError(console, "play: " + (device ? std::string() : o.asset.string() + ": ") + playback.status().message(),
                       kExitFailure);
  }
  ProgressBar bar(console.err, "play", times.size(), !console.quiet && console.interactive && times.size() > 1);
  std::vector<Vec3> positions;
  std::vector<Vec3> framing;  // --png: vertices the pictures' camera must see (playPictures)
  std::filesystem::path last_directory;
  WrittenOutputs written;  // a failure part way removes the frames and files already written
  double deform_seconds = 0.0;
  for (std::size_t f = 0; f < times.size(); ++f) {
    const Clock::time_point start = Clock::now();
    if (Status s = playback->positionsAt(times[f], positions); !s.ok()) {
      written.removeAll();
      return reportError(console, "play: " + s.message(), kExitFailure);
    }
    deform_seconds += std::chrono::duration<double>(Clock::now() - start).count();
    if (!o.png_dir.empty()) addFramingPoints(positions, times.size(), framing);
    if (!write_meshes) {
      bar.step(f + 1);
      continue;
    }
    if (Status s = ensureParentDirectory(files[f], last_directory); !s.ok()) return reportFailure(console, written.undo(s));
    if (point_cache) {
      if (Status s = cache->add(objPositions(asset, positions)); !s.ok()) {
        return reportError(console, "play: " + o.output + ": " + s.message(), kExitFailure);
      }
      bar.step(f + 1);
      continue;
    }
    if (glb) {
      baked.push_back(outputPositions(asset, positions));
      baked_normals.push_back(outputNormals(asset, positions));
      bar.step(f + 1);
      continue;
    }
    const std::string comment = "odeskin play " + o.asset.filename().string() + " t = " + numberText(times[f]);
    if (Status s = writeFrameObj(files[f], asset, positions, comment); !s.ok()) {
      return reportFailure(console, written.undo(s));
    }
    written.add(files[f]);
    bar.step(f + 1);
  }
  bar.finish();
  if (Status s = playback->checkValidation(); !s.ok()) return reportFailure(console, written.undo(s));
  QuantizationCost quantization;
  double quantization_box = 0.0;
  if (glb && write_meshes) {
    std::vector<double> seconds;
    seconds.reserve(times.size());
    for (double t : times) seconds.push_back(t * asset.segment_seconds);
    // --t, or clamped times at the end of a sequence, may repeat a time: keep strictly increasing keys.
    std::vector<std::vector<Vec3>> kept, kept_normals;
    std::vector<double> kept_seconds;
    for (std::size_t f = 0; f < baked.size(); ++f) {
      if (!kept_seconds.empty() && !(seconds[f] > kept_seconds.back())) continue;
      kept.push_back(std::move(baked[f]));
      kept_normals.push_back(std::move(baked_normals[f]));
      kept_seconds.push_back(seconds[f]);
    }
    BakedGlbOptions options;
    options.materials = materials ? &*materials : nullptr;
    options.quantize = o.quantize;
    if (Status s = writeBakedGlb(o.output, outputFaces(asset), kept, kept_seconds, options,
                                 {kept_normals, asset.render.uvs, asset.render.primitives}, &quantization);
        !s.ok()) {
      return reportFailure(console, s);
    }
    written.add(o.output);
    quantization_box = longestBoxSide(kept.front());
  }

  // Sample k is scene frame k (MDD: at k / F seconds): a scene at F frames per second plays it in time.
  if (point_cache) {
    if (Status s = cache->write(o.output, PointCacheTiming{o.fps.value_or(24.0), 0.0}); !s.ok()) {
      return reportFailure(console, s);
    }
    written.add(o.output);
  }

  std::vector<std::filesystem::path> pictures;
  if (!o.png_dir.empty()) {
    if (Status s = playPictures(o, asset, *playback, *session, times, framing, console, pictures); !s.ok()) {
      for (const std::filesystem::path& picture : pictures) written.add(picture);
      written.removeAll();
      return reportError(console, "play: " + s.message(), kExitFailure);
    }
  }

  const double mean = deform_seconds / static_cast<double>(times.size());
  if (!console.quiet) {
    char timing[64];
    std::snprintf(timing, sizeof timing, "%.3f ms", 1e3 * mean);
    const std::string cache_note =
        " (point cache of " + std::to_string(objVertexCount(asset)) + " vertices for the mesh `play --t 0 -o BASE.obj` writes)";
    if (o.t) {
      const auto segment = static_cast<std::size_t>(std::min(std::floor(*o.t), std::max(t_end - 1.0, 0.0)));
      console.out << "t = " << numberText(*o.t) << " (segment " << segment << ", tau " << numberText(*o.t - static_cast<double>(segment))
                  << ") -> " << (write_meshes ? files.front().string() : pictures.front().string())
                  << (point_cache ? cache_note : std::string()) << "\n";
    } else {
      console.out << times.size() << " frame" << (times.size() == 1 ? "" : "s") << " at " << numberText(*o.fps)
                  << " fps (t " << numberText(times.front()) << " to " << numberText(times.back()) << ")";
      if (write_meshes) {
        console.out << " -> ";
        if (glb) {
          console.out << files.front().string() << " (one morph target per frame)";
        } else if (point_cache) {
          console.out << files.front().string() << cache_note;
        } else {
          console.out << files.front().string() << " ... " << files.back().string();
        }
      }
      console.out << "\n";
    }
    if (o.quantize && glb && write_meshes) {
      printQuantization(console.out, quantization, quantization_box > 0.0 ? quantization_box : 1.0, "frames");
    }
    console.out << "device: " << playback->device() << ", " << timing << " per frame (deformation only)\n";
    if (!pictures.empty()) {
      console.out << "pictures: " << pictures.front().string() << " ... " << pictures.back().string() << "\n";
    }
  }
  if (report) {
    if ((glb || point_cache) && write_meshes) files.assign(1, o.output);
    report->files = std::move(files);
    report->pictures = std::move(pictures);
    report->times = std::move(times);
    report->device = playback->device();
    report->mean_frame_seconds = mean;
  }
  return kExitOk;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin render` and `odeskin play --png` called as the program calls them, with the validation
// layer on: pictures have the requested size and content, panels share one camera, heat maps match
// the CPU errors, turntable frames differ, curves show; bad input fails with one line and exit 1,
// bad options with exit 2, and nothing is written then.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <tuple>

#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC  // private to this test: no clash with tinygltf's copy
#include <stb/stb_image.h>

#include "engine/io/asset_file.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/visual/curve_lines.hpp"
#include "engine/visual/vertex_error.hpp"
#include "host/device.hpp"
#include "host/gpu_test_support.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/play_command.hpp"
#include "samples/odeskin/render_command.hpp"
#include "visual/render_colour.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using visual::Image;
using visual::Rgba8;

const fs::path kData = ODESKIN_DATA_DIR;
const fs::path kCylinder = kData / "cylinder";

using testing::Captured;
using testing::CommandCase;

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_render_test_", name); }

Image readPng(const fs::path& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &w, &h, &channels, 4);
  EXPECT_NE(data, nullptr) << path;
  if (data == nullptr) return {};
  Image image(static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
  std::memcpy(image.pixels.data(), data, image.pixels.size() * 4);
  stbi_image_free(data);
  return image;
}

std::size_t countIf(const Image& image, const std::function<bool(Rgba8)>& f) {
  return static_cast<std::size_t>(std::count_if(image.pixels.begin(), image.pixels.end(), f));
}

Image crop(const Image& image, std::uint32_t x0, std::uint32_t width) {
  Image out(width, image.height);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) out.at(x, y) = image.at(x0 + x, y);
  }
  return out;
}

class RenderCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Result<vk::Gpu> gpu = vk::Gpu::open("auto", false);
    has_gpu_ = gpu.ok();
    if (!has_gpu_) return;
    Result<ProceduralArm> arm = makeProceduralArm(ArmOptions{});
    ASSERT_TRUE(arm.ok()) << arm.status().toString();
    FitOptions fit;
    fit.materials = {skinMaterial()};
    Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, fit);
    ASSERT_TRUE(asset.ok()) << asset.status().toString();
    dir_ = new fs::path(scratch("assets"));
    ASSERT_TRUE(saveAsset(armPath(), *asset).ok());
  }
  static void TearDownTestSuite() { delete dir_; }

  void SetUp() override {
    if (has_gpu_) return;
    if (testing::gpuRequired()) {
      FAIL() << "ODESKIN_REQUIRE_GPU=1 but no Vulkan device";
    } else {
      GTEST_SKIP() << "no Vulkan device";
    }
  }

  static fs::path armPath() { return *dir_ / "arm.odsk"; }

  static RenderOptions options(std::vector<fs::path> inputs, const fs::path& output) {
    RenderOptions o;
    o.inputs = std::move(inputs);
    o.output = output.string();
    o.validation = true;
    return o;
  }
  static int render(const RenderOptions& o, Captured& io, RenderReport* report = nullptr) {
    return runRenderCommand(o, io.console, report);
  }

  static bool has_gpu_;
  static fs::path* dir_;
};
bool RenderCommand::has_gpu_ = false;
fs::path* RenderCommand::dir_ = nullptr;

TEST_F(RenderCommand, DrawsAnObjAtTheRequestedSize) {
  const fs::path dir = scratch("obj");
  RenderOptions o = options({kCylinder / "cylinder.obj"}, dir / "c.png");
  o.size = "300x200";
  Captured io;
  RenderReport report;
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  const Image image = readPng(dir / "c.png");
  EXPECT_EQ(image.width, 300u);
  EXPECT_EQ(image.height, 200u);
  const Rgba8 background{247, 247, 249, 255};
  EXPECT_EQ(image.at(0, 0), background);
  EXPECT_GT(countIf(image, [&](Rgba8 p) { return p != background; }), 300u * 200u / 10);
  EXPECT_NE(io.out.str().find("300 x 200, 1 panel"), std::string::npos) << io.out.str();
  EXPECT_GT(report.mean_frame_seconds, 0.0);
  EXPECT_TRUE(io.err.str().empty()) << io.err.str();
  // The summary gives the samples drawn with; more than a device offers are lowered, and said so.
  EXPECT_NE(io.out.str().find(std::to_string(report.samples) + " samples per pixel, "), std::string::npos)
      << io.out.str();
  o.samples = 64;
  Captured many;
  ASSERT_EQ(render(o, many, &report), kExitOk) << many.err.str();
  ASSERT_GE(report.samples, 1u);
  ASSERT_LE(report.samples, 64u);
  EXPECT_EQ(report.samples & (report.samples - 1), 0u);  // a power of two
  if (report.samples < 64) {
    EXPECT_NE(many.out.str().find("per pixel (64 asked; the most the device offers up to that)"), std::string::npos)
        << many.out.str();
  }
  o.samples = 1;
  Captured one;
  ASSERT_EQ(render(o, one, &report), kExitOk) << one.err.str();
  EXPECT_EQ(report.samples, 1u);
  EXPECT_NE(one.out.str().find(", 1 sample per pixel, "), std::string::npos) << one.out.str();
}

TEST_F(RenderCommand, SideBySidePanelsShareOneCameraAndScale) {
  const fs::path dir = scratch("panels");
  RenderOptions o = options({kCylinder / "cylinder.obj", kCylinder / "cylinder.obj"}, dir / "same.png");
  o.size = "400x200";
  o.no_labels = true;
  Captured io;
  RenderReport report;
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  EXPECT_EQ(report.panels, 2u);
  const Image same = readPng(dir / "same.png");
  ASSERT_EQ(same.width, 400u);
  // The same mesh twice: both halves are the same picture, pixel for pixel.
  EXPECT_EQ(crop(same, 0, 200).pixels, crop(same, 200, 200).pixels);
  // A bent pose beside the rest pose: the halves differ, and the rest pose is drawn smaller than
  // alone, because the camera frames both (same scale for every panel).
  o.inputs = {kCylinder / "cylinder.obj", kCylinder / "poses-1" / "cylinder-3.obj"};
  o.output = (dir / "pair.png").string();
  ASSERT_EQ(render(o, io), kExitOk) << io.err.str();
  const Image pair = readPng(dir / "pair.png");
  EXPECT_NE(crop(pair, 0, 200).pixels, crop(pair, 200, 200).pixels);
  const Rgba8 background{247, 247, 249, 255};
  auto drawn = [&](const Image& image) { return countIf(image, [&](Rgba8 p) { return p != background; }); };
  EXPECT_NE(drawn(crop(pair, 0, 200)), drawn(crop(same, 0, 200)));
}

TEST_F(RenderCommand, HeatMapMatchesTheCpuErrorsAndDrawsAColourBar) {
  const fs::path dir = scratch("heat");
  const fs::path reference = kCylinder / "poses-1" / "cylinder-1.obj";
  const fs::path pose = kCylinder / "poses-1" / "cylinder-2.obj";
  RenderOptions o = options({pose, reference}, dir / "heat.png");
  o.heat = reference;
  o.size = "600x300";
  Captured io;
  RenderReport report;
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  // The reference panel has no heat; the other's largest error is the bar's top by default.
  Result<std::vector<double>> errors = visual::relativeVertexErrors(readObj(pose)->positions, readObj(reference)->positions);
  ASSERT_TRUE(errors.ok());
  const double worst = *std::max_element(errors->begin(), errors->end());
  ASSERT_EQ(report.max_errors.size(), 1u);
  EXPECT_DOUBLE_EQ(report.max_errors[0], worst);
  ASSERT_TRUE(report.heat_max.has_value());
  EXPECT_DOUBLE_EQ(*report.heat_max, worst);
  const Image image = readPng(dir / "heat.png");
  ASSERT_EQ(image.width, 600u);
  auto saturated = [](Rgba8 p) {
    const int hi = std::max({p.r, p.g, p.b}), lo = std::min({p.r, p.g, p.b});
    return hi - lo > 60;
  };
  auto red = [&](Rgba8 p) { return saturated(p) && visual::hueDegrees(p) < 20.0; };
  auto blue = [&](Rgba8 p) { return saturated(p) && visual::hueDegrees(p) > 200.0; };
  // The left panel's colours span the map, from blue (no error) to red (the largest).
  const Image left = crop(image, 0, 250);
  EXPECT_GT(countIf(left, red), 0u);
  EXPECT_GT(countIf(left, blue), 50u);
  EXPECT_NE(io.out.str().find("heat: error / longest box side of cylinder-1.obj"), std::string::npos) << io.out.str();

  // A fixed scale far above every error: no red anywhere in the panels.
  o.heat_max = 1.0;
  o.output = (dir / "fixed.png").string();
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  EXPECT_DOUBLE_EQ(*report.heat_max, 1.0);
  EXPECT_EQ(countIf(crop(readPng(dir / "fixed.png"), 0, 250), red), 0u);
}

// The GPU draws in float, which holds neither 1e150 nor 1e-90: the picture of a mesh must not
// depend on its size (these drew nothing before).
TEST_F(RenderCommand, SizeAndPlaceDoNotChangeThePicture) {
  const fs::path dir = scratch("scale");
  Result<ObjMesh> mesh = readObj(kCylinder / "cylinder.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  auto draw = [&](const std::string& name, double scale, const Vec3& offset) {
    ObjMesh moved = *mesh;
    for (Vec3& p : moved.positions) p = scale * p + offset;
    EXPECT_TRUE(writeObj(dir / (name + ".obj"), moved.positions, moved.faces).ok());
    RenderOptions o = options({dir / (name + ".obj")}, dir / (name + ".png"));
    o.size = "240x160";
    o.no_labels = true;
    Captured io;
    EXPECT_EQ(render(o, io), kExitOk) << name << ": " << io.err.str();
    return readPng(dir / (name + ".png"));
  };
  const Image reference = draw("unit", 1.0, Vec3(0.0));
  const Rgba8 background{247, 247, 249, 255};
  const std::size_t covered = countIf(reference, [&](Rgba8 p) { return p != background; });
  ASSERT_GT(covered, 240u * 160u / 10);
  for (const auto& [name, scale, offset] : {std::tuple{"huge", 1e150, Vec3(-3e150, 0.0, 1e150)},
                                            std::tuple{"tiny", 1e-90, Vec3(0.0, 2e-90, 0.0)}}) {
    const Image image = draw(name, scale, offset);
    ASSERT_EQ(image.pixels.size(), reference.pixels.size()) << name;
    // Rounding may move an edge pixel's coverage; no more than 1% of the mesh's pixels differ.
    std::size_t differ = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      const Rgba8 a = image.pixels[i], b = reference.pixels[i];
      differ += std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)}) > 8 ? 1 : 0;
    }
    EXPECT_LT(differ, covered / 100) << name << ": " << differ << " of " << covered << " pixels differ";
  }
}

TEST_F(RenderCommand, BadInputFailsWithOneLineAndExitCode1) {
  const fs::path dir = scratch("bad_input");
  std::vector<CommandCase<RenderOptions>> cases;
  RenderOptions mismatch = options({kCylinder / "cylinder.obj"}, dir / "x.png");
  mismatch.heat = kData / "horse-gallop" / "horse-01.obj";
  cases.push_back({mismatch, "--heat: " + (kCylinder / "cylinder.obj").string() + ": 420 vertices but the reference has 8431"});
  cases.push_back({options({dir / "absent.obj"}, dir / "x.png"), "absent.obj"});
  const fs::path corrupt = dir / "corrupt.odsk";
  std::ofstream(corrupt) << "not an asset";
  cases.push_back({options({corrupt}, dir / "x.png"), "corrupt.odsk: not an odeskin asset"});
  Result<ObjMesh> cylinder = readObj(kCylinder / "cylinder.obj");
  ASSERT_TRUE(cylinder.ok());
  for (Vec3& p : cylinder->positions) p *= 1e200;
  const fs::path huge = dir / "huge.obj";
  ASSERT_TRUE(writeObj(huge, cylinder->positions, cylinder->faces).ok());
  cases.push_back({options({huge}, dir / "x.png"), huge.string() + ": the mesh is too large for double-precision distances"});
  testing::expectRejected(cases, [](const RenderOptions& o, Captured& io) { return render(o, io); }, kExitFailure,
                          "render");
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST_F(RenderCommand, BadOptionsAreUsageErrors) {
  const fs::path dir = scratch("usage");
  const fs::path obj = kCylinder / "cylinder.obj";
  std::vector<CommandCase<RenderOptions>> cases;
  for (const std::string size : {"12x", "0x0", "abc", "800x10", "99999x100"}) {
    RenderOptions o = options({obj}, dir / "x.png");
    o.size = size;
    cases.push_back({o, "--size '" + size + "'"});
  }
  cases.push_back({options({dir / "mesh.ply"}, dir / "x.png"), "unknown input format '.ply'"});
  cases.push_back({options({obj}, dir / "x.jpg"), "must be a .png file"});
  cases.push_back({options({}, dir / "x.png"), "at least one INPUT"});
  RenderOptions strip = options({obj}, dir / "x.png");
  strip.strip = (dir / "s.png").string();
  cases.push_back({strip, "--strip needs --turntable"});
  RenderOptions strip_frame = options({obj}, dir / "turn.png");
  strip_frame.turntable = 4;
  strip_frame.strip = (dir / "turn_001.png").string();
  cases.push_back({strip_frame, "turn_001.png is also the name of a turntable frame"});
  RenderOptions strip_pattern = options({obj}, dir / "turn_%02d.png");
  strip_pattern.turntable = 4;
  strip_pattern.strip = (dir / "turn_03.png").string();
  cases.push_back({strip_pattern, "turn_03.png is also the name of a turntable frame"});
  RenderOptions curves = options({obj}, dir / "x.png");
  curves.curves = true;
  cases.push_back({curves, "--curves needs a .odsk input"});
  RenderOptions labels = options({obj, obj}, dir / "x.png");
  labels.labels = {"one"};
  cases.push_back({labels, "--labels gives 1 names for 2 panels"});
  RenderOptions elevation = options({obj}, dir / "x.png");
  elevation.elevation_deg = 95.0;
  cases.push_back({elevation, "elevation"});
  RenderOptions time = options({armPath()}, dir / "x.png");
  time.t = 5.0;
  cases.push_back({time, "--t 5 is outside [0, 1]"});
  RenderOptions heat_max = options({obj}, dir / "x.png");
  heat_max.heat = obj;
  heat_max.heat_max = -1.0;
  cases.push_back({heat_max, "--heat-max must be positive"});
  RenderOptions heat_tiny = heat_max;
  heat_tiny.heat_max = 1e-320;
  cases.push_back({heat_tiny, "--heat-max 9.99989e-321 is below 1e-30"});
  RenderOptions untimed = options({obj}, dir / "x.png");
  untimed.t = 0.5;
  cases.push_back({untimed, "--t applies to a .odsk or .glb/.gltf input"});
  cases.push_back({options({obj}, dir / "t_%03d.png"), "t_%03d.png is a frame pattern: add --turntable N"});
  RenderOptions azimuth = options({obj}, dir / "x.png");
  azimuth.azimuth_deg = std::numeric_limits<double>::quiet_NaN();
  cases.push_back({azimuth, "view: azimuth nan is not a finite number"});
  testing::expectRejected(cases, [](const RenderOptions& o, Captured& io) { return render(o, io); }, kExitUsage,
                          "render");
  EXPECT_TRUE(fs::is_empty(dir)) << "a rejected command wrote something";
}

TEST_F(RenderCommand, TurntableFramesTurnAndMakeAStrip) {
  const fs::path dir = scratch("turntable");
  RenderOptions o = options({armPath()}, dir / "turn" / "arm.png");
  o.turntable = 4;
  o.size = "160x120";
  o.strip = (dir / "strip.png").string();
  Captured io;
  RenderReport report;
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  ASSERT_EQ(report.files.size(), 5u);
  EXPECT_EQ(report.files[0], dir / "turn" / "arm_000.png");
  EXPECT_EQ(report.files[3], dir / "turn" / "arm_003.png");
  std::vector<Image> frames;
  for (std::size_t f = 0; f < 4; ++f) frames.push_back(readPng(report.files[f]));
  for (std::size_t a = 0; a < 4; ++a) {
    EXPECT_EQ(frames[a].width, 160u);
    for (std::size_t b = a + 1; b < 4; ++b) EXPECT_NE(frames[a].pixels, frames[b].pixels) << a << " vs " << b;
  }
  const Image strip = readPng(dir / "strip.png");
  EXPECT_EQ(strip.width, 4u + 4u * (160u + 4u));  // one row of four
  // A printf pattern names the frames instead.
  o.output = (dir / "f_%02d.png").string();
  o.strip.clear();
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  EXPECT_TRUE(fs::exists(dir / "f_03.png"));
  // A frame that cannot be written (a link to /dev/full, as a full disk) takes the frames before it along.
  const fs::path full = dir / "full";
  fs::create_directories(full);
  fs::create_symlink("/dev/full", full / "g_02.png");
  o.output = (full / "g_%02d.png").string();
  Captured failed;
  EXPECT_EQ(render(o, failed), kExitFailure);
  EXPECT_NE(failed.err.str().find("g_02.png: write failed"), std::string::npos) << failed.err.str();
  EXPECT_FALSE(fs::exists(full / "g_00.png"));
  EXPECT_FALSE(fs::exists(full / "g_01.png"));
}

TEST_F(RenderCommand, AssetsDrawCurvesAndTheirLbsTwin) {
  const fs::path dir = scratch("asset");
  RenderOptions o = options({armPath()}, dir / "plain.png");
  o.t = 0.5;
  o.size = "240x180";
  Captured io;
  ASSERT_EQ(render(o, io), kExitOk) << io.err.str();
  o.curves = true;
  o.output = (dir / "curves.png").string();
  ASSERT_EQ(render(o, io), kExitOk) << io.err.str();
  auto curvePixels = [](const Image& image) {
    return countIf(image, [](Rgba8 p) {
      for (std::uint32_t k = 0; k < visual::curvePaletteSize(); ++k) {
        if (visual::channelDistance(p, visual::toRgba8(visual::curveColour(k))) <= 1) return true;
      }
      return false;
    });
  };
  EXPECT_EQ(curvePixels(readPng(dir / "plain.png")), 0u);
  EXPECT_GT(curvePixels(readPng(dir / "curves.png")), 200u);

  // --lbs: the skin-only pose in a panel before the asset's own; mid-way they differ.
  o.curves = false;
  o.lbs = true;
  o.size = "480x180";
  o.no_labels = true;
  o.output = (dir / "lbs.png").string();
  RenderReport report;
  ASSERT_EQ(render(o, io, &report), kExitOk) << io.err.str();
  EXPECT_EQ(report.panels, 2u);
  const Image both = readPng(dir / "lbs.png");
  EXPECT_NE(crop(both, 0, 240).pixels, crop(both, 240, 240).pixels);
}

TEST_F(RenderCommand, GlbInputIsDrawnAtItsBindPose) {
  const fs::path dir = scratch("glb");
  PlayOptions play;
  play.asset = armPath();
  play.fps = 2.0;
  play.output = (dir / "arm.glb").string();
  Captured io;
  ASSERT_EQ(runPlayCommand(play, io.console), kExitOk) << io.err.str();
  RenderOptions o = options({dir / "arm.glb"}, dir / "glb.png");
  o.size = "200x150";
  ASSERT_EQ(render(o, io), kExitOk) << io.err.str();
  const Image image = readPng(dir / "glb.png");
  EXPECT_GT(countIf(image, [](Rgba8 p) { return p != Rgba8{247, 247, 249, 255}; }), 1000u);
  // The baked file has no skin: its frames are a weights animation, drawn at an animation time too.
  o.output = (dir / "glb-late.png").string();
  o.t = 1.0;
  ASSERT_EQ(render(o, io), kExitOk) << io.err.str();
  EXPECT_NE(readPng(dir / "glb-late.png").pixels, image.pixels);
}

TEST_F(RenderCommand, PlayPngWritesEveryFrameAndAStrip) {
  const fs::path dir = scratch("play");
  PlayOptions play;
  play.asset = armPath();
  play.fps = 4.0;
  play.png_dir = dir / "pictures";
  play.png_size = "200x150";
  play.playback.validation = true;
  Captured io;
  PlayReport report;
  ASSERT_EQ(runPlayCommand(play, io.console, &report), kExitOk) << io.err.str();
  EXPECT_TRUE(report.files.empty());  // no -o: pictures only
  ASSERT_EQ(report.pictures.size(), 6u);  // t = 0, 0.25, ..., 1 and the strip
  EXPECT_EQ(report.pictures[0], dir / "pictures" / "frame_0000.png");
  EXPECT_EQ(report.pictures[5], dir / "pictures" / "strip.png");
  const Image first = readPng(report.pictures[0]);
  const Image last = readPng(report.pictures[4]);
  EXPECT_EQ(first.width, 200u);
  EXPECT_EQ(first.height, 150u);
  EXPECT_NE(first.pixels, last.pixels);
  EXPECT_GT(readPng(report.pictures[5]).width, 200u);
  // Bad picture options are usage errors, before anything is played.
  play.png_size = "wide";
  Captured bad;
  EXPECT_EQ(runPlayCommand(play, bad.console), kExitUsage);
  EXPECT_NE(bad.err.str().find("--size 'wide'"), std::string::npos) << bad.err.str();
}

TEST_F(RenderCommand, PlayPngFolderIsANameNotAPatternAndIsMadeFirst) {
  const fs::path dir = scratch("play_folder");
  PlayOptions play;
  play.asset = armPath();
  play.t = 1.0;
  play.png_dir = dir / "100%d";  // a % in the folder was read as a frame number: a crash
  play.png_size = "64x48";
  Captured io;
  PlayReport report;
  ASSERT_EQ(runPlayCommand(play, io.console, &report), kExitOk) << io.err.str();
  ASSERT_EQ(report.pictures.size(), 2u);
  EXPECT_EQ(report.pictures[0], dir / "100%d" / "frame_0000.png");
  EXPECT_TRUE(fs::exists(report.pictures[0]));
  // A file where the folder goes fails before the mesh is written, not after.
  std::ofstream(dir / "taken") << "a file\n";
  play.png_dir = dir / "taken";
  play.output = (dir / "arm.obj").string();
  Captured bad;
  EXPECT_EQ(runPlayCommand(play, bad.console), kExitFailure);
  EXPECT_NE(bad.err.str().find("--png " + (dir / "taken").string() + ": cannot create directory"), std::string::npos)
      << bad.err.str();
  EXPECT_FALSE(fs::exists(dir / "arm.obj"));
}

}  // namespace
}  // namespace odeskin

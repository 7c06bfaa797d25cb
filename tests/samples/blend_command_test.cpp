// SPDX-License-Identifier: MIT
// `odeskin blend` called as the program calls it: the OBJ is the documented grid (vertex i*V + j is
// S(i/(U-1), 2 pi j/V), quads wrapping in v) of the engine's surface; the defaults are the thesis's
// parameters; --hermite and --spline change the profile; bad options (unknown or garbled example,
// NaN, res < 2) are usage errors and ill-posed parameters failures, each with one error line and no
// file left behind.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/surfaces/blend_examples.hpp"
#include "engine/surfaces/blending_surface.hpp"
#include "engine/surfaces/hermite_blend.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/blend_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Captured;
using testing::CommandCase;

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_blend_test_", name); }

int blend(const BlendCommandOptions& o, Captured& io, BlendReport* report = nullptr) {
  return runBlendCommand(o, io.console, report);
}

BlendCommandOptions options(const std::string& example, const fs::path& output) {
  BlendCommandOptions o;
  o.example = example;
  o.output = output;
  return o;
}

TEST(BlendCommand, WritesTheDocumentedGrid) {
  const fs::path dir = scratch("grid");
  BlendCommandOptions o = options("3.18", dir / "sub" / "fig35c.obj");
  o.alpha = 3.7;
  o.beta = 2.0;
  o.gamma = 18.0;
  o.res = "9,24";
  Captured io;
  BlendReport report;
  ASSERT_EQ(blend(o, io, &report), kExitOk) << io.err.str();
  EXPECT_TRUE(io.err.str().empty()) << io.err.str();
  EXPECT_NE(io.out.str().find("9 x 24 grid, 216 vertices, 192 quads"), std::string::npos) << io.out.str();
  EXPECT_NE(report.regime.find("I: complex quadruple"), std::string::npos) << report.regime;
  EXPECT_LT(report.position_error, 1e-14);
  EXPECT_LT(report.tangent_error, 1e-13);

  Result<ObjMesh> mesh = readObj(o.output);
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  ASSERT_EQ(mesh->positions.size(), 216u);
  Result<BlendExample> e = blendExample("3.18");
  Result<BlendingSurface> s = BlendingSurface::create(e->boundary, 3.7, 2.0, 18.0);
  ASSERT_TRUE(s.ok());
  for (std::uint32_t i = 0; i < 9; ++i) {
    for (std::uint32_t j = 0; j < 24; ++j) {
      const Vec3 expected = s->at(i / 8.0, 2.0 * std::numbers::pi * j / 24.0);
      // The OBJ stores 9 significant digits or more; the blend spans ~2 units.
      EXPECT_LT(glm::length(mesh->positions[i * 24 + j] - expected), 1e-6) << i << " " << j;
    }
  }
  ASSERT_EQ(mesh->faces.faceCount(), 8u * 24u);
  const std::uint32_t* last = &mesh->faces.indices[mesh->faces.face_offsets[23]];  // row 0, j = 23: the seam
  EXPECT_EQ(last[0], 23u);
  EXPECT_EQ(last[1], 24u + 23u);
  EXPECT_EQ(last[2], 24u);
  EXPECT_EQ(last[3], 0u);
}

TEST(BlendCommand, DefaultsAreTheThesisParametersAndProfilesCanChange) {
  const fs::path dir = scratch("defaults");
  for (const auto& [id, alpha, beta, gamma] : {std::tuple{"3.15", 1.0, 2.0, 1.0}, std::tuple{"3.16", 1.0, 3.0, 1.0},
                                              std::tuple{"3.17", 1.0, 1.0, 1.0}, std::tuple{"3.18", 1.0, 0.5, 1.0}}) {
    Captured io;
    BlendReport report;
    ASSERT_EQ(blend(options(id, dir / (std::string(id) + ".obj")), io, &report), kExitOk) << io.err.str();
    EXPECT_EQ(report.alpha, alpha);
    EXPECT_EQ(report.beta, beta);
    EXPECT_EQ(report.gamma, gamma);
    EXPECT_EQ(report.u_count, 64u);
    EXPECT_EQ(report.v_count, 128u);
    EXPECT_EQ(readObj(dir / (std::string(id) + ".obj"))->positions.size(), 64u * 128u);
    EXPECT_LT(report.reach, 10.0) << id;
    EXPECT_TRUE(io.err.str().empty()) << io.err.str();
  }
  BlendCommandOptions hermite = options("3.18", dir / "hermite.obj");
  hermite.hermite = true;
  hermite.res = "5,8";
  Captured io;
  ASSERT_EQ(blend(hermite, io), kExitOk) << io.err.str();
  Result<ObjMesh> mesh = readObj(hermite.output);
  ASSERT_TRUE(mesh.ok());
  Result<BlendingSurface> h = BlendingSurface::create(blendExample("3.18")->boundary, hermiteCardinals);
  EXPECT_LT(glm::length(mesh->positions[2 * 8 + 3] - h->at(0.5, 2.0 * std::numbers::pi * 3 / 8)), 1e-6);
  BlendCommandOptions spline = options("3.18", dir / "spline.obj");
  spline.spline_pieces = 4;
  Captured io2;
  ASSERT_EQ(blend(spline, io2), kExitOk) << io2.err.str();
  EXPECT_NE(io2.out.str().find("clamped cubic spline with 4 pieces"), std::string::npos) << io2.out.str();
}

TEST(BlendCommand, BadOptionsAreUsageErrors) {
  const fs::path dir = scratch("usage");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<CommandCase<BlendCommandOptions>> cases;
  cases.push_back({options("3.99", dir / "x.obj"), "unknown example '3.99'"});
  cases.push_back({options("3.14", dir / "x.obj"), "3.14 is garbled"});
  cases.push_back({options("", dir / "x.obj"), "--example is required"});
  BlendCommandOptions o = options("3.18", dir / "x.obj");
  o.alpha = nan;
  cases.push_back({o, "--alpha must be a finite number"});
  o = options("3.18", dir / "x.obj");
  o.gamma = std::numeric_limits<double>::infinity();
  cases.push_back({o, "--gamma must be a finite number"});
  for (const auto& [res, message] : {std::pair{"1,64", "U = 1 must be in [2, 100000]"}, std::pair{"64,2", "V = 2 must be in [3"},
                                     std::pair{"0,0", "U = 0"}, std::pair{"64", "--res must be two positive integers"},
                                     std::pair{"a,b", "got 'a,b'"}, std::pair{"-3,8", "got '-3,8'"},
                                     std::pair{"100000,100000", "more than 50000000 vertices"}}) {
    o = options("3.18", dir / "x.obj");
    o.res = res;
    cases.push_back({o, message});
  }
  o = options("3.18", dir / "x.obj");
  o.hermite = true;
  o.beta = 1.0;
  cases.push_back({o, "--hermite is the cubic Hermite blend and takes no"});
  o = options("3.18", dir / "x.obj");
  o.spline_pieces = 0;
  cases.push_back({o, "--spline must be in [1, 1000]"});
  cases.push_back({options("3.18", dir / "x.ply"), "unknown output format '.ply'"});
  testing::expectRejected(cases, [](const BlendCommandOptions& opt, Captured& io) { return blend(opt, io); }, kExitUsage,
                          "blend");
  EXPECT_TRUE(fs::is_empty(dir)) << "a rejected command wrote something";
}

// A grid the machine cannot hold is refused before it is computed; the real machine's memory
// stands in at run time.
TEST(BlendCommand, AGridLargerThanMemoryIsRefusedUpFront) {
  constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
  const Status refused = blendFitsInMemory(50'000'000, 4 * kGiB);
  EXPECT_EQ(refused.code(), StatusCode::kOutOfRange);
  EXPECT_EQ(refused.message(),
            "blend: 50000000 grid vertices need about 9.3 GiB, more than this machine's 4.0 GiB of memory; "
            "lower --res");
  EXPECT_TRUE(blendFitsInMemory(50'000'000, 16 * kGiB).ok());
  EXPECT_TRUE(blendFitsInMemory(50'000'000, 0).ok());  // memory unknown
}

// Just off a resonance the constraints hold to rounding while the surface bulges a hundred million
// times the data's size: written, since it is what was asked, with a warning.
TEST(BlendCommand, NearResonanceIsWrittenWithAWarning) {
  const fs::path dir = scratch("near_resonance");
  BlendCommandOptions o = options("3.17", dir / "x.obj");
  o.gamma = 0.0;
  o.beta = 39.4784176;  // 4 pi^2 is 39.47841760435743
  o.res = "8,8";
  Captured io;
  BlendReport report;
  ASSERT_EQ(blend(o, io, &report), kExitOk) << io.err.str();
  EXPECT_GT(report.reach, 1e6);
  EXPECT_NE(io.err.str().find("warning: blend: the surface reaches "), std::string::npos) << io.err.str();
  EXPECT_NE(io.err.str().find("times the size of its trimline data; (alpha, beta, gamma) lies near a resonance"),
            std::string::npos)
      << io.err.str();
  fs::remove_all(dir);
}

TEST(BlendCommand, IllPosedParametersFailWithTheReason) {
  const fs::path dir = scratch("failure");
  std::vector<CommandCase<BlendCommandOptions>> cases;
  BlendCommandOptions o = options("3.16", dir / "x.obj");
  o.alpha = 0.0;
  cases.push_back({o, "alpha = 0"});
  o = options("3.16", dir / "x.obj");
  o.beta = 4.0 * std::numbers::pi * std::numbers::pi;
  o.gamma = 0.0;
  cases.push_back({o, "is resonant"});
  o = options("3.16", dir / "out.obj" / "x.obj");
  cases.push_back({o, "out.obj: cannot create directory"});
  std::ofstream(dir / "out.obj") << "a file, not a folder";
  testing::expectRejected(cases, [](const BlendCommandOptions& opt, Captured& io) { return blend(opt, io); },
                          kExitFailure, "blend");
  EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

}  // namespace
}  // namespace odeskin

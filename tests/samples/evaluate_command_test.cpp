// SPDX-License-Identifier: MIT
// `odeskin evaluate --times` called as the program calls it: the in-betweens are played at the
// times given (the JSON's "t" fields, and the linear method's error recomputed here from the files
// at those times), and a bad times list (wrong count, not increasing, not finite) is a usage error
// with one error line and no JSON written.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/baselines/vertex_error.hpp"
#include "engine/io/obj_reader.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/evaluate_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Captured;
using testing::CommandCase;

const fs::path kCylinder = fs::path(ODESKIN_DATA_DIR) / "cylinder";

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_evaluate_test_", name); }

// The four poses-1 cylinders with their libigl rig: a small input every method fits in milliseconds.
EvaluateCommandOptions cylinderOptions(const fs::path& json) {
  EvaluateCommandOptions o;
  for (int k = 1; k <= 4; ++k) o.frames.push_back(kCylinder / "poses-1" / ("cylinder-" + std::to_string(k) + ".obj"));
  o.keys = {0, 3};
  o.methods = "linear,lbs";
  o.rig = (kCylinder / "cylinder.tgf").string();
  o.bind = kCylinder / "cylinder.obj";
  o.weights = kCylinder / "cylinder.DMAT";
  o.json = json;
  return o;
}

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

std::vector<Vec3> readPositions(const fs::path& path) {
  Result<ObjMesh> mesh = readObj(path);
  EXPECT_TRUE(mesh.ok()) << mesh.status().toString();
  return mesh.ok() ? mesh->positions : std::vector<Vec3>{};
}

// MVE of the linear blend of frames 0 and 3 at tau against frame f.
double linearMve(const EvaluateCommandOptions& o, double tau, std::size_t f) {
  const std::vector<Vec3> a = readPositions(o.frames[0]);
  const std::vector<Vec3> b = readPositions(o.frames[3]);
  std::vector<Vec3> blend;
  for (std::size_t i = 0; i < a.size(); ++i) blend.push_back((1.0 - tau) * a[i] + tau * b[i]);
  Result<VertexError> e = vertexError(blend, readPositions(o.frames[f]));
  EXPECT_TRUE(e.ok()) << e.status().toString();
  return e.ok() ? e->mve : -1.0;
}

TEST(EvaluateCommand, TimesPlaceTheInBetweens) {
  const fs::path dir = scratch("times");
  // Seconds, not frame indices, and unevenly spaced: tau = (t - 10) / (20 - 10) = 0.1 and 0.7.
  EvaluateCommandOptions o = cylinderOptions(dir / "times.json");
  o.times = {10.0, 11.0, 17.0, 20.0};
  Captured io;
  ASSERT_EQ(runEvaluateCommand(o, io.console), kExitOk) << io.err.str();
  const nlohmann::json doc = readJson(o.json);
  ASSERT_EQ(doc["frames"].size(), 2u) << doc.dump();
  const double expected_t[] = {0.1, 0.7};
  for (std::size_t i = 0; i < 2; ++i) {
    const nlohmann::json& frame = doc["frames"][i];
    EXPECT_EQ(frame["frame"].get<int>(), static_cast<int>(i + 1));
    EXPECT_NEAR(frame["t"].get<double>(), expected_t[i], 1e-15);
    // The method was played at that time, not only labelled with it.
    EXPECT_NEAR(frame["methods"]["linear"]["mve"].get<double>(), linearMve(o, expected_t[i], i + 1), 1e-12);
  }

  // Without --times the in-betweens sit at 1/3 and 2/3 (uniform in frame index), and score differently.
  o.times.clear();
  o.json = dir / "uniform.json";
  Captured uniform_io;
  ASSERT_EQ(runEvaluateCommand(o, uniform_io.console), kExitOk) << uniform_io.err.str();
  const nlohmann::json uniform = readJson(o.json);
  ASSERT_EQ(uniform["frames"].size(), 2u);
  EXPECT_NEAR(uniform["frames"][0]["t"].get<double>(), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(uniform["frames"][1]["t"].get<double>(), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(uniform["frames"][0]["methods"]["linear"]["mve"].get<double>(), linearMve(o, 1.0 / 3.0, 1), 1e-12);
  EXPECT_NE(uniform["frames"][0]["methods"]["linear"]["mve"].get<double>(),
            doc["frames"][0]["methods"]["linear"]["mve"].get<double>());
}

TEST(EvaluateCommand, TimesWithMoreKeysAreLocalToEachSegment) {
  // Keys 0, 2, 3: frame 1 lies in segment 0 at (4 - 0) / (5 - 0) = 0.8, so t = 0.8.
  const fs::path dir = scratch("segments");
  EvaluateCommandOptions o = cylinderOptions(dir / "segments.json");
  o.keys = {0, 2, 3};
  o.times = {0.0, 4.0, 5.0, 9.0};
  Captured io;
  ASSERT_EQ(runEvaluateCommand(o, io.console), kExitOk) << io.err.str();
  const nlohmann::json doc = readJson(o.json);
  ASSERT_EQ(doc["frames"].size(), 1u);
  EXPECT_EQ(doc["frames"][0]["frame"].get<int>(), 1);
  EXPECT_NEAR(doc["frames"][0]["t"].get<double>(), 0.8, 1e-15);
}

TEST(EvaluateCommand, BadTimesAndMethodsAreUsageErrors) {
  const fs::path dir = scratch("bad");
  const fs::path json = dir / "bad.json";
  auto with_times = [&](std::vector<double> times) {
    EvaluateCommandOptions o = cylinderOptions(json);
    o.times = std::move(times);
    return o;
  };
  auto with_methods = [&](const std::string& methods) {
    EvaluateCommandOptions o = cylinderOptions(json);
    o.methods = methods;
    return o;
  };
  auto with_rig = [&](const std::string& rig, int bones) {
    EvaluateCommandOptions o = cylinderOptions(json);
    o.rig = rig;
    o.bind.clear();
    o.weights.clear();
    o.bones = bones;
    return o;
  };
  auto with_up = [&](const std::string& rig, const std::string& up) {
    EvaluateCommandOptions o = with_rig(rig, 0);
    o.up = up;
    return o;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<CommandCase<EvaluateCommandOptions>> cases{
      {with_times({0.0, 1.0, 2.0}), "3 times for 4 frames"},
      {with_times({0.0, 1.0, 2.0, 3.0, 4.0}), "5 times for 4 frames"},
      {with_times({0.0, 1.0, 1.0, 2.0}), "times must be strictly increasing (frame 2)"},
      {with_times({0.0, 2.0, 1.0, 3.0}), "times must be strictly increasing (frame 2)"},
      {with_times({0.0, nan, 2.0, 3.0}), "the time of frame 1 is not finite"},
      {with_times({0.0, 1.0, 2.0, std::numeric_limits<double>::infinity()}), "the time of frame 3 is not finite"},
      {with_methods(",lbs"), "--methods ',lbs' has an empty name (a comma too many)"},
      {with_methods("lbs,,dqs"), "--methods 'lbs,,dqs' has an empty name"},
      {with_methods("lbs,skin"), "unknown method 'skin'"},
      {with_rig("curves", 3), "--bones applies to the automatic rig (--rig auto)"},
      {with_up("auto", "z"), "--up applies to --rig curves"},
      {with_up("curves", "up"), "--up 'up' must be x, y, z, -x, -y or -z"},
  };
  testing::expectRejected(
      cases, [](const EvaluateCommandOptions& o, Captured& io) { return runEvaluateCommand(o, io.console); },
      kExitUsage, "evaluate");
  EXPECT_FALSE(fs::exists(json)) << "a rejected command must not write its JSON";
}

TEST(EvaluateCommand, PicturesWithoutADeviceFailBeforeAnythingIsWritten) {
  const fs::path dir = scratch("no_device");
  EvaluateCommandOptions o = cylinderOptions(dir / "scores.json");
  o.png_dir = dir / "pictures";
  Captured io;
  EXPECT_EQ(runEvaluateCommand(o, io.console, "no-such-device"), kExitFailure);
  EXPECT_NE(io.err.str().find("evaluate: --png: drawing needs a Vulkan device"), std::string::npos) << io.err.str();
  EXPECT_FALSE(fs::exists(o.json));
  EXPECT_FALSE(fs::exists(o.png_dir));
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin reconstruct` called as the program calls it, on a triangulated height field and two poses
// of it (another surface, and one with two vertices swapped as a renumbered file has them): the
// reconstructions keep the mesh's faces and vertex order and lie on the surface, the flagged pose
// gets its reference file, the report and the network file are complete and readable; bad options
// are usage errors (exit 2) and bad inputs failures (exit 1) with one line naming the file, and
// nothing is left behind.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/surfaces/network_json.hpp"
#include "engine/surfaces/tessellation.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/reconstruct_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Captured;
using testing::CommandCase;

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_reconstruct_test_", name); }

int run(const ReconstructCommandOptions& o, Captured& io) { return runReconstructCommand(o, io.console); }

// z = f(x, y) over [-1, 1] x [-0.8, 0.8] on a 41 x 33 grid, two triangles per cell.
ObjMesh heightField(const std::function<double(double, double)>& f) {
  ObjMesh m;
  const std::uint32_t nx = 41, ny = 33;
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      const double x = -1.0 + 2.0 * i / (nx - 1), y = -0.8 + 1.6 * j / (ny - 1);
      m.positions.emplace_back(x, y, f(x, y));
    }
  }
  for (std::uint32_t j = 0; j + 1 < ny; ++j) {
    for (std::uint32_t i = 0; i + 1 < nx; ++i) {
      const std::uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      for (const std::array<std::uint32_t, 3>& t : {std::array{a, b, d}, std::array{a, d, c}}) {
        m.faces.indices.insert(m.faces.indices.end(), t.begin(), t.end());
        m.faces.face_offsets.push_back(static_cast<std::uint32_t>(m.faces.indices.size()));
      }
    }
  }
  return m;
}

fs::path write(const fs::path& path, const ObjMesh& m) {
  EXPECT_TRUE(writeObj(path, m.positions, m.faces).ok()) << path;
  return path;
}

double wavy(double x, double y) { return 0.15 * std::sin(1.3 * x + 0.4) * std::cos(1.1 * y) + 0.1 * x * x; }

struct Inputs {
  fs::path mesh, pose, torn;
};

Inputs writeInputs(const fs::path& dir) {
  const ObjMesh mesh = heightField(wavy);
  ObjMesh pose = heightField([](double x, double y) { return wavy(x, y) + 0.1 * std::sin(2.0 * x) * y; });
  ObjMesh torn = pose;
  std::swap(torn.positions[5 * 41 + 6], torn.positions[25 * 41 + 30]);
  fs::create_directories(dir / "in");
  return {write(dir / "in" / "mesh.obj", mesh), write(dir / "in" / "pose.obj", pose), write(dir / "in" / "torn.obj", torn)};
}

ReconstructCommandOptions options(const Inputs& in) {
  ReconstructCommandOptions o;
  o.mesh = in.mesh;
  o.rows = 6;
  o.columns = 4;
  o.points = 3;
  return o;
}

TEST(ReconstructCommand, WritesReconstructionsReportAndNetwork) {
  const fs::path dir = scratch("valid");
  const Inputs in = writeInputs(dir);
  ReconstructCommandOptions o = options(in);
  o.poses = {in.pose, in.torn};
  o.output = dir / "out" / "recon.obj";
  o.network = dir / "out" / "net.json";
  o.json = dir / "out" / "report.json";
  Captured io;
  ReconstructReport report;
  ASSERT_EQ(runReconstructCommand(o, io.console, &report), kExitOk) << io.err.str();
  EXPECT_TRUE(io.err.str().empty()) << io.err.str();
  const std::string out = io.out.str();
  EXPECT_NE(out.find("network: 6 x 4 patches (rho 1, eta 3, lambda 1), 7 boundaries x 3 curves x 13 points = 273 points"),
            std::string::npos) << out;
  EXPECT_NE(out.find("size: 819 floats against 4059 for the vertices: 5.0x smaller"), std::string::npos) << out;

  // Every file has the mesh's faces and vertex order, and lies on its pose.
  const ObjMesh mesh = *readObj(in.mesh);
  ASSERT_EQ(report.poses.size(), 3u);
  for (const auto& [file, pose] : {std::pair{dir / "out" / "recon.obj", in.mesh}, std::pair{dir / "out" / "recon-pose.obj", in.pose},
                                   std::pair{dir / "out" / "recon-torn.obj", in.pose}}) {
    Result<ObjMesh> r = readObj(file);
    ASSERT_TRUE(r.ok()) << r.status().toString();
    EXPECT_EQ(r->faces.indices, mesh.faces.indices);
    const ObjMesh truth = *readObj(pose);
    ASSERT_EQ(r->positions.size(), truth.positions.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < truth.positions.size(); ++i) worst = std::max(worst, glm::distance(r->positions[i], truth.positions[i]));
    EXPECT_LT(worst, 2e-3) << file;  // the box is 2 units wide; the network is coarse
  }
  // The swapped vertices and their neighbours are flagged, left out, and filled in the reference.
  const ReconstructPoseReport& torn = report.poses[2];
  EXPECT_EQ(torn.flagged_vertices, 14u);
  EXPECT_EQ(torn.measured_vertices, mesh.positions.size() - 14u);
  EXPECT_GT(torn.flagged_max, 0.5);
  EXPECT_NEAR(torn.mean, report.poses[1].mean, 0.1 * report.poses[1].mean);
  EXPECT_EQ(torn.reference, dir / "out" / "recon-torn-reference.obj");
  const ObjMesh filled = *readObj(torn.reference);
  EXPECT_LT(glm::distance(filled.positions[5 * 41 + 6], readObj(in.pose)->positions[5 * 41 + 6]), 1e-3);
  EXPECT_TRUE(report.poses[0].reference.empty());
  EXPECT_FALSE(fs::exists(dir / "out" / "recon-pose-reference.obj"));
  EXPECT_LT(report.poses[0].max_surface, 1e-3);
  EXPECT_LE(report.poses[0].mean_surface, report.poses[0].mean);

  // The report says what the summary says.
  std::ifstream json_file(o.json);
  const nlohmann::json json = nlohmann::json::parse(json_file);
  EXPECT_EQ(json["stored_points"], 273);
  EXPECT_EQ(json["mesh_floats"], 3 * 41 * 33);
  EXPECT_EQ(json["poses"].size(), 3u);
  EXPECT_EQ(json["poses"][2]["flagged_vertices"], 14);
  EXPECT_DOUBLE_EQ(json["poses"][1]["max_surface"].get<double>(), report.poses[1].max_surface);
  // The network file is a valid network: odeskin surface tessellates it.
  Result<Network> network = loadNetwork(o.network);
  ASSERT_TRUE(network.ok()) << network.status().toString();
  EXPECT_EQ(network->rows(), 6u);
  EXPECT_EQ(network->columns(), 4u);
  EXPECT_TRUE(tessellateNetwork(*network, {5, 5}).ok());
}

// A window far below the facets differentiates the mesh's kinks: the rebuilt surface is far off, and
// is said to be; smaller still, the derivatives overflow, and the message names the window.
TEST(ReconstructCommand, ATinyDerivativeWindowIsWarnedOfOrRefused) {
  const fs::path dir = scratch("window");
  const Inputs in = writeInputs(dir);
  ReconstructCommandOptions o = options(in);
  o.derivative_fit = "6,3,1e-4";
  Captured warned;
  ReconstructReport report;
  ASSERT_EQ(runReconstructCommand(o, warned.console, &report), kExitOk) << warned.err.str();
  ASSERT_EQ(report.poses.size(), 1u);
  EXPECT_GT(report.poses[0].max, 0.2);
  EXPECT_NE(warned.err.str().find("warning: " + in.mesh.string() + ": the rebuilt surface misses vertex " +
                                  std::to_string(report.poses[0].worst_vertex + 1) + " by "),
            std::string::npos)
      << warned.err.str();
  EXPECT_NE(warned.err.str().find("a --derivative-fit window of 0.0001 row heights"), std::string::npos) << warned.err.str();

  o.derivative_fit = "6,3,1e-300";
  o.output = dir / "out" / "recon.obj";
  Captured refused;
  EXPECT_EQ(run(o, refused), kExitFailure);
  EXPECT_NE(refused.err.str().find(in.mesh.string() + ": boundary 0: the derivative fit over a window of 1e-300 row "
                                   "heights gives u-derivatives that are not finite"),
            std::string::npos)
      << refused.err.str();
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(ReconstructCommand, BadOptionsAreUsageErrors) {
  const fs::path dir = scratch("usage");
  const Inputs in = writeInputs(dir);
  const fs::path out = dir / "out";
  std::vector<CommandCase<ReconstructCommandOptions>> cases;
  const auto with = [&](const std::function<void(ReconstructCommandOptions&)>& change, const std::string& message) {
    ReconstructCommandOptions o = options(in);
    change(o);
    cases.push_back({o, message});
  };
  with([&](auto& o) { o.output = out / "recon.ply"; }, "-o " + (out / "recon.ply").string() + ": write .obj");
  with([&](auto& o) { o.network = out / "net.obj"; }, "--network");
  with([&](auto& o) { o.json = out / "report.txt"; }, "--json");
  with([&](auto& o) { o.rows = 0; }, "--rows 0 is outside [1, 1000]");
  with([&](auto& o) { o.columns = 1001; }, "--cols 1001");
  with([&](auto& o) { o.points = 0; }, "--points 0");
  with(
      [&](auto& o) {
        o.rows = 1000;
        o.columns = 1000;
        o.points = 10;
      },
      "mesh samples per pose, more than 10000000");
  with([&](auto& o) { o.shape = "1,3"; }, "--shape '1,3'");
  with([&](auto& o) { o.shape = "1,nan,1"; }, "three finite numbers");
  with([&](auto& o) { o.shape = "1,3,1,"; }, "--shape");
  with([&](auto& o) { o.derivative_fit = "6,9,0.5"; }, "--derivative-fit '6,9,0.5'");
  with([&](auto& o) { o.derivative_fit = "6,3,0"; }, "WINDOW in (0, 1]");
  with([&](auto& o) { o.derivative_fit = "6.5,3,0.5"; }, "--derivative-fit");
  with([&](auto& o) { o.tear_ratio = 1.0; }, "--tear-ratio 1 must be");
  with([&](auto& o) { o.mesh.clear(); }, "MESH.obj is required");
  with([&](auto& o) { o.output = in.mesh; }, "is an input; it would be overwritten");
  with(
      [&](auto& o) {
        o.poses = {in.pose, dir / "elsewhere" / "pose.obj"};
        o.output = out / "recon.obj";
      },
      "two outputs would be");
  testing::expectRejected(cases, run, kExitUsage, "reconstruct");
  EXPECT_FALSE(fs::exists(out)) << "a rejected command wrote something";
}

TEST(ReconstructCommand, BadInputsFailNamingTheFile) {
  const fs::path dir = scratch("failure");
  const Inputs in = writeInputs(dir);
  const fs::path out = dir / "out";
  // A closed mesh, a pose of another mesh, a pose with a changed face, a file that is no OBJ.
  ObjMesh tetra;
  tetra.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.faces.indices = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
  tetra.faces.face_offsets = {0, 3, 6, 9, 12};
  const fs::path closed = write(dir / "in" / "closed.obj", tetra);
  ObjMesh changed = *readObj(in.pose);
  std::swap(changed.faces.indices[30], changed.faces.indices[31]);
  const fs::path flipped = write(dir / "in" / "flipped.obj", changed);
  const fs::path garbage = dir / "in" / "garbage.obj";
  std::ofstream(garbage) << "v 0 0 nan\nf 1 1 1\n";
  // The mesh and a pose scaled to 1e200 across: finite, but their squared lengths overflow.
  ObjMesh scaled = *readObj(in.pose);
  for (Vec3& p : scaled.positions) p *= 1e200;
  const fs::path huge = write(dir / "in" / "huge.obj", scaled);

  std::vector<CommandCase<ReconstructCommandOptions>> cases;
  const auto with = [&](const std::function<void(ReconstructCommandOptions&)>& change, const std::string& message) {
    ReconstructCommandOptions o = options(in);
    o.output = out / "recon.obj";
    o.json = out / "report.json";
    change(o);
    cases.push_back({o, message});
  };
  with([&](auto& o) { o.mesh = dir / "in" / "absent.obj"; }, "absent.obj");
  with([&](auto& o) { o.mesh = closed; }, closed.string() + ": the mesh is closed");
  with([&](auto& o) { o.mesh = garbage; }, "garbage.obj");
  with([&](auto& o) { o.poses = {in.pose, closed}; }, closed.string() + ": 4 vertices, " + in.mesh.string() + " has 1353");
  with([&](auto& o) { o.poses = {flipped}; }, flipped.string() + ": face 11 differs");
  with([&](auto& o) { o.mesh = huge; }, huge.string() + ": the mesh is too large for double-precision distances");
  with([&](auto& o) { o.poses = {huge}; }, huge.string() + ": the pose: the mesh is too large for double-precision distances");
  with([&](auto& o) { o.shape = "1,80.76291422570652,0"; }, "--shape 1,80.76291422570652,0: ");
  with([&](auto& o) { o.shape = "0,3,1"; }, "--shape 0,3,1: ");
  testing::expectRejected(cases, run, kExitFailure, "reconstruct");
  EXPECT_FALSE(fs::exists(out)) << "a failed command wrote something";

  // An output folder that cannot be made: nothing of the other outputs stays.
  std::ofstream(dir / "blocker") << "a file, not a folder";
  ReconstructCommandOptions o = options(in);
  o.json = dir / "report.json";
  o.output = dir / "blocker" / "recon.obj";
  std::vector<CommandCase<ReconstructCommandOptions>> blocked{{o, "blocker: cannot create directory"}};
  testing::expectRejected(blocked, run, kExitFailure, "reconstruct");
  EXPECT_FALSE(fs::exists(dir / "report.json"));
}

}  // namespace
}  // namespace odeskin

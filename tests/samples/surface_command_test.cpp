// SPDX-License-Identifier: MIT
// `odeskin surface` called as the program calls it: the sample networks become valid .glb files
// (read back with tinygltf: positions, unit normals, triangles of the welded grid) and OBJ files;
// the Vulkan backend writes the same mesh within the GPU parity bound; a bad network - malformed
// JSON, a missing field, a NaN parameter, a resonant shape, a pairing that cannot be C2, a missing
// file - ends with exit 1 and one line naming the file and the field, and leaves no file behind;
// bad options end with exit 2.
#include <cmath>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "engine/io/obj_reader.hpp"
#include "engine/surfaces/network_json.hpp"
#include "engine/surfaces/tessellation.hpp"
#include "host/device.hpp"
#include "host/gpu_test_support.hpp"
#include "samples/command_test_support.hpp"
#include "samples/odeskin/surface_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using testing::Captured;
using testing::CommandCase;

const fs::path kNetworks = fs::path(ODESKIN_SOURCE_DIR) / "samples/surfaces/networks";

fs::path scratch(const std::string& name) { return testing::scratchDir("odeskin_surface_test_", name); }

std::string readText(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

int run(const SurfaceCommandOptions& o, Captured& io) { return runSurfaceCommand(o, io.console); }

// The accessor's data as floats (tightly packed VEC3 / SCALAR uint32 only, as we write them).
template <typename T>
std::vector<T> accessorData(const tinygltf::Model& m, int index) {
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  const std::size_t components = a.type == TINYGLTF_TYPE_VEC3 ? 3 : 1;
  std::vector<T> out(a.count * components);
  std::memcpy(out.data(), m.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + a.byteOffset,
              out.size() * sizeof(T));
  return out;
}

TEST(SurfaceCommand, WritesAValidGlbAndObj) {
  const fs::path dir = scratch("valid");
  for (const char* name : {"vase", "sheet", "torus"}) {
    SurfaceCommandOptions o;
    o.network = kNetworks / (std::string(name) + ".json");
    o.output = dir / "out" / (std::string(name) + ".glb");
    o.resolution = "17,13";
    o.obj = true;
    Captured io;
    SurfaceReport report;
    ASSERT_EQ(runSurfaceCommand(o, io.console, &report), 0) << io.err.str();
    EXPECT_NE(io.out.str().find("no open edge where patches meet"), std::string::npos) << io.out.str();

    // The reference mesh this must be.
    Result<Network> network = loadNetwork(o.network);
    ASSERT_TRUE(network.ok());
    Result<SurfaceMesh> mesh = tessellateNetwork(*network, {17, 13});
    ASSERT_TRUE(mesh.ok());
    EXPECT_EQ(report.vertices, mesh->positions.size());
    EXPECT_EQ(report.rim_edges, unsharedEdges(mesh->faces).size());

    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &error, &warning, o.output.string())) << error;
    ASSERT_EQ(m.meshes.size(), 1u);
    const tinygltf::Primitive& p = m.meshes[0].primitives.at(0);
    const std::vector<float> xyz = accessorData<float>(m, p.attributes.at("POSITION"));
    const std::vector<float> normals = accessorData<float>(m, p.attributes.at("NORMAL"));
    const std::vector<std::uint32_t> indices = accessorData<std::uint32_t>(m, p.indices);
    ASSERT_EQ(xyz.size(), 3 * mesh->positions.size());
    EXPECT_EQ(indices.size(), 6 * mesh->faces.faceCount());
    EXPECT_EQ(indices.size(), 3 * report.triangles);
    for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(xyz[3 * i + k], static_cast<float>(mesh->positions[i][k]));
      const double length = std::hypot(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
      EXPECT_NEAR(length, 1.0, 1e-6);
    }
    for (std::uint32_t index : indices) EXPECT_LT(index, mesh->positions.size());

    Result<ObjMesh> obj = readObj(dir / "out" / (std::string(name) + ".obj"));
    ASSERT_TRUE(obj.ok()) << obj.status().toString();
    EXPECT_EQ(obj->positions.size(), mesh->positions.size());
  }
  fs::remove_all(dir);
}

// glTF is y-up; the sample networks are z-up and lay on their side in every viewer. --up turns the
// mesh node, never the positions.
TEST(SurfaceCommand, UpTurnsTheNodeToGltfsUp) {
  const fs::path dir = scratch("up");
  const std::vector<std::pair<std::string, std::vector<double>>> cases = {
      {"y", {}}, {"z", {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}}, {"-z", {std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)}},
      {"x", {0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)}}, {"-y", {1.0, 0.0, 0.0, 0.0}}};
  for (const auto& [axis, rotation] : cases) {
    SurfaceCommandOptions o;
    o.network = kNetworks / "vase.json";
    o.output = dir / ("vase_" + axis + ".glb");
    o.resolution = "5,5";
    o.up = axis;
    Captured io;
    ASSERT_EQ(runSurfaceCommand(o, io.console), 0) << io.err.str();
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &error, &warning, o.output.string())) << error;
    ASSERT_EQ(m.nodes.size(), 1u);
    ASSERT_EQ(m.nodes[0].rotation.size(), rotation.size()) << axis;
    for (std::size_t k = 0; k < rotation.size(); ++k) EXPECT_NEAR(m.nodes[0].rotation[k], rotation[k], 1e-15) << axis;
  }
  fs::remove_all(dir);
}

TEST(SurfaceCommand, ShapeOverridesEveryPatch) {
  const fs::path dir = scratch("shape");
  SurfaceCommandOptions o;
  o.network = kNetworks / "fig4_1b.json";  // refused as written: (1, 3, 1) next to (0.1, 3, 0.1)
  o.output = dir / "fig.glb";
  o.shape = "0.1,0.3,0.1";
  Captured io;
  ASSERT_EQ(run(o, io), 0) << io.err.str();
  EXPECT_NE(io.out.str().find("regimes: B (1 set of cardinal functions)"), std::string::npos) << io.out.str();
  o.shape = "1,80.78355056537535,1";
  Captured resonant;
  EXPECT_EQ(run(o, resonant), kExitFailure);
  EXPECT_NE(resonant.err.str().find("fig4_1b.json: patch (row 0, column 0): ode6: resonant"), std::string::npos)
      << resonant.err.str();
  // A denormal is a number, so the network says why it cannot be used.
  o.shape = "1e-320,3,1";
  Captured tiny;
  EXPECT_EQ(run(o, tiny), kExitFailure);
  EXPECT_NE(tiny.err.str().find("fig4_1b.json: patch (row 0, column 0): ode6: eta/rho or lambda/rho overflows"),
            std::string::npos)
      << tiny.err.str();
  fs::remove_all(dir);
}

TEST(SurfaceCommand, ValidationOnTheCpuBackendIsANote) {
  const fs::path dir = scratch("validation");
  SurfaceCommandOptions o;
  o.network = kNetworks / "sheet.json";
  o.output = dir / "sheet.glb";
  o.validation = true;
  Captured io;
  ASSERT_EQ(run(o, io), 0) << io.err.str();
  EXPECT_NE(io.err.str().find("note: --validation checks Vulkan calls, and --backend cpu makes none"), std::string::npos)
      << io.err.str();
  EXPECT_TRUE(fs::exists(o.output));
  fs::remove_all(dir);
}

TEST(SurfaceCommand, VulkanBackendWritesTheSameMesh) {
  if (!vk::Gpu::open("auto", false).ok()) {
    if (testing::gpuRequired()) FAIL() << "ODESKIN_REQUIRE_GPU=1 but no Vulkan device";
    GTEST_SKIP() << "no Vulkan device";
  }
  const fs::path dir = scratch("vulkan");
  SurfaceCommandOptions o;
  o.network = kNetworks / "vase.json";
  o.output = dir / "vase.glb";
  o.backend = "vulkan";
  o.validation = true;
  o.resolution = "21,19";
  Captured io;
  ASSERT_EQ(run(o, io), 0) << io.err.str();
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &error, &warning, o.output.string())) << error;
  const std::vector<float> xyz = accessorData<float>(m, m.meshes[0].primitives[0].attributes.at("POSITION"));
  Result<SurfaceMesh> mesh = tessellateNetwork(*loadNetwork(o.network), {21, 19});
  ASSERT_TRUE(mesh.ok());
  ASSERT_EQ(xyz.size(), 3 * mesh->positions.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < mesh->positions.size(); ++i) {
    worst = std::max(worst, glm::length(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]) - mesh->positions[i]));
  }
  EXPECT_LE(worst, 1e-5 * 3.3);  // the vase's longest box side is 3.3
  fs::remove_all(dir);
}

TEST(SurfaceCommand, BadNetworksNameTheFileAndFieldAndLeaveNothing) {
  const fs::path dir = scratch("bad");
  const std::string sheet = readText(kNetworks / "sheet.json");
  const fs::path syntax = writeText(dir / "syntax.json", replaced(sheet, "\"columns\": 3,", "\"columns\": 3,,"));
  const fs::path missing = writeText(dir / "missing.json", replaced(sheet, "\"version\": 1,", ""));
  const fs::path no_curve = writeText(dir / "no_curve.json", replaced(sheet, "\"curve\": \"mid\", ", ""));
  const fs::path nan = writeText(dir / "nan.json", replaced(sheet, "\"eta\": 3", "\"eta\": NaN"));
  const fs::path huge = writeText(dir / "huge.json", replaced(sheet, "\"lambda\": 1}", "\"lambda\": 1e999}"));
  const fs::path resonant = writeText(dir / "resonant.json", replaced(sheet, "\"eta\": 3", "\"eta\": 80.78355056537535"));
  const fs::path zero_rho = writeText(dir / "zero_rho.json", replaced(sheet, "\"rho\": 1", "\"rho\": 0"));
  // One control point at 1e50: the surface reaches beyond what glTF's float32 positions hold.
  const fs::path far = writeText(dir / "far.json", replaced(sheet, "[3, 0, 0]]}", "[3, 0, 1e50]]}"));
  // At 1e308 the solve itself overflows: the network is named, not the output file.
  const fs::path inf = writeText(dir / "inf.json", replaced(sheet, "[3, 0, 0]]}", "[3, 0, 1e308]]}"));
  auto options = [&](const fs::path& network) {
    SurfaceCommandOptions o;
    o.network = network;
    o.output = dir / "out.glb";
    o.obj = true;
    return o;
  };
  const std::vector<CommandCase<SurfaceCommandOptions>> cases = {
      {options(syntax), syntax.string() + ": columns: invalid JSON (line 4"},
      {options(missing), missing.string() + ": version: missing"},
      {options(no_curve), no_curve.string() + ": boundaries[1].curve: missing"},
      {options(nan), nan.string() + ": shape.eta: invalid JSON"},
      {options(nan), "JSON has no NaN or Infinity"},
      {options(huge), huge.string() + ": shape.lambda: invalid JSON"},
      {options(resonant), resonant.string() + ": patch (row 0, column 0): ode6: resonant shape parameters"},
      {options(zero_rho), zero_rho.string() + ": patch (row 0, column 0): ode6: rho = 0"},
      {options(far), far.string() + ": surface glTF: vertex"},
      {options(far), "is outside glTF's float32 range"},
      {options(inf), inf.string() + ": the surface is not finite at vertex "},
      {options(kNetworks / "fig4_1b.json"), "erratum F9"},
      {options(dir / "absent.json"), (dir / "absent.json").string() + ": cannot open"},
  };
  testing::expectRejected(cases, run, kExitFailure, "surface");
  EXPECT_FALSE(fs::exists(dir / "out.glb"));
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
  EXPECT_FALSE(fs::exists(dir / "out.glb.partial"));
  fs::remove_all(dir);
}

// A grid the machine cannot hold is refused before any tessellation (Linux would grant the memory
// and kill the process once it was used); the real machine's memory stands in at run time.
TEST(SurfaceCommand, AGridLargerThanMemoryIsRefusedUpFront) {
  constexpr std::uint64_t kGiB = std::uint64_t{1} << 30;
  const Status refused = surfaceFitsInMemory(12'000'000, 2 * kGiB);
  EXPECT_EQ(refused.code(), StatusCode::kOutOfRange);
  EXPECT_EQ(refused.message(),
            "12000000 vertices, tessellated and written, need about 3.6 GiB, more than this machine's 2.0 GiB of "
            "memory; lower --res");
  EXPECT_TRUE(surfaceFitsInMemory(12'000'000, 8 * kGiB).ok());
  EXPECT_TRUE(surfaceFitsInMemory(12'000'000, 0).ok());  // memory unknown
  EXPECT_TRUE(surfaceFitsInMemory(2 * kGiB / kSurfaceBytesPerVertex, 2 * kGiB).ok());
  EXPECT_FALSE(surfaceFitsInMemory(2 * kGiB / kSurfaceBytesPerVertex + 1, 2 * kGiB).ok());
}

TEST(SurfaceCommand, BadOptionsAreUsageErrors) {
  const fs::path dir = scratch("usage");
  auto options = [&](const std::string& output, const std::string& res) {
    SurfaceCommandOptions o;
    o.network = kNetworks / "vase.json";
    o.output = dir / output;
    o.resolution = res;
    return o;
  };
  auto shaped = [&](const std::string& shape) {
    SurfaceCommandOptions o = options("x.glb", "9,9");
    o.shape = shape;
    return o;
  };
  SurfaceCommandOptions backend = options("x.glb", "9,9");
  backend.backend = "metal";
  SurfaceCommandOptions up = options("x.glb", "9,9");
  up.up = "w";
  const std::vector<CommandCase<SurfaceCommandOptions>> cases = {
      {options("x.gltf", "9,9"), "x.gltf: write .glb"},
      {options("x.glb", "1,9"), "--res '1,9'"},
      {options("x.glb", "9"), "--res '9'"},
      {options("x.glb", "9,x"), "--res '9,x'"},
      {options("x.glb", "-3,9"), "--res '-3,9'"},
      {backend, "--backend must be cpu, vulkan or auto"},
      {up, "surface: --up 'w' must be x, y, z, -x, -y or -z"},
      {shaped("1,3"), "--shape '1,3': expected RHO,ETA,LAMBDA"},
      {shaped("1,3,x"), "--shape '1,3,x'"},
      {shaped("1,3,1,2"), "--shape '1,3,1,2'"},
      {shaped("1,nan,1"), "--shape '1,nan,1'"},
      {shaped("0x10,3,1"), "--shape '0x10,3,1'"},
      {shaped("1, 3,1"), "--shape '1, 3,1'"},
  };
  testing::expectRejected(cases, run, kExitUsage, "surface");
  EXPECT_TRUE(fs::is_empty(dir));
  // Too fine for one mesh: a failure about this network at this resolution, not a usage error.
  Captured io;
  EXPECT_EQ(run(options("x.glb", "99999,99999"), io), kExitFailure);
  EXPECT_NE(io.err.str().find("vase.json: tessellation: "), std::string::npos) << io.err.str();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "output_paths.hpp"
#include "surface_command.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <vector>

#include "engine/core/finite_vector.hpp"
#include "engine/core/machine_memory.hpp"
#include "engine/core/number_text.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/surfaces/network_json.hpp"
#include "engine/surfaces/tessellation_glb.hpp"
#include "file_extension.hpp"
#include "host/surface_tessellator.hpp"
#include "up_axis.hpp"

namespace odeskin {
namespace {

// "U,V" with integers >= 2.
bool parseResolution(const std::string& text, TessellationResolution& r) {
  unsigned long u = 0, v = 0;
  std::size_t used = 0;
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return false;
  try {
    u = std::stoul(text.substr(0, comma), &used);
    if (used != comma) return false;
    v = std::stoul(text.substr(comma + 1), &used);
    if (used != text.size() - comma - 1) return false;
  } catch (const std::exception&) {
    return false;
  }
  if (u < 2 || v < 2 || u > 100000 || v > 100000 || !std::isdigit(static_cast<unsigned char>(text[0])) ||
      !std::isdigit(static_cast<unsigned char>(text[comma + 1]))) {
    return false;
  }
  r.u_samples = static_cast<std::uint32_t>(u);
  r.v_samples = static_cast<std::uint32_t>(v);
  return true;
}

// "RHO,ETA,LAMBDA" with three finite numbers.
bool parseShape(const std::string& text, Ode6Shape& shape) {
  const std::optional<std::vector<double>> values = finiteNumbersIn(text, 3);
  if (!values) return false;
  shape = {(*values)[0], (*values)[1], (*values)[2]};
  return true;
}

// --obj: OUT.obj beside OUT.glb.
std::filesystem::path objPath(const SurfaceCommandOptions& o) { return std::filesystem::path(o.output).replace_extension(".obj"); }

std::string usageProblem(const SurfaceCommandOptions& o, TessellationResolution& r, Ode6Shape& shape, Vec3& up) {
  if (o.output.empty()) return "surface: -o OUT.glb is required";
  if (lowerExtension(o.output) != ".glb") {
    return "surface: " + o.output.string() + ": write .glb (one self-contained glTF binary; add --obj for an OBJ too)";
  }
  const std::filesystem::path inputs[] = {o.network};
  for (const std::filesystem::path& out : {o.output, o.obj ? objPath(o) : std::filesystem::path()}) {
    if (overwritesInput(out, inputs)) return "surface: " + out.string() + " is an input; it would be overwritten";
  }
  if (!parseResolution(o.resolution, r)) {
    return "surface: --res '" + o.resolution + "': expected U,V samples per patch, integers in [2, 100000]";
  }
  if (o.backend != "cpu" && o.backend != "vulkan" && o.backend != "auto") {
    return "surface: --backend must be cpu, vulkan or auto, got '" + o.backend + "'";
  }
  if (!o.shape.empty() && !parseShape(o.shape, shape)) {
    return "surface: --shape '" + o.shape + "': expected RHO,ETA,LAMBDA, three finite numbers";
  }
  Result<Vec3> axis = parseUpAxis(o.up);
  if (!axis.ok()) return "surface: " + axis.status().message();
  up = *axis;
  return {};
}

// The welded mesh on the GPU: same grid and faces, float positions widened.
Result<SurfaceMesh> tessellateOnGpu(const SurfaceCommandOptions& o, const Network& network, TessellationResolution r,
                                    double& seconds) {
  vk::DebugLog log;
  vk::InstanceOptions instance_options;
  instance_options.validation = o.validation;
  instance_options.debug_log = &log;
  SurfaceMesh mesh;
  {
    ODESKIN_ASSIGN_OR_RETURN(vk::Instance instance, vk::Instance::create(instance_options));
    ODESKIN_ASSIGN_OR_RETURN(vk::Device device, vk::Device::create(instance, o.device));
    ODESKIN_ASSIGN_OR_RETURN(SurfaceTessellator gpu, SurfaceTessellator::create(device, network, r));
    const auto start = std::chrono::steady_clock::now();
    ODESKIN_TRY(gpu.run());
    std::vector<gpu::Float4> out(gpu.grid().vertexCount());
    ODESKIN_TRY(gpu.readPositions(out));
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    mesh.grid = gpu.grid();
    mesh.faces = gridFaces(mesh.grid);
    mesh.positions.reserve(out.size());
    for (const gpu::Float4& p : out) mesh.positions.emplace_back(p.x, p.y, p.z);
  }
  if (o.validation && log.count() > 0) {
    return deviceError("surface: the validation layer reported " + std::to_string(log.count()) +
                       " message(s), the first: " + log.messages().front());
  }
  return mesh;
}

void printSummary(std::ostream& out, const SurfaceCommandOptions& o, const Network& n, TessellationResolution r,
                  const SurfaceReport& report, const std::filesystem::path& obj) {
  out << "surface " << o.network.filename().string() << " -> " << o.output.string();
  if (!obj.empty()) out << " and " << obj.string();
  out << ": " << n.rows() << " x " << n.columns() << " patches";
  if (n.closedU() || n.closedV()) {
    out << " (closed in " << (n.closedU() && n.closedV() ? "u and v" : n.closedU() ? "u" : "v") << ")";
  }
  out << ", " << r.u_samples << " x " << r.v_samples << " samples each\n";
  out << "mesh: " << report.vertices << " vertices, " << report.triangles << " triangles, welded; "
      << (report.rim_edges == 0 ? std::string("closed (no rim)") : std::to_string(report.rim_edges) + " rim edges")
      << ", no open edge where patches meet\n";
  std::set<std::string> regimes;
  for (std::uint32_t k = 0; k < n.cardinalCount(); ++k) regimes.insert(ode6RegimeName(n.cardinalAt(k).regime()));
  out << "regimes:";
  for (const std::string& name : regimes) out << " " << name.substr(0, 1);
  out << " (" << n.cardinalCount() << " set" << (n.cardinalCount() == 1 ? "" : "s") << " of cardinal functions)\n";
  char ms[32];
  std::snprintf(ms, sizeof ms, "%.3g", 1e3 * report.tessellate_seconds);
  out << "tessellated on " << report.backend << " in " << ms << " ms"
      << (report.backend == "vulkan" ? " (dispatch and read back)" : "")
      << "\n";
}

}  // namespace

Status surfaceFitsInMemory(std::uint64_t vertices, std::uint64_t memory_bytes) {
  // vertices <= kMaxTessellationVertices (2^26), so the product stays far from overflow.
  return checkFitsInMemory(vertices * kSurfaceBytesPerVertex, memory_bytes,
                           std::to_string(vertices) + " vertices, tessellated and written,", "lower --res");
}

int runSurfaceCommand(const SurfaceCommandOptions& o, Console& console, SurfaceReport* report_out) {
  TessellationResolution resolution;
  Ode6Shape shape;
  Vec3 up(0.0, 1.0, 0.0);
  if (const std::string problem = usageProblem(o, resolution, shape, up); !problem.empty()) {
    return reportUsage(console, problem);
  }
  if (o.validation && o.backend == "cpu" && !console.quiet) {
    console.err << "note: --validation checks Vulkan calls, and --backend cpu makes none\n";
  }
  Result<NetworkDescription> description = readNetworkDescription(o.network);
  if (!description.ok()) return reportError(console, "surface: " + description.status().message(), kExitFailure);
  if (!o.shape.empty()) std::fill(description->shapes.begin(), description->shapes.end(), shape);
  std::vector<std::string> warnings;
  Result<Network> network = Network::build(std::move(description).value(), &warnings);
  if (!network.ok()) {
    return reportError(console, "surface: " + o.network.string() + ": " + network.status().message(), kExitFailure);
  }
  if (!console.quiet) {
    for (const std::string& w : warnings) console.err << "warning: " << o.network.string() << ": " << w << "\n";
  }

  // Grid-size errors concern this network at this --res; device errors speak for themselves.
  const auto input_error = [&](const Status& s) {
    const bool about_input = s.code() == StatusCode::kOutOfRange || s.code() == StatusCode::kInvalidArgument;
    return reportError(console, "surface: " + (about_input ? o.network.string() + ": " : std::string()) + s.message(),
                       kExitFailure);
  };
  Result<TessellationGrid> grid = tessellationGrid(*network, resolution);
  if (!grid.ok()) return input_error(grid.status());
  if (Status fits = surfaceFitsInMemory(grid->vertexCount(), physicalMemoryBytes()); !fits.ok()) {
    return input_error(Status(fits.code(), "--res " + o.resolution + ": " + fits.message()));
  }

  SurfaceReport report;
  report.rows = network->rows();
  report.columns = network->columns();
  report.warnings = warnings.size();
  Result<SurfaceMesh> mesh = Status(internalError("surface: no backend ran"));
  std::string backend = o.backend;
  if (backend != "cpu") {
    mesh = tessellateOnGpu(o, *network, resolution, report.tessellate_seconds);
    // --backend auto: any Vulkan failure (no device, out of memory, device lost) means the CPU.
    const StatusCode code = mesh.ok() ? StatusCode::kOk : mesh.status().code();
    if (backend == "auto" && (code == StatusCode::kUnavailable || code == StatusCode::kDeviceError)) {
      if (!console.quiet) console.err << "note: Vulkan failed (" << mesh.status().message() << "); tessellating on the CPU\n";
      backend = "cpu";
    } else if (backend == "auto") {
      backend = "vulkan";
    }
  }
  if (backend == "cpu") {
    const auto start = std::chrono::steady_clock::now();
    // cppcheck-suppress redundantInitialization ; Result has no default constructor to leave it empty
    mesh = tessellateNetwork(*network, resolution);
    report.tessellate_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  report.backend = backend;
  if (!mesh.ok()) return input_error(mesh.status());
  // The network parsed and solved, but its numbers (a derivative of 1e-300, a point of 1e308) left
  // the surface beyond double precision: that is the network's fault, not the output file's.
  const auto bad = std::find_if(mesh->positions.begin(), mesh->positions.end(), [](const Vec3& p) { return !isFinite(p); });
  if (bad != mesh->positions.end()) {
    return input_error(outOfRange("the surface is not finite at vertex " + std::to_string(bad - mesh->positions.begin()) +
                                  ": a curve point or derivative is too large or too small for the solve"));
  }
  report.vertices = mesh->positions.size();
  report.triangles = 2 * mesh->faces.faceCount();
  report.rim_edges = unsharedEdges(mesh->faces).size();

  if (Status s = createParentFolder(o.output); !s.ok()) return reportError(console, "surface: " + s.message(), kExitFailure);
  std::filesystem::path obj;
  WrittenOutputs written;
  if (o.obj) {
    obj = objPath(o);
    if (Status s = writeObj(obj, mesh->positions, mesh->faces, "odeskin surface " + o.network.filename().string()); !s.ok()) {
      return reportError(console, "surface: " + s.message(), kExitFailure);
    }
    written.add(obj);
  }
  const std::vector<Vec3> normals = vertexNormals(*mesh);
  if (Status s = writeSurfaceGlb(o.output, *mesh, normals, up); !s.ok()) {
    written.removeAll();
    // A mesh the glTF cannot hold (float32's range) is this network's; write errors name the file.
    const bool about_input = s.code() == StatusCode::kInvalidArgument;
    return reportError(console, "surface: " + (about_input ? o.network.string() + ": " : std::string()) + s.message(),
                       kExitFailure);
  }
  if (!console.quiet) printSummary(console.out, o, *network, resolution, report, obj);
  if (report_out) *report_out = report;
  return kExitOk;
}

}  // namespace odeskin

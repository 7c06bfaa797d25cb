// SPDX-License-Identifier: MIT
#include "reconstruct_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/core/number_text.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/surfaces/mesh_network.hpp"
#include "engine/surfaces/mesh_network_deviation.hpp"
#include "engine/surfaces/mesh_network_pose.hpp"
#include "engine/surfaces/network_json.hpp"
#include "file_extension.hpp"
#include "output_paths.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

fs::path poseOutput(const fs::path& output, const fs::path& pose, const char* suffix) {
  return output.parent_path() / (output.stem().string() + "-" + pose.stem().string() + suffix + ".obj");
}

std::string usageProblem(const ReconstructCommandOptions& o, MeshNetworkOptions& m) {
  if (o.mesh.empty()) return "reconstruct: MESH.obj is required";
  for (const auto& [flag, path, extension] : {std::tuple{"-o", &o.output, ".obj"}, std::tuple{"--network", &o.network, ".json"},
                                             std::tuple{"--json", &o.json, ".json"}}) {
    if (!path->empty() && lowerExtension(*path) != extension) {
      return std::string("reconstruct: ") + flag + " " + path->string() + ": write " + extension;
    }
  }
  const auto count = [](const char* name, std::uint32_t value, std::uint32_t hi) -> std::string {
    if (value >= 1 && value <= hi) return {};
    return std::string("reconstruct: ") + name + " " + std::to_string(value) + " is outside [1, " + std::to_string(hi) + "]";
  };
  for (const std::string& problem : {count("--rows", o.rows, kMaxMeshNetworkPatches), count("--cols", o.columns, kMaxMeshNetworkPatches),
                                     count("--points", o.points, 1000)}) {
    if (!problem.empty()) return problem;
  }
  m.rows = o.rows;
  m.columns = o.columns;
  m.points_per_column = o.points;
  const std::optional<std::vector<double>> shape = finiteNumbersIn(o.shape, 3);
  if (!shape) return "reconstruct: --shape '" + o.shape + "': expected RHO,ETA,LAMBDA, three finite numbers";
  m.shape = {(*shape)[0], (*shape)[1], (*shape)[2]};
  const std::vector<double> values = finiteNumbersIn(o.derivative_fit, 3).value_or(std::vector<double>{});
  if (values.empty() || values[0] != std::floor(values[0]) || values[1] != std::floor(values[1]) ||
      values[0] < 1 || values[0] > 1000 || values[1] < 2 || values[1] > 8 || values[0] < values[1] || !(values[2] > 0.0) ||
      values[2] > 1.0) {
    return "reconstruct: --derivative-fit '" + o.derivative_fit +
           "': expected POINTS,DEGREE,WINDOW with 2 <= DEGREE <= 8, DEGREE <= POINTS <= 1000 and WINDOW in (0, 1]";
  }
  m.derivative_points = static_cast<std::uint32_t>(values[0]);
  m.derivative_degree = static_cast<std::uint32_t>(values[1]);
  m.derivative_window = values[2];
  if (meshNetworkSampleCount(m) > kMaxMeshNetworkSamples) {
    return "reconstruct: --rows " + std::to_string(o.rows) + " --cols " + std::to_string(o.columns) + " --points " +
           std::to_string(o.points) + " would read " + std::to_string(meshNetworkSampleCount(m)) +
           " mesh samples per pose, more than " + std::to_string(kMaxMeshNetworkSamples);
  }
  if (!(o.tear_ratio > 1.0) || !std::isfinite(o.tear_ratio)) {
    return "reconstruct: --tear-ratio " + numberText(o.tear_ratio) + " must be a finite number > 1";
  }
  std::vector<fs::path> input_files{o.mesh};
  input_files.insert(input_files.end(), o.poses.begin(), o.poses.end());
  std::set<fs::path> outputs;
  std::vector<fs::path> wanted{o.network, o.json};
  if (!o.output.empty()) {
    wanted.push_back(o.output);
    for (const fs::path& p : o.poses) {
      wanted.push_back(poseOutput(o.output, p, ""));
      wanted.push_back(poseOutput(o.output, p, "-reference"));
    }
  }
  for (const fs::path& p : wanted) {
    if (p.empty()) continue;
    if (overwritesInput(p, input_files)) return "reconstruct: " + p.string() + " is an input; it would be overwritten";
    if (!outputs.insert(p.lexically_normal()).second) {
      return "reconstruct: two outputs would be " + p.string() +
             (o.poses.empty() ? std::string() : " (poses with the same file name?)");
    }
  }
  return {};
}

Status checkSameMesh(const fs::path& pose_file, const ObjMesh& pose, const fs::path& mesh_file, const ObjMesh& mesh) {
  if (pose.positions.size() != mesh.positions.size()) {
    return invalidArgument(pose_file.string() + ": " + std::to_string(pose.positions.size()) + " vertices, " +
                           mesh_file.string() + " has " + std::to_string(mesh.positions.size()) + ": not a pose of the same mesh");
  }
  if (pose.faces.face_offsets != mesh.faces.face_offsets || pose.faces.indices != mesh.faces.indices) {
    std::size_t f = 0;
    while (f < std::min(pose.faces.faceCount(), mesh.faces.faceCount()) &&
           std::equal(pose.faces.indices.begin() + pose.faces.face_offsets[f], pose.faces.indices.begin() + pose.faces.face_offsets[f + 1],
                      mesh.faces.indices.begin() + mesh.faces.face_offsets[f], mesh.faces.indices.begin() + mesh.faces.face_offsets[f + 1])) {
      ++f;
    }
    return invalidArgument(pose_file.string() + ": face " + std::to_string(f + 1) + " differs from " + mesh_file.string() +
                           "'s: not a pose of the same mesh");
  }
  return okStatus();
}

// One pose: the flags, the network read on it, the reconstruction and its figures.
Result<ReconstructPoseReport> reconstructPose(const MeshNetwork& m, const ObjMesh& mesh, const fs::path& file,
                                              const std::vector<Vec3>& positions, double tear_ratio,
                                              std::vector<Vec3>& reconstruction, std::vector<Vec3>& filled) {
  ReconstructPoseReport r;
  r.file = file;
  const auto start = Clock::now();
  ODESKIN_ASSIGN_OR_RETURN(PoseFlags flags, flagVertices(mesh.positions, positions, mesh.faces, tear_ratio));
  ODESKIN_ASSIGN_OR_RETURN(filled, fillFlagged(mesh.positions, positions, mesh.faces, flags.flagged));
  ODESKIN_ASSIGN_OR_RETURN(Network network, m.build(filled));
  reconstruction = m.reconstruct(network);
  r.reconstruct_seconds = secondsSince(start);
  const auto measure = Clock::now();
  const MeshDeviation d = measureDeviation(network, m.vertexParameters(), positions, flags.flagged);
  r.measure_seconds = secondsSince(measure);
  r.flagged_vertices = flags.flagged_vertices;
  r.stretched_edges = flags.stretched_edges;
  r.max_stretch = flags.max_stretch;
  r.measured_vertices = d.measured;
  r.box = d.box;
  r.mean = d.mean_parametric;
  r.max = d.max_parametric;
  r.mean_surface = d.mean_surface;
  r.max_surface = d.max_surface;
  r.worst_vertex = d.worst_vertex;
  r.flagged_max = d.excluded_max_parametric;
  return r;
}

Json reportJson(const ReconstructCommandOptions& o, const MeshNetworkOptions& m, const ReconstructReport& r) {
  Json poses = Json::array();
  for (const ReconstructPoseReport& p : r.poses) {
    poses.push_back({{"file", p.file.string()},
                     {"flagged_vertices", p.flagged_vertices},
                     {"stretched_edges", p.stretched_edges},
                     {"max_stretch", p.max_stretch},
                     {"measured_vertices", p.measured_vertices},
                     {"box", p.box},
                     {"mean", p.mean},
                     {"max", p.max},
                     {"mean_surface", p.mean_surface},
                     {"max_surface", p.max_surface},
                     {"worst_vertex", p.worst_vertex + 1},
                     {"flagged_max", p.flagged_max},
                     {"reconstruct_seconds", p.reconstruct_seconds},
                     {"measure_seconds", p.measure_seconds},
                     {"output", p.written.string()},
                     {"reference", p.reference.string()}});
  }
  return {{"mesh", o.mesh.string()},
          {"vertices", r.vertices},
          {"triangles", r.triangles},
          {"rim_vertices", r.rim_vertices},
          {"rim_length", r.rim_length},
          {"holes", r.holes},
          {"rows", m.rows},
          {"columns", m.columns},
          {"points_per_column", m.points_per_column},
          {"curve_points", r.curve_points},
          {"boundaries", m.rows + 1},
          {"stored_points", r.stored_points},
          {"stored_floats", 3 * r.stored_points},
          {"mesh_floats", 3 * r.vertices},
          {"size_reduction", r.size_reduction},
          {"shape", {{"rho", m.shape.rho}, {"eta", m.shape.eta}, {"lambda", m.shape.lambda}}},
          {"derivative_fit", {{"points", m.derivative_points}, {"degree", m.derivative_degree}, {"window", m.derivative_window}}},
          {"tear_ratio", o.tear_ratio},
          {"extract_seconds", r.extract_seconds},
          {"units", "mean, max, mean_surface, max_surface, flagged_max: fractions of box, the longest side of the measured "
                    "vertices' bounding box; flagged vertices are left out of them"},
          {"poses", poses}};
}

// An OBJ to write: a reconstruction or a filled reference, with the mesh's faces.
struct ObjOutput {
  fs::path path;
  std::vector<Vec3> positions;
};

// Every output, atomically each; on a failure the files already written are removed again.
Status writeOutputs(const ReconstructCommandOptions& o, const MeshNetworkOptions& options, const MeshNetwork& m,
                    const ObjMesh& mesh, const std::vector<ObjOutput>& objs, const ReconstructReport& report) {
  WrittenOutputs written;
  for (const fs::path& p : {o.output, o.network, o.json}) ODESKIN_TRY(createParentFolder(p));
  for (const ObjOutput& obj : objs) {
    if (Status s = writeObj(obj.path, obj.positions, mesh.faces, "odeskin reconstruct " + o.mesh.filename().string()); !s.ok()) {
      return written.undo(s);
    }
    written.add(obj.path);
  }
  if (!o.network.empty()) {
    Result<NetworkDescription> description = m.describe(mesh.positions);
    if (!description.ok()) {
      return written.undo(Status(description.status().code(), o.mesh.string() + ": " + description.status().message()));
    }
    if (Status s = writeFileAtomically(o.network, networkJson(*description)); !s.ok()) return written.undo(s);
    written.add(o.network);
  }
  if (!o.json.empty()) {
    if (Status s = writeFileAtomically(o.json, reportJson(o, options, report).dump(2) + "\n"); !s.ok()) return written.undo(s);
  }
  return okStatus();
}

void printSummary(std::ostream& out, const ReconstructCommandOptions& o, const MeshNetwork& m, const ReconstructReport& r) {
  const MeshNetworkOptions& n = m.options();
  out << "reconstruct " << o.mesh.filename().string() << ": " << r.vertices << " vertices, " << r.triangles
      << " triangles; rim of " << r.rim_vertices << " vertices on the unit square";
  if (!r.holes.empty()) {
    std::size_t filled = 0;
    for (std::size_t h : r.holes) filled += h;
    out << ", " << r.holes.size() << " hole" << (r.holes.size() == 1 ? "" : "s") << " filled (" << filled << " rim vertices)";
  }
  out << "\nnetwork: " << n.rows << " x " << n.columns << " patches (rho " << numberText(n.shape.rho) << ", eta "
      << numberText(n.shape.eta) << ", lambda " << numberText(n.shape.lambda) << "), " << n.rows + 1 << " boundaries x 3 curves x "
      << r.curve_points << " points = " << r.stored_points << " points\n";
  char line[256];
  std::snprintf(line, sizeof line, "size: %zu floats against %zu for the vertices: %.1fx smaller\n", 3 * r.stored_points,
                3 * r.vertices, r.size_reduction);
  out << line;
  std::snprintf(line, sizeof line, "extracted in %.2f s (parameterisation and %zu mesh samples)\n", r.extract_seconds,
                m.meshSamples());
  out << line;
  out << "pose                      flagged    mean      max   surface mean  surface max   rebuilt in\n";
  for (const ReconstructPoseReport& p : r.poses) {
    std::snprintf(line, sizeof line, "%-24s %8zu %7.3f%% %7.3f%%       %7.3f%%     %7.3f%%   %7.1f ms\n",
                  p.file.filename().string().c_str(), p.flagged_vertices, 100.0 * p.mean, 100.0 * p.max,
                  100.0 * p.mean_surface, 100.0 * p.max_surface, 1e3 * p.reconstruct_seconds);
    out << line;
  }
  if (r.rim_length < 0.5 * r.poses.front().box) {
    out << "note: the rim is short against the mesh (" << numberText(r.rim_length) << " against a box side of "
        << numberText(r.poses.front().box)
        << "): a nearly closed surface spreads badly over a square, so expect large deviations\n";
  }
  out << "deviation: % of the longest side of each pose's box, vertex to S at its (u, v) and to the surface; flagged: "
         "vertices on edges stretched more than "
      << numberText(o.tear_ratio) << "x against " << o.mesh.filename().string()
      << ", left out of the figures, their positions filled in from their neighbours for the curve samples\n";
}

// Defaults on the data's faces stay within 7% of the box; a surface that misses by much more is not
// a reconstruction, and the table alone is easy to read past.
constexpr double kFarDeviation = 0.2;

void warnOfLargeDeviations(std::ostream& err, const MeshNetworkOptions& n, const ReconstructReport& r) {
  for (const ReconstructPoseReport& p : r.poses) {
    if (!(p.max > kFarDeviation)) continue;
    err << "warning: " << p.file.string() << ": the rebuilt surface misses vertex " << p.worst_vertex + 1 << " by "
        << percentText(p.max) << " of the box";
    if (n.derivative_window < finiteNumbersIn(kDefaultDerivativeFit, 3)->back()) {
      err << "; a --derivative-fit window of " << numberText(n.derivative_window)
          << " row heights turns the mesh's facets into large S_uu (the default is " << kDefaultDerivativeFit << ")\n";
    } else {
      err << "; the network does not follow this mesh (one sheet with one rim, such as a face, suits it)\n";
    }
  }
}

}  // namespace

int runReconstructCommand(const ReconstructCommandOptions& o, Console& console, ReconstructReport* report_out) {
  MeshNetworkOptions options;
  if (const std::string problem = usageProblem(o, options); !problem.empty()) return reportUsage(console, problem);
  if (Result<Ode6Cardinal> cardinal = Ode6Cardinal::create(options.shape); !cardinal.ok()) {
    return reportError(console, "reconstruct: --shape " + o.shape + ": " + cardinal.status().message(), kExitFailure);
  }
  Result<ObjMesh> mesh = readObj(o.mesh);
  if (!mesh.ok()) return reportError(console, "reconstruct: " + mesh.status().message(), kExitFailure);
  std::vector<ObjMesh> poses;
  for (const fs::path& file : o.poses) {
    Result<ObjMesh> pose = readObj(file);
    if (!pose.ok()) return reportError(console, "reconstruct: " + pose.status().message(), kExitFailure);
    if (Status s = checkSameMesh(file, *pose, o.mesh, *mesh); !s.ok()) return reportError(console, "reconstruct: " + s.message(), kExitFailure);
    poses.push_back(std::move(pose).value());
  }

  ReconstructReport report;
  const auto start = Clock::now();
  Result<MeshNetwork> m = MeshNetwork::extract(mesh->positions, mesh->faces, options);
  report.extract_seconds = secondsSince(start);
  if (!m.ok()) return reportError(console, "reconstruct: " + o.mesh.string() + ": " + m.status().message(), kExitFailure);
  report.vertices = mesh->positions.size();
  for (std::size_t f = 0; f < mesh->faces.faceCount(); ++f) report.triangles += mesh->faces.face_offsets[f + 1] - mesh->faces.face_offsets[f] - 2;
  report.rim_vertices = m->disk().rim.size();
  for (std::size_t k = 0; k < m->disk().rim.size(); ++k) {
    report.rim_length += glm::distance(mesh->positions[m->disk().rim[k]], mesh->positions[m->disk().rim[(k + 1) % m->disk().rim.size()]]);
  }
  for (const auto& hole : m->disk().holes) report.holes.push_back(hole.size());
  report.curve_points = m->curvePoints();
  report.stored_points = m->storedPoints();
  report.size_reduction = static_cast<double>(report.vertices) / static_cast<double>(report.stored_points);

  // Everything is computed before anything is written, so a failure leaves no file behind.
  std::vector<ObjOutput> objs;
  for (std::size_t k = 0; k <= poses.size(); ++k) {
    const fs::path& file = k == 0 ? o.mesh : o.poses[k - 1];
    const std::vector<Vec3>& positions = k == 0 ? mesh->positions : poses[k - 1].positions;
    std::vector<Vec3> reconstruction, filled;
    Result<ReconstructPoseReport> pose = reconstructPose(*m, *mesh, file, positions, o.tear_ratio, reconstruction, filled);
    if (!pose.ok()) return reportError(console, "reconstruct: " + file.string() + ": " + pose.status().message(), kExitFailure);
    if (!o.output.empty()) {
      pose->written = k == 0 ? o.output : poseOutput(o.output, file, "");
      objs.push_back({pose->written, std::move(reconstruction)});
      if (pose->flagged_vertices > 0) {
        pose->reference = poseOutput(o.output, file, "-reference");
        objs.push_back({pose->reference, std::move(filled)});
      }
    }
    report.poses.push_back(std::move(pose).value());
  }

  if (Status s = writeOutputs(o, options, *m, *mesh, objs, report); !s.ok()) {
    return reportError(console, "reconstruct: " + s.message(), kExitFailure);
  }
  if (!console.quiet) {
    printSummary(console.out, o, *m, report);
    warnOfLargeDeviations(console.err, options, report);
  }
  if (report_out) *report_out = std::move(report);
  return kExitOk;
}

}  // namespace odeskin

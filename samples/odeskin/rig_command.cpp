// SPDX-License-Identifier: MIT
#include "rig_command.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>
#include <vector>

#include <glm/geometric.hpp>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "engine/core/number_text.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/io/gltf_rig_writer.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/libigl_writer.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/mesh/poly_mesh.hpp"
#include "engine/rig/curve_rig.hpp"
#include "engine/rig/skeleton_compare.hpp"
#include "file_extension.hpp"
#include "material_warning.hpp"
#include "output_paths.hpp"
#include "rig_picture.hpp"
#include "up_axis.hpp"

namespace odeskin {
namespace {

// glibc raises its mmap threshold to the largest block freed so far, so whether a repeat's
// buffers are reused or mapped afresh (and page-faulted again) depended on what other code had
// happened to allocate and free: a smaller reserve in skeleton creation made the horse's mesh
// edges time 1.5 ms in one build and 2.8 ms in the next. Fixed thresholds keep every repeat's
// buffers in the heap, so the stage times measure the rig and not the allocator's history.
// mallopt is not thread-safe: this runs first in the command, before anything starts a thread.
void keepRepeatBuffersInHeap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // NOLINT(concurrency-mt-unsafe): no other thread yet; glibc's largest value on 64-bit
  mallopt(M_TRIM_THRESHOLD, 64 << 20);  // NOLINT(concurrency-mt-unsafe): as above
#endif
}

std::optional<CurveSource> curveSource(const std::string& name) {
  if (name == "auto") return CurveSource::kAuto;
  if (name == "levels") return CurveSource::kLevels;
  if (name == "cuts") return CurveSource::kPlaneCuts;
  if (name == "loops") return CurveSource::kEdgeLoops;
  return std::nullopt;
}

const char* curveSourceName(CurveSource source) {
  switch (source) {
    case CurveSource::kLevels:
      return "geodesic rings";
    case CurveSource::kPlaneCuts:
      return "plane cuts";
    case CurveSource::kEdgeLoops:
      return "quad edge loops";
    case CurveSource::kAuto:
      break;
  }
  return "auto";
}

std::string usageProblem(const RigCommandOptions& o) {
  if (o.meshes.empty()) return "rig: give the mesh (an OBJ file), optionally followed by example poses, or one .gltf/.glb";
  const bool gltf = std::any_of(o.meshes.begin(), o.meshes.end(), isGltfFile);
  if (gltf && o.meshes.size() > 1) return "rig: give one .gltf/.glb file (--times or --targets for poses), or OBJ meshes, not both";
  for (const std::filesystem::path& m : o.meshes) {
    if (!gltf && lowerExtension(m) != ".obj") {
      return "rig: " + m.string() + ": unknown mesh format '" + lowerExtension(m) + "' (expected .obj, .gltf or .glb)";
    }
  }
  if (!gltf && (!o.mesh.empty() || !o.animation.empty() || !o.times.empty() || !o.targets.empty())) {
    return "rig: --mesh, --animation, --times and --targets apply to a .gltf/.glb input";
  }
  if (!o.animation.empty() && o.times.empty()) return "rig: --animation applies with --times";
  if (o.output.empty()) return "rig: -o SKELETON.tgf is required";
  if (lowerExtension(o.output) != ".tgf") return "rig: -o " + o.output.string() + ": the skeleton is written as a .tgf file";
  if (!o.weights.empty() && lowerExtension(o.weights) != ".dmat") {
    return "rig: --weights " + o.weights.string() + ": the weights are written as a .dmat file";
  }
  if (!o.gltf.empty() && lowerExtension(o.gltf) != ".glb") return "rig: --gltf " + o.gltf.string() + ": must be a .glb file";
  if (!o.png.empty() && lowerExtension(o.png) != ".png") return "rig: --png " + o.png.string() + ": must be a .png file";
  if (!o.compare.empty() && lowerExtension(o.compare) != ".tgf") {
    return "rig: --compare " + o.compare.string() + ": give the ground-truth skeleton as a .tgf file";
  }
  std::vector<std::filesystem::path> inputs = o.meshes;
  inputs.push_back(o.compare);
  const std::filesystem::path outputs[] = {o.output, o.weights, o.gltf, o.png};
  for (std::size_t i = 0; i < std::size(outputs); ++i) {
    const std::filesystem::path& out = outputs[i];
    if (overwritesInput(out, inputs)) return "rig: " + out.string() + " is an input; it would be overwritten";
    if (const std::string why = folderNotFile(out); !why.empty()) return "rig: " + out.string() + " " + why;
    for (std::size_t j = 0; j < i; ++j) {
      if (sameOutputFile(outputs[j], out)) {
        return "rig: " + outputs[j].string() + " and " + out.string() + " name the same file; give each output its own";
      }
    }
  }
  if (!o.png.empty() && !std::isfinite(o.azimuth_deg)) {
    return "rig: --azimuth must be a finite number of degrees, got " + numberText(o.azimuth_deg);
  }
  if (!parseTemplateKind(o.template_kind)) {
    return "rig: --template " + o.template_kind + ": use auto, humanoid, quadruped or none";
  }
  if (!curveSource(o.curves)) return "rig: --curves " + o.curves + ": use auto, levels, cuts or loops";
  if (!(o.angle_deg > 0.0 && o.angle_deg < 180.0)) return "rig: --angle must lie in (0, 180) degrees";
  // Each run keeps its stage times for the medians: 1e8 runs held 7 GB of them (and days of work).
  if (o.repeat < 1 || o.repeat > kMaxRigRepeats) {
    return "rig: --repeat must lie in [1, " + std::to_string(kMaxRigRepeats) + "], got " + std::to_string(o.repeat);
  }
  if (Result<Vec3> up = parseUpAxis(o.up); !up.ok()) return "rig: " + up.status().message();
  return {};
}

// The bind mesh and the example poses, with a glTF input's look for --gltf.
struct RigInput {
  std::vector<Vec3> rest;
  FaceList faces;
  std::vector<std::vector<Vec3>> poses;
  RenderLayout render;                  // the input's render vertices (glTF, or an OBJ with vt/vn), or empty
  std::vector<std::string> warnings;    // the readers', naming the file
  std::size_t replaced_skin_joints = 0; // the joints of a skin the input already had
};

Result<RigInput> readRigInput(const RigCommandOptions& o) {
  RigInput in;
  if (isGltfFile(o.meshes.front())) {
    GltfPoseRequest request;
    request.mesh = o.mesh;
    request.animation = o.animation;
    request.times = o.times;
    request.morph_targets = o.targets;
    request.min_poses = 1;
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet set, readGltfExamples(o.meshes.front(), request));
    // The check fit makes of the same file (a mesh drawn twice by two primitives is not manifold).
    ODESKIN_TRY(buildPolyMesh(set.rest_positions, set.faces, o.meshes.front().string()).status());
    in.rest = std::move(set.rest_positions);
    in.faces = std::move(set.faces);
    in.poses.assign(std::make_move_iterator(set.poses.begin() + 1), std::make_move_iterator(set.poses.end()));
    in.render = std::move(set.render);
    in.warnings = std::move(set.warnings);
    if (set.rig) in.replaced_skin_joints = set.rig->skeleton.boneCount();
  } else if (o.meshes.size() == 1) {
    ODESKIN_ASSIGN_OR_RETURN(ObjMesh mesh, readObj(o.meshes.front()));
    // The manifold check a sequence's reader makes: the curves and levels assume manifold faces.
    ODESKIN_TRY(buildPolyMesh(mesh.positions, mesh.faces, o.meshes.front().string()).status());
    in.render = objRenderLayout(mesh);
    in.warnings = objLayoutWarnings(mesh);
    in.rest = std::move(mesh.positions);
    in.faces = std::move(mesh.faces);
  } else {
    // Same topology in every pose, checked by the sequence reader.
    ODESKIN_ASSIGN_OR_RETURN(ExampleSet set, readObjSequence(o.meshes));
    in.rest = set.rest_positions;
    in.faces = std::move(set.faces);
    in.render = std::move(set.render);
    in.warnings = std::move(set.warnings);
    in.poses.assign(std::make_move_iterator(set.poses.begin() + 1), std::make_move_iterator(set.poses.end()));
  }
  return in;
}

// The materials a glTF input's primitives use, for --gltf; none when they use none.
Result<std::optional<gltf::MaterialLibrary>> inputMaterials(const RigCommandOptions& o, const RenderLayout& render,
                                                            std::size_t& untextured) {
  const bool dressed = std::any_of(render.primitives.begin(), render.primitives.end(),
                                   [](const RenderPrimitive& p) { return p.material >= 0; });
  if (!dressed) return std::optional<gltf::MaterialLibrary>();
  ODESKIN_ASSIGN_OR_RETURN(gltf::MaterialLibrary library, gltf::readMaterialLibrary(o.meshes.front()));
  // A TEXCOORD_0 the reader could not keep (on some primitives only) leaves the textures unmappable.
  if (render.uvs.empty()) untextured = gltf::dropTextures(library);
  return std::optional<gltf::MaterialLibrary>(std::move(library));
}

double fastest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end()); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int runRigCommand(const RigCommandOptions& o, Console& console) {
  if (const std::string problem = usageProblem(o); !problem.empty()) return reportUsage(console, problem);
  if (o.repeat > 1) keepRepeatBuffersInHeap();

  Result<RigInput> input = readRigInput(o);
  if (!input.ok()) return reportFailure(console, Status(input.status().code(), "rig: " + input.status().message()));
  if (!console.quiet) {
    for (const std::string& w : input->warnings) console.err << "warning: rig: " << w << "\n";
  }
  // Read before anything is written: a texture --gltf cannot copy fails the command, not its last output.
  Result<std::optional<gltf::MaterialLibrary>> materials = std::optional<gltf::MaterialLibrary>();
  std::size_t untextured = 0;
  if (!o.gltf.empty()) materials = inputMaterials(o, input->render, untextured);
  if (!materials.ok()) {
    return reportFailure(console, Status(materials.status().code(), "rig: --gltf: " + materials.status().message()));
  }
  if (!console.quiet) warnOfDroppedTextures(console.err, o.meshes.front(), o.meshes.front(), untextured);
  const std::vector<Vec3>& rest = input->rest;
  const FaceList& faces = input->faces;
  const std::vector<std::vector<Vec3>>& poses = input->poses;

  std::optional<Skeleton> truth;
  if (!o.compare.empty()) {
    Result<Skeleton> read = readTgf(o.compare);
    if (!read.ok()) return reportFailure(console, Status(read.status().code(), "rig: --compare: " + read.status().message()));
    truth = std::move(*read);
  }

  CurveRigOptions options;
  options.curves.source = *curveSource(o.curves);
  options.animation.angle_threshold_deg = o.angle_deg;
  options.animation.template_kind = *parseTemplateKind(o.template_kind);
  options.animation.up = *parseUpAxis(o.up);
  options.compute_weights = !o.weights.empty() || !o.gltf.empty();
  std::vector<double> topology_s, curves_s, skeleton_s, weights_s;
  std::vector<double> centre_s, edge_distance_s, coarse_s, marching_s, fine_s, loops_s;  // vertex identification's stages
  Result<CurveRig> rig = invalidArgument("rig: not run");
  for (int run = 0; run < o.repeat; ++run) {
    rig = buildCurveRig(rest, faces, poses, options);
    if (!rig.ok()) {
      // The curve rig's errors are about the meshes' content: name the bind mesh (and poses).
      const std::string meshes =
          o.meshes.front().string() + (poses.empty() ? "" : " and " + std::to_string(poses.size()) + " poses");
      return reportFailure(console, Status(rig.status().code(), "rig: " + meshes + ": " + rig.status().message()));
    }
    topology_s.push_back(rig->seconds_topology);
    curves_s.push_back(rig->seconds_curves);
    skeleton_s.push_back(rig->seconds_skeleton);
    weights_s.push_back(rig->seconds_weights);
    centre_s.push_back(rig->curve_skeleton.seconds_centre);
    edge_distance_s.push_back(rig->curve_skeleton.seconds_edge_distance);
    coarse_s.push_back(rig->curve_skeleton.seconds_coarse_levels);
    marching_s.push_back(rig->curve_skeleton.seconds_marching);
    fine_s.push_back(rig->curve_skeleton.seconds_fine_levels);
    loops_s.push_back(rig->curve_skeleton.seconds_edge_loops);
  }
  const CurveRig& r = *rig;

  for (const std::filesystem::path* file : {&o.output, &o.weights, &o.gltf, &o.png}) {
    const std::filesystem::path parent = file->parent_path();
    if (file->empty() || parent.empty()) continue;
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) return reportFailure(console, ioError("rig: " + parent.string() + ": cannot create directory: " + ec.message()));
  }
  // The picture first: it needs a Vulkan device, the likeliest thing to be missing, and a
  // failure then replaces none of the other outputs.
  if (!o.png.empty()) {
    RigPictureOptions picture;
    picture.up = *parseUpAxis(o.up);
    picture.device = o.device;
    picture.azimuth_deg = o.azimuth_deg;
    picture.title = o.meshes.front().filename().string();
    picture.truth = truth ? &*truth : nullptr;
    Status s = drawRigPicture(o.png, rest, faces, r.curve_skeleton.curves, r.curve_skeleton.skeleton, r.animation, picture);
    if (!s.ok()) return reportFailure(console, Status(s.code(), "rig: --png: " + s.message()));
  }
  WrittenOutputs written;
  if (!o.png.empty()) written.add(o.png);
  if (Status s = writeTgf(o.output, r.rig.skeleton); !s.ok()) return reportFailure(console, written.undo(s));
  written.add(o.output);
  if (!o.weights.empty()) {
    if (Status s = writeWeightsDmat(o.weights, r.rig.influences, r.rig.skeleton.boneCount()); !s.ok()) {
      return reportFailure(console, written.undo(s));
    }
    written.add(o.weights);
  }
  if (!o.gltf.empty()) {
    RigGlbLook look;
    look.render = &input->render;
    look.materials = *materials ? &**materials : nullptr;
    if (Status s = writeRigGlb(o.gltf, rest, faces, r.rig, look); !s.ok()) return reportFailure(console, written.undo(s));
  }
  if (console.quiet) return kExitOk;

  std::ostream& out = console.out;
  const CurveSkeletonResult& cs = r.curve_skeleton;
  char line[256];
  std::snprintf(line, sizeof line, "mesh: %zu vertices, %zu faces, %zu example pose%s\n", rest.size(), faces.faceCount(),
                poses.size(), poses.size() == 1 ? "" : "s");
  out << line;
  if (!input->render.empty()) {
    out << (input->render.obj_order ? "OBJ: " : "glTF: ") << input->render.topology_of_render.size()
        << " render vertices welded into " << rest.size()
        << ", " << std::max<std::size_t>(input->render.primitives.size(), 1) << " primitive"
        << (input->render.primitives.size() > 1 ? "s" : "");
    if (input->replaced_skin_joints > 0) out << "; its skin of " << input->replaced_skin_joints << " joints is not used";
    out << "\n";
  }
  std::snprintf(line, sizeof line, "curves: %zu (%s), %zu body parts, %zu bumps pruned; curve skeleton: %zu nodes\n",
                cs.curves.size(), curveSourceName(cs.source), cs.part_count,
                cs.pruned_branches, cs.skeleton.nodeCount());
  out << line;
  if (cs.source == CurveSource::kEdgeLoops) {
    std::snprintf(line, sizeof line,
                  "ray-and-fan: %zu circumferential, %zu axial, %zu undecided edges; %zu rings, %zu lines along the limbs\n",
                  cs.circumferential_edges, cs.axial_edges, cs.unknown_edges, cs.edge_loop_rings, cs.axial_lines);
    out << line;
  }
  if (!cs.note.empty()) out << "note: " << cs.note << "\n";
  if (cs.unreached_vertices > 0) {
    out << "note: " << cs.unreached_vertices << " vertices lie in other connected components than the largest; "
        << "they get weights but no bones of their own\n";
  }
  std::size_t by_reason[6] = {0, 0, 0, 0, 0, 0};
  for (const JointReason reason : r.animation.reasons) ++by_reason[static_cast<std::size_t>(reason)];
  out << "skeleton: " << r.rig.skeleton.boneCount() << " bones, " << r.animation.jointCount() << " joints (";
  for (std::size_t k = 0; k < 6; ++k) {
    out << (k > 0 ? ", " : "") << by_reason[k] << " " << reasonName(static_cast<JointReason>(k));
  }
  out << "); template " << templateKindName(r.animation.used);
  if (!r.animation.template_note.empty()) out << ": " << r.animation.template_note;
  out << "\n";
  if (o.repeat > 1) {
    std::snprintf(line, sizeof line,
                  "time (median / fastest of %d runs): mesh edges %.3f / %.3f ms, curve (vertex) identification %.3f / "
                  "%.3f ms, skeleton creation %.3f / %.3f ms, weights %.3f / %.3f ms\n",
                  o.repeat, 1e3 * median(topology_s), 1e3 * fastest(topology_s), 1e3 * median(curves_s),
                  1e3 * fastest(curves_s), 1e3 * median(skeleton_s), 1e3 * fastest(skeleton_s), 1e3 * median(weights_s),
                  1e3 * fastest(weights_s));
    out << line;
    std::snprintf(line, sizeof line,
                  "identification stages (median / fastest): centre section %.3f / %.3f ms, edge distances %.3f / %.3f ms, "
                  "coarse levels %.3f / %.3f ms, fast marching %.3f / %.3f ms, fine levels %.3f / %.3f ms\n",
                  1e3 * median(centre_s), 1e3 * fastest(centre_s), 1e3 * median(edge_distance_s), 1e3 * fastest(edge_distance_s), 1e3 * median(coarse_s), 1e3 * fastest(coarse_s),
                  1e3 * median(marching_s), 1e3 * fastest(marching_s), 1e3 * median(fine_s), 1e3 * fastest(fine_s));
    out << line;
    if (r.curve_skeleton.source == CurveSource::kEdgeLoops) {
      std::snprintf(line, sizeof line, "edge loops (half-edge mesh, ray-and-fan test, loop walk): %.3f / %.3f ms\n",
                    1e3 * median(loops_s), 1e3 * fastest(loops_s));
    } else {
      line[0] = '\0';
    }
  } else {
    std::snprintf(line, sizeof line,
                  "time: mesh edges %.3f ms, curve (vertex) identification %.3f ms, skeleton creation %.3f ms, weights "
                  "%.3f ms\n",
                  1e3 * topology_s[0], 1e3 * curves_s[0], 1e3 * skeleton_s[0], 1e3 * weights_s[0]);
  }
  out << line;
  if (truth) {
    Vec3 lo(1e300), hi(-1e300);
    for (const Vec3& p : rest) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const SkeletonComparison c = compareSkeletons(*truth, r.rig.skeleton, glm::length(hi - lo));
    std::snprintf(line, sizeof line,
                  "compare: %zu bones vs %zu in %s; joints: truth -> nearest ours mean %.2f%% max %.2f%%, ours -> nearest "
                  "truth mean %.2f%% max %.2f%% of the box diagonal\n",
                  c.bones, c.truth_bones, o.compare.filename().string().c_str(), 100.0 * c.truth_to_ours_mean,
                  100.0 * c.truth_to_ours_max, 100.0 * c.ours_to_truth_mean, 100.0 * c.ours_to_truth_max);
    out << line;
  }
  out << "wrote " << o.output.string();
  if (!o.weights.empty()) out << ", " << o.weights.string();
  if (!o.gltf.empty()) out << ", " << o.gltf.string();
  if (!o.png.empty()) out << ", " << o.png.string();
  out << "\n";
  return kExitOk;
}

}  // namespace odeskin

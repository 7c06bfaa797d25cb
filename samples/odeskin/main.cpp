// SPDX-License-Identifier: MIT
// The odeskin command line: CLI11 wiring only; each verb lives in its own file. Exit status: 0
// success; 1 bad input or runtime failure, with one line "odeskin: error: ..." on stderr; 2 usage error.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "asset_info.hpp"
#include "bench_command.hpp"
#include "blend_command.hpp"
#include "demo.hpp"
#include "engine/offline/fourier_fit.hpp"
#include "evaluate_command.hpp"
#include "export_command.hpp"
#include "fit_command.hpp"
#include "host/device_info.hpp"
#include "play_command.hpp"
#include "progress.hpp"
#include "reconstruct_command.hpp"
#include "compare_command.hpp"
#include "render_command.hpp"
#include "surface_command.hpp"
#include "rig_command.hpp"
#include "samples/decimal_integers.hpp"
#include "samples/standard_output.hpp"
#include "signal_cleanup.hpp"

namespace {

constexpr double kDemoEndTolerance = 1e-5;  // frame 0 / last frame vs start.obj / end.obj, of the box

// The --backend names; CLI11 has already checked the name against the same list.
odeskin::Backend backendNamed(const std::string& name) {
  if (name == "cpu") return odeskin::Backend::kCpu;
  if (name == "vulkan") return odeskin::Backend::kVulkan;
  return odeskin::Backend::kAuto;
}

int fail(const odeskin::Status& status) {
  std::cerr << "odeskin: error: " << status.message() << "\n";
  return 1;
}

int runDemoCommand(const odeskin::DemoOptions& options, bool quiet) {
  std::ostringstream discarded;  // --quiet: the summary goes nowhere, the check still decides the exit
  odeskin::Result<odeskin::DemoResult> result = odeskin::runDemo(options, quiet ? discarded : std::cout);
  if (!result.ok()) return fail(odeskin::Status(result.status().code(), "demo: " + result.status().message()));
  const odeskin::DemoResult& r = *result;
  if (!quiet) {
    std::printf("frames: %zu written to %s\n", r.frames.size(), options.output_dir.string().c_str());
    std::printf("per-frame time: %.3f ms wall", 1e3 * r.mean_frame_seconds);
    if (r.mean_gpu_seconds > 0.0) std::printf(", %.3f ms GPU (timestamp queries)", 1e3 * r.mean_gpu_seconds);
    std::printf("\ncheck: frame 0 vs start.obj %.2e, last frame vs end.obj %.2e (of the box, limit %.0e)\n",
                r.first_frame_error, r.last_frame_error, kDemoEndTolerance);
  }
  if (r.first_frame_error > kDemoEndTolerance || r.last_frame_error > kDemoEndTolerance) {
    return fail(odeskin::internalError("the played frames do not reproduce the example poses"));
  }
  return 0;
}

CLI::App* addFitCommand(CLI::App& app, odeskin::FitCommandOptions& o, std::string& residual, std::string& skinning) {
  CLI::App* fit = app.add_subcommand("fit", "Fit a deformer to example poses and save it as a .odsk asset");
  fit->footer(
      "Inputs: OBJ poses of one mesh (optionally --bind REST.obj), one .gltf/.glb with --times or --targets,\n"
      "or OBJ poses with a libigl rig (--rig SKELETON.tgf --bind REST.obj [--weights W.dmat] [--transforms ...]).\n"
      "Example: odeskin fit horse-01.obj horse-03.obj horse-05.obj -o horse.odsk --terms 9 --timings");
  fit->add_option("poses", o.inputs, "Example poses: OBJ files, or one .gltf/.glb")->required();
  fit->add_option("-o,--output", o.output, "The .odsk asset to write")->required();
  fit->add_option("--rig", o.rig,
                  "auto (derive bones from the poses' motion), curves (from the bind mesh's iso-curves, `odeskin rig`)\n"
                  "or a libigl .tgf skeleton; default: the input's rig, else auto");
  fit->add_option("--bind", o.bind, "Rest mesh (.obj) of the OBJ poses; default: the first pose");
  fit->add_option("--weights", o.weights, "Skinning weights (.dmat) for --rig SKELETON.tgf");
  fit->add_option("--transforms", o.transforms, "One .Tmat per pose for --rig SKELETON.tgf")->delimiter(',');
  fit->add_option("--mesh", o.mesh, "glTF: the mesh node (default: the first skinned mesh)");
  fit->add_option("--animation", o.animation, "glTF: animation name or index (default: the first)");
  fit->add_option("--times", o.times, "glTF: animation times in seconds, one example pose each after the bind mesh (pose 0)")
      ->delimiter(',');
  fit->add_option("--targets", o.targets, "glTF: morph target indices, one example pose each after the times'")
      ->delimiter(',');
  fit->add_option("--terms", o.terms, "Fourier terms N per curve")->check(CLI::Range(1, odeskin::kMaxFourierModes));
  fit->add_option("--material", o.material, "skin, static, or rho,eta,zeta,xi for every part (default skin)");
  fit->add_option("--materials", o.materials_json,
                  "Per-part materials: {\"default\": \"skin\", \"parts\": {\"<bone>\": \"static\" | {\"rho\":..}}}");
  fit->add_option("--residual", residual, "bind (rotation-aware) or posed (the thesis's)")
      ->check(CLI::IsMember({"bind", "posed"}));
  fit->add_option("--skinning", skinning, "lbs or dqs")->check(CLI::IsMember({"lbs", "dqs"}));
  fit->add_option("--key-tolerance", o.key_tolerance, "Key poses reproduced within this fraction of the box, 1e-12 to 0.1");
  fit->add_flag("--pure-fourier", o.pure_fourier,
                "No sparse remainders (the thesis's representation): keys are met only to the reported key error,\n"
                "and the shape jumps by it at every inner key");
  fit->add_option("--bones", o.bones, "Automatic rig: bone count (0: chosen from the mesh)");
  fit->add_option("--up", o.up,
                  "--rig curves: the mesh's up axis, x, y, z, -x, -y or -z (default y), for its templates");
  fit->add_option("--segment-seconds", o.segment_seconds, "Playback length of one key-to-key segment, 1e-4 to 1e6 seconds");
  fit->add_flag("--timings", o.timings, "Print the stage breakdown of the thesis's Table 6.3");
  return fit;
}

CLI::App* addExportCommand(CLI::App& app, odeskin::ExportCommandOptions& o, double& fps) {
  CLI::App* cmd = app.add_subcommand("export", "Write a .odsk asset as a glTF 2.0 binary (.glb) any viewer plays");
  cmd->footer(
      "The mesh, its skin and skeletal animation, and the analytic deformation as morph targets (one per\n"
      "segment, material and mode) whose CUBICSPLINE (or LINEAR) weights follow the time basis; time in seconds is\n"
      "T x segment length. Assets with a posed-space residual or dual-quaternion skinning are baked instead\n"
      "(one morph target per frame), as --bake does for any asset.\n"
      "Examples: odeskin export horse.odsk -o horse.glb\n"
      "          odeskin export horse.odsk -o horse.glb --tolerance 1e-6\n"
      "          odeskin export horse.odsk -o horse-baked.glb --bake --fps 60\n"
      "          odeskin export horse.odsk -o horse-blender.glb --interpolation linear\n"
      "          odeskin export horse.odsk -o horse-small.glb --quantize\n"
      "Blender 3.4's importer drops CUBICSPLINE tangents (glTF-Blender-IO#419): export with\n"
      "--interpolation linear for Blender.");
  cmd->add_option("asset", o.asset, "The .odsk asset")->required();
  cmd->add_option("-o,--output", o.output, "The .glb file to write")->required();
  cmd->add_flag("--bake", o.bake, "One morph target per frame (LINEAR cross-fades) instead of per-mode targets");
  cmd->add_option("--fps", fps, "Frames per second of a bake (default 30)");
  cmd->add_option("--tolerance", o.tolerance,
                  "Position error allowed from the weight keys, and from the skeleton keys, as a fraction of the box\n"
                  "in [1e-8, 0.01] (default 1e-5)");
  cmd->add_option("--materials", o.materials,
                  "Dress the mesh in the materials and textures of this glTF (the file the asset was fitted from, or\n"
                  "any file with one material)");
  cmd->add_option("--interpolation", o.interpolation,
                  "cubic (CUBICSPLINE keys with tangents, the default) or linear (LINEAR keys, more of them, played\n"
                  "as written by importers that drop tangents)");
  cmd->add_flag_callback("--no-target-normals", [&o] { o.target_normals = false; },
                         "Morph targets without NORMAL deltas (about half the bytes; viewers then shade the skinned base shape)");
  cmd->add_flag("--quantize", o.quantize,
                "KHR_mesh_quantization: 16-bit positions and position deltas, 8-bit normals, 16-bit normal deltas\n"
                "(about two thirds of the bytes; the summary gives the rounding's error)");
  return cmd;
}

CLI::App* addEvaluateCommand(CLI::App& app, odeskin::EvaluateCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("evaluate", "Score every in-between method against ground-truth frames");
  cmd->footer(
      "FRAMES are OBJ files of one mesh; --keys are indices into them (from 0). Every method is fitted on\n"
      "the keys and played at the other frames between the first and last key, at tau uniform in frame\n"
      "index within each segment (or from --times, one per frame). Errors are fractions of the ground\n"
      "truth's longest bounding-box side: MVE = max vertex distance, mean = mean vertex distance (the\n"
      "table prints them in %). --pose-source truth fits each frame's skeleton to that frame (only the\n"
      "skeleton, per-bone rigid fits like the keys' unless --skeleton-fit lbs); keys interpolates the key\n"
      "skeletons. Methods: linear, lbs, dqs, psd_lbs, psd_dqs, fd_curve, odeskin_static, odeskin_dynamic.\n"
      "JSON: {\"pose_source\", \"frames\": [{\"frame\", \"t\", \"methods\": {name: {\"mve\", \"mean\",\n"
      "\"ms_per_frame\"}}}], \"summary\": {name: {\"mve_max\", \"mean_mean\"}}}.\n"
      "Examples: odeskin evaluate horse-0{1..9}.obj --keys 0,4,8 --pose-source truth --json truth.json\n"
      "          odeskin evaluate horse-*.obj --keys 0,4,8,12,16,20,24 --methods lbs,odeskin_static \\\n"
      "              --pose-source keys --json keys.json --terms 9\n"
      "          odeskin evaluate horse-0{1..5}.obj --keys 0,4 --json h.json --png heat/");
  cmd->add_option("frames", o.frames, "Ground-truth frames: OBJ files of one mesh, in time order")->required();
  cmd->add_option("--keys", o.keys, "Key frame indices into FRAMES, strictly increasing, at least 2")
      ->delimiter(',')->required();
  cmd->add_option("--methods", o.methods, "all, or a comma list of method names (default all)");
  cmd->add_option("--pose-source", o.pose_source, "truth or keys (default truth)")
      ->check(CLI::IsMember({"truth", "keys"}));
  cmd->add_option("--json", o.json, "Write the per-frame and summary numbers here")->required();
  cmd->add_option("--times", o.times, "One time per frame, strictly increasing (default: the frame index)")
      ->delimiter(',');
  cmd->add_option("--terms", o.terms, "Fourier terms N per curve of the odeskin fit (default 9)")
      ->check(CLI::Range(1, odeskin::kMaxFourierModes));
  cmd->add_option("--rig", o.rig,
                  "auto (default: bones derived from the keys' motion), curves (from the first key's iso-curves)\n"
                  "or a libigl .tgf skeleton");
  cmd->add_option("--bind", o.bind, "Rest mesh (.obj) for --rig SKELETON.tgf");
  cmd->add_option("--weights", o.weights, "Skinning weights (.dmat) for --rig SKELETON.tgf");
  cmd->add_option("--bones", o.bones, "Automatic rig: bone count (0: chosen from the mesh)");
  cmd->add_option("--up", o.up,
                  "--rig curves: the mesh's up axis, x, y, z, -x, -y or -z (default y), for its templates");
  cmd->add_option("--skeleton-fit", o.skeleton_fit,
                  "rigid (default: per-bone rigid fits, keys and truth frames alike) or lbs (the rig's SSDR\n"
                  "transforms, which minimise each frame's LBS error)")
      ->check(CLI::IsMember({"rigid", "lbs"}));
  cmd->add_option("--png", o.png_dir,
                  "Also DIR/frame_NNNN.png per in-between frame: a panel per method coloured by its error\n"
                  "against the truth (fraction of the truth's longest box side, as render --heat), and DIR/obj/");
  return cmd;
}

CLI::App* addBlendCommand(CLI::App& app, odeskin::BlendCommandOptions& o, double& alpha, double& beta, double& gamma,
                          int& spline) {
  CLI::App* cmd = app.add_subcommand("blend", "Write a fourth-order ODE blending surface of the thesis (ch. 3) as OBJ");
  cmd->footer(
      "Blends the two trimlines of thesis example 3.15, 3.16, 3.17 or 3.18 (MATH.md 2.13; 3.14 is garbled, C14)\n"
      "with the solution of alpha G'''' + beta G'' + gamma G = 0 that meets both curves and their tangents.\n"
      "Default parameters are the thesis's: 3.15 (1, 2, 1), 3.16 (1, 3, 1), 3.17 (1, 1, 1), 3.18 (1, 0.5, 1)\n"
      "of Fig. 3.5(a). The OBJ is a U x V grid: vertex i*V + j is S(u_i, v_j), u_i = i/(U-1), v_j = 2 pi j/V,\n"
      "with quads joining the grid and wrapping in v. alpha = 0 and resonant parameters (e.g. gamma = 0,\n"
      "beta = 4 pi^2 alpha) are rejected with exit status 1.\n"
      "Examples: odeskin blend --example 3.17 -o hyperboloid.obj\n"
      "          odeskin blend --example 3.18 --alpha 3.7 --beta 2 --gamma 18 --res 80,240 -o fig35c.obj\n"
      "          odeskin blend --example 3.18 --hermite -o hermite.obj\n"
      "          odeskin blend --example 3.18 --spline 4 -o spline4.obj");
  cmd->add_option("--example", o.example, "Thesis example: 3.15, 3.16, 3.17 or 3.18")->required();
  cmd->add_option("--alpha", alpha, "Shape parameter alpha (default: the example's)");
  cmd->add_option("--beta", beta, "Shape parameter beta (default: the example's)");
  cmd->add_option("--gamma", gamma, "Shape parameter gamma (default: the example's)");
  cmd->add_option("--res", o.res, "Grid samples U,V across and around the blend, U >= 2, V >= 3 (default 64,128)");
  cmd->add_flag("--hermite", o.hermite, "The cubic Hermite blend of Eq. 3.19 instead of the ODE");
  cmd->add_option("--spline", spline, "The clamped cubic-spline approximation (Sec. 3.7) with N pieces, 1 to 1000");
  cmd->add_option("-o,--output", o.output, "The .obj file to write")->required();
  return cmd;
}

CLI::App* addSurfaceCommand(CLI::App& app, odeskin::SurfaceCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("surface", "Tessellate a network of C2 surface patches (thesis ch. 4) into one .glb");
  cmd->footer(
      "NETWORK.json: curves, boundaries with their u-derivatives (coefficients, control curves or given\n"
      "curves) and a shape (rho, eta, lambda) per patch; schema in docs/surfaces.md. Patches sharing a\n"
      "boundary are C2 across it; patches side by side in v must have equal eta/rho and lambda/rho\n"
      "(MATH.md 3.8), otherwise the network is refused unless it says \"continuity\": \"warn\".\n"
      "The mesh is one welded grid: --res U,V samples per patch, shared along every seam.\n"
      "Examples: odeskin surface samples/surfaces/networks/vase.json -o vase.glb --up z\n"
      "          odeskin surface torus.json -o torus.glb --res 65,65 --obj\n"
      "          odeskin surface patch.json -o thin.glb --shape 0.0001,3,0.0001\n"
      "          odeskin surface sheet.json -o sheet.glb --backend vulkan --validation");
  cmd->add_option("network", o.network, "The network (.json)")->required();
  cmd->add_option("-o,--output", o.output, "The .glb file to write")->required();
  cmd->add_option("--res", o.resolution, "U,V: samples per patch along u and v, both edges included (default 33,33)");
  cmd->add_flag("--obj", o.obj, "Also write the welded quads as OUT.obj (same stem as the .glb)");
  cmd->add_option("--shape", o.shape, "RHO,ETA,LAMBDA for every patch instead of the file's shapes");
  cmd->add_option("--up", o.up,
                  "The network's up axis: x, y, z, -x, -y or -z (default y). glTF is y-up: another axis turns the\n"
                  "mesh node so viewers show it upright (the sample networks are z-up)");
  cmd->add_option("--backend", o.backend,
                  "cpu (double-precision reference), vulkan (compute shader, float), or auto (vulkan, else cpu)")
      ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
  cmd->add_flag("--validation", o.validation, "vulkan: enable the Khronos validation layer; fail on any message");
  return cmd;
}

CLI::App* addRigCommand(CLI::App& app, odeskin::RigCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("rig", "Derive a skeleton and weights from a mesh's iso-parametric curves (thesis ch. 5)");
  cmd->footer(
      "The first MESH is the bind mesh; further OBJ meshes of the same vertices are example poses: where a\n"
      "limb bends in any of them a joint goes (the larger bend wins where poses disagree). Or one .gltf/.glb:\n"
      "its mesh, with poses from --times or --targets; --gltf then keeps its seams, UVs and materials. Joints: where limbs\n"
      "leave the body, at branch points and free ends, where the curve skeleton turns by more than --angle,\n"
      "and the template's (elbows, knees, spine; --template auto picks by the number of feet). Writes libigl\n"
      "files: the skeleton (.tgf), distance weights (.dmat, V x B); --gltf a skinned .glb; --png a picture.\n"
      "Examples: odeskin rig cat-00.obj -o cat.tgf --weights cat.dmat --png cat-rig.png\n"
      "          odeskin rig cheburashka.obj -o cheb.tgf --template humanoid --gltf cheb.glb\n"
      "          odeskin rig cylinder.obj poses-2/cylinder-*.obj -o cyl.tgf --template none\n"
      "          odeskin rig character.glb -o character.tgf --gltf character-rigged.glb\n"
      "          odeskin rig cat-00.obj -o cat.tgf --curves cuts --repeat 20   (stage times: median, fastest)");
  cmd->add_option("meshes", o.meshes, "OBJ files: the bind mesh, then optional example poses; or one .gltf/.glb")->required();
  cmd->add_option("-o,--output", o.output, "The skeleton to write (.tgf)")->required();
  cmd->add_option("--weights", o.weights, "Also write the skinning weights (.dmat, vertices x bones)");
  cmd->add_option("--template", o.template_kind, "auto, humanoid, quadruped or none (default auto)")
      ->check(CLI::IsMember({"auto", "humanoid", "quadruped", "none"}));
  cmd->add_option("--gltf", o.gltf, "Also write the mesh with its skin and joints as a .glb");
  CLI::Option* rig_png =
      cmd->add_option("--png", o.png, "Also draw the curves and the skeleton over the mesh (Vulkan; lavapipe works)");
  cmd->add_option("--curves", o.curves, "auto (default: loops on a mesh of >= 80% quads, else levels), levels (geodesic\n"
                  "rings), cuts (odeskin's plane-cut curve identification run on the parts the rings find) or loops\n"
                  "(the quad edge loops the ray-and-fan test calls circumferential)")
      ->check(CLI::IsMember({"auto", "cuts", "levels", "loops"}));
  cmd->add_option("--angle", o.angle_deg, "Turn in degrees that makes a joint (default 20)");
  cmd->add_option("--up", o.up, "The mesh's up axis: x, y, z, -x, -y or -z (default y)");
  cmd->add_option("--compare", o.compare, "A ground-truth skeleton (.tgf): print joint errors and bone counts against it");
  cmd->add_option("--azimuth", o.azimuth_deg, "--png camera angle about the up axis in degrees (default 30)")->needs(rig_png);
  cmd->add_option("--repeat", o.repeat, "Run the rig N times and print the median and fastest time of each stage");
  cmd->add_option("--mesh", o.mesh, "glTF: the mesh node (default: the first skinned mesh, else the first mesh)");
  cmd->add_option("--animation", o.animation, "glTF: animation name or index for --times (default: the first)");
  cmd->add_option("--times", o.times, "glTF: animation times in seconds, one example pose each")->delimiter(',');
  cmd->add_option("--targets", o.targets, "glTF: morph target indices, one example pose each")->delimiter(',');
  return cmd;
}

CLI::App* addReconstructCommand(CLI::App& app, odeskin::ReconstructCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("reconstruct", "Rebuild a mesh (a face) from a curve network of C2 patches (thesis 4.7)");
  cmd->footer(
      "MESH.obj: one open surface (holes such as a mouth are filled), laid over the unit square by mean-value\n"
      "coordinates: u along its second principal direction (a face's height), v along the first. rows + 1\n"
      "curves across it are sampled from the triangles with their u-derivatives (a least-squares fit along u)\n"
      "and become a rows x cols network of C2 patches (docs/surfaces.md). Reports, for every vertex, the\n"
      "distance to S at its (u, v) and to the surface, as % of the box's longest side, and the data size.\n"
      "--poses: poses of the same mesh (same vertices and faces, e.g. expressions): the same samples read on\n"
      "each pose rebuild it. Vertices on edges stretched more than --tear-ratio times (numbered differently\n"
      "from MESH) are flagged: left out of the figures and filled in from their neighbours for the samples.\n"
      "-o OUT.obj: MESH's reconstruction with MESH's faces and vertex order (odeskin render OUT.obj --heat\n"
      "MESH.obj draws the error); pose P gives OUT-P.obj, and OUT-P-reference.obj if P has flagged vertices.\n"
      "Examples: odeskin reconstruct face-00.obj -o recon.obj\n"
      "          odeskin reconstruct face-00.obj --rows 24 --cols 12 --json report.json\n"
      "          odeskin reconstruct face-00.obj --poses face-01.obj face-02.obj -o out/recon.obj --network net.json");
  cmd->add_option("mesh", o.mesh, "The mesh (.obj)")->required();
  cmd->add_option("--poses", o.poses, "Poses of the same mesh (.obj) rebuilt with the same curve network");
  cmd->add_option("--rows", o.rows, "Patches along u (default 16)")->check(CLI::Range(1, 1000));
  cmd->add_option("--cols", o.columns, "Patches along v (default 16)")->check(CLI::Range(1, 1000));
  cmd->add_option("--points", o.points, "Curve points per patch along v (default 2; a curve has cols x points + 1)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--shape", o.shape, "RHO,ETA,LAMBDA of every patch (default 1,3,1)");
  cmd->add_option("--derivative-fit", o.derivative_fit,
                  "POINTS,DEGREE,WINDOW: mesh samples per side, polynomial degree and reach in row heights of the\n"
                  "S_u, S_uu fit (default 6,3,0.5)");
  cmd->add_option("--tear-ratio", o.tear_ratio, "Flag pose vertices on edges stretched more than this (default 4)");
  cmd->add_option("-o,--output", o.output, "The reconstruction of MESH (.obj); poses are written beside it");
  cmd->add_option("--network", o.network, "Also MESH's curve network as a network file (.json) for odeskin surface");
  cmd->add_option("--json", o.json, "Write the figures here (.json)");
  return cmd;
}

struct CompareCliValues {
  double t = 0.0;
  double heat_max = 0.0;
  CLI::Option* t_opt = nullptr;
  CLI::Option* heat_max_opt = nullptr;
};

CLI::App* addCompareCommand(CLI::App& app, odeskin::CompareOptions& o, CompareCliValues& v) {
  CLI::App* cmd = app.add_subcommand("compare", "Per-vertex error of a mesh against a reference, and a PLY heat map");
  cmd->footer(
      "MESH and REFERENCE have the same vertices (.obj, .glb/.gltf, or a .odsk played at --t). Errors are\n"
      "distances over REFERENCE's longest bounding-box side, as odeskin evaluate measures them: the largest\n"
      "(MVE) and its vertex, the mean, the RMS and the 99th percentile. -o OUT.ply writes MESH with a heat\n"
      "colour per vertex (blue 0 to red at --heat-max, default the MVE) and the error as its quality, for\n"
      "MeshLab or Blender; give several comparisons one --heat-max to share a scale.\n"
      "Examples: odeskin compare horse.odsk horse-03.obj --t 0.5\n"
      "          odeskin compare horse.odsk horse-03.obj --t 0.5 -o error.ply --heat-max 0.01 --json error.json");
  cmd->add_option("mesh", o.mesh, "The mesh to score")->required();
  cmd->add_option("reference", o.reference, "The reference with the same vertices (ground truth)")->required();
  v.t_opt = cmd->add_option("--t", v.t, "MESH's time: global T in [0, K-1] for .odsk (default 0), animation seconds for .glb/.gltf (default: the bind\n"
                   "pose, the mesh as its buffers hold it)");
  cmd->add_option("-o,--output", o.ply, "MESH coloured by its error (.ply)");
  v.heat_max_opt = cmd->add_option("--heat-max", v.heat_max, "Top of the colour range, a fraction of the box (default: the MVE)");
  cmd->add_option("--json", o.json, "Write the figures here (.json)");
  return cmd;
}

struct RenderCliValues {
  double t = 0.0;
  double heat_max = 0.0;
  std::filesystem::path heat;
  CLI::Option* t_opt = nullptr;
  CLI::Option* heat_opt = nullptr;
  CLI::Option* heat_max_opt = nullptr;
};

CLI::App* addRenderCommand(CLI::App& app, odeskin::RenderOptions& o, RenderCliValues& v) {
  CLI::App* render = app.add_subcommand("render", "Draw meshes to PNG without a display (Vulkan; lavapipe works)");
  render->footer(
      "Several inputs are drawn side by side with one camera and scale. --heat REF colours each panel by\n"
      "its distance to REF per vertex, as a fraction of REF's longest bounding-box side (MATH.md 6.1), with a colour bar.\n"
      "--t: global time T in [0, K-1] for .odsk assets, seconds into the animation for .gltf/.glb.\n"
      "Examples: odeskin render horse-01.obj -o horse.png --azimuth 90\n"
      "          odeskin render horse.odsk horse-03.obj --t 0.5 --lbs --heat horse-03.obj -o compare.png\n"
      "          odeskin render arm.odsk --curves --turntable 8 -o turn/arm_%02d.png --strip turn.png");
  render->add_option("inputs", o.inputs, "Meshes: .obj, .gltf/.glb (bind pose or --t seconds), .odsk (at --t)")->required();
  render->add_option("-o,--output", o.output, "OUT.png; with --turntable a pattern OUT_%03d.png (default: OUT_NNN.png)")
      ->required();
  v.t_opt = render->add_option("--t", v.t, "Asset time T in [0, K-1] (default 0); glTF animation seconds (default: the bind pose, the mesh as its\n"
                   "buffers hold it)");
  render->add_option("--size", o.size, "Whole picture WIDTHxHEIGHT (default 720x540 per panel, plus the colour bar)");
  v.heat_opt = render->add_option("--heat", v.heat, "Reference mesh with the same vertices: per-vertex error heat map");
  v.heat_max_opt = render->add_option("--heat-max", v.heat_max, "Top of the colour bar as a fraction of REF's longest box side (default: the largest error)");
  render->add_flag("--curves", o.curves, "Draw the assets' iso-parametric curves over the surface");
  render->add_flag("--lbs", o.lbs, "Also draw each asset skinned without its residual (plain LBS), in a panel before it");
  render->add_option("--turntable", o.turntable, "Write N frames turning once about the up axis");
  render->add_option("--strip", o.strip, "With --turntable: also a contact sheet of the frames (PNG)");
  render->add_option("--azimuth", o.azimuth_deg, "Camera angle about the up axis in degrees (0: looking down -z for up y)");
  render->add_option("--elevation", o.elevation_deg, "Camera height above the horizon in degrees");
  render->add_option("--fov", o.fov_deg, "Vertical field of view in degrees");
  render->add_option("--up", o.up, "Up axis: x, y, z, -x, -y or -z");
  render->add_option("--labels", o.labels, "Panel names, comma separated (default: file names)")->delimiter(',');
  render->add_flag("--no-labels", o.no_labels, "No text under the panels");
  render->add_option("--background", o.background, "Background colour RRGGBB");
  render->add_option("--samples", o.samples, "Multisampling per pixel (1 turns it off)");
  render->add_flag("--validation", o.validation, "Enable the Khronos validation layer; fail on any message");
  return render;
}

// The command line parsed and run; `verb` is set once a verb is known, for main's last-resort message.
int run(int argc, char** argv, std::string& verb) {
  CLI::App app{"odeskin: analytic physics-based skin deformation (Bian 2018) on CPU and Vulkan compute"};
  app.require_subcommand(1);
  app.fallthrough();  // global options may follow the verb
  std::string device = "auto";
  bool quiet = false;
  app.add_option("--device", device, "Vulkan device: auto, an index or a name substring (env ODESKIN_DEVICE)");
  app.add_flag("-q,--quiet", quiet, "No summaries, notes or progress bars (errors still go to stderr)");

  std::filesystem::path info_asset;
  CLI::App* info = app.add_subcommand("info", "Describe a .odsk asset, or without one list the Vulkan devices");
  info->add_option("asset", info_asset, "A .odsk asset: counts, coefficient and byte sizes, size ratios");
  info->footer("Examples: odeskin info              (the Vulkan devices)\n"
               "          odeskin info arm.odsk     (an asset)");

  odeskin::DemoOptions demo;
  std::string demo_backend = "auto";
  std::string residual = "bind";
  CLI::App* demo_cmd = app.add_subcommand("demo", "Fit the procedural arm's two poses and play the in-betweens");
  demo_cmd->footer(
      "Checks that the first and last frames reproduce the two poses, and prints the per-frame time.\n"
      "Examples: odeskin demo\n"
      "          odeskin demo --backend cpu --frames 60 --material static -o arm-frames");
  demo_cmd->add_option("-o,--output", demo.output_dir, "Output folder for start.obj, end.obj, frame_NNNN.obj");
  demo_cmd->add_option("--frames", demo.frames, "Frames from t = 0 to t = 1")->check(CLI::Range(2, 100000));
  demo_cmd->add_option("--backend", demo_backend, "cpu, vulkan or auto")->check(CLI::IsMember({"auto", "cpu", "vulkan"}));
  demo_cmd->add_option("--modes", demo.modes, "Fourier modes N per curve")->check(CLI::Range(1, 15));
  demo_cmd->add_option("--material", demo.material, "skin (dynamic) or static")->check(CLI::IsMember({"skin", "static"}));
  demo_cmd->add_option("--residual", residual, "bind (rotation-aware) or posed (the thesis's)")
      ->check(CLI::IsMember({"bind", "posed"}));
  demo_cmd->add_option("--threads", demo.threads, "CPU threads (0 = all)");
  demo_cmd->add_flag("--validation", demo.validation, "Enable the Khronos validation layer; fail on any message");
  demo_cmd->add_option("--save-asset", demo.asset_path, "Also save the fitted arm as a .odsk asset (for play and info)");

  odeskin::PlayOptions play;
  double play_t = 0.0;
  double play_fps = 0.0;
  double play_seconds = 0.0;
  std::string play_backend = "cpu";
  CLI::App* play_cmd =
      app.add_subcommand("play",
                         "Evaluate an asset at a time or over a sequence: OBJ frames, a baked GLB, or a PC2 or MDD cache");
  play_cmd->footer(
      "T runs over [0, K-1] for K example poses: integer T is example pose T, T = 1.5 the middle of the\n"
      "second segment. A sequence maps seconds to T = seconds / segment length.\n"
      "Examples: odeskin play arm.odsk --t 0.5 -o mid.obj\n"
      "          odeskin play arm.odsk --fps 30 --seconds 1 -o frames/arm_%04d.obj --backend vulkan\n"
      "          odeskin play horse.odsk --fps 8 --png preview --size 480x360\n"
      "          odeskin play horse.odsk --t 0 -o base.obj && odeskin play horse.odsk --fps 24 -o horse.pc2\n"
      "A .pc2 or .mdd point cache (sample k at scene frame k) animates the mesh --t 0 writes, vertex\n"
      "for vertex: Blender's Mesh Cache modifier, 3ds Max's Point Cache (PC2), LightWave and Modo (MDD).");
  play_cmd->add_option("asset", play.asset, "The .odsk asset")->required();
  CLI::Option* t_opt = play_cmd->add_option("--t", play_t, "One frame at global time T in [0, K-1]");
  CLI::Option* fps_opt = play_cmd->add_option("--fps", play_fps, "A sequence at this frame rate");
  CLI::Option* seconds_opt =
      play_cmd->add_option("--seconds", play_seconds, "Sequence length in seconds (default: the whole asset)");
  t_opt->excludes(fps_opt);
  seconds_opt->needs(fps_opt);
  play_cmd->add_option("-o,--output", play.output,
                       "OUT.obj, a pattern with one frame number (OUT_%04d.obj), OUT.glb (baked), OUT.pc2 or OUT.mdd\n"
                       "(point caches)");
  play_cmd->add_option("--materials", play.materials,
                       "With -o OUT.glb: dress it in the materials and textures of this glTF (the file it was fitted from)");
  play_cmd->add_flag("--quantize", play.quantize,
                     "With -o OUT.glb: KHR_mesh_quantization (16-bit positions and deltas, 8-bit normals); the summary\n"
                     "gives the rounding's error");
  CLI::Option* play_png =
      play_cmd->add_option("--png", play.png_dir, "Also draw the frames to DIR/frame_NNNN.png and DIR/strip.png (Vulkan)");
  // The picture options without --png would be ignored, so they are refused.
  play_cmd->add_option("--size", play.png_size, "--png picture size WIDTHxHEIGHT")->needs(play_png);
  play_cmd->add_flag("--curves", play.png_curves, "--png: draw the iso-parametric curves")->needs(play_png);
  play_cmd->add_option("--azimuth", play.png_azimuth_deg, "--png camera angle about +y in degrees")->needs(play_png);
  play_cmd->add_option("--elevation", play.png_elevation_deg, "--png camera height above the horizon in degrees")
      ->needs(play_png);
  play_cmd->add_option("--backend", play_backend, "cpu (double reference), vulkan, or auto")
      ->check(CLI::IsMember({"auto", "cpu", "vulkan"}));
  play_cmd->add_flag("--validation", play.playback.validation, "Enable the Khronos validation layer; fail on any message");

  odeskin::FitCommandOptions fit;
  std::string fit_residual = "bind";
  std::string fit_skinning = "lbs";
  CLI::App* fit_cmd = addFitCommand(app, fit, fit_residual, fit_skinning);

  odeskin::ExportCommandOptions export_options;
  double export_fps = 30.0;
  CLI::App* export_cmd = addExportCommand(app, export_options, export_fps);
  odeskin::RenderOptions render;
  RenderCliValues render_values;
  CLI::App* render_cmd = addRenderCommand(app, render, render_values);

  odeskin::EvaluateCommandOptions evaluate_options;
  CLI::App* evaluate_cmd = addEvaluateCommand(app, evaluate_options);

  odeskin::BenchCommandOptions bench_options;
  CLI::App* bench_cmd = odeskin::addBenchCommand(app, bench_options);

  odeskin::RigCommandOptions rig_options;
  CLI::App* rig_cmd = addRigCommand(app, rig_options);

  odeskin::BlendCommandOptions blend_options;
  double blend_alpha = 0.0, blend_beta = 0.0, blend_gamma = 0.0;
  int blend_spline = 0;
  CLI::App* blend_cmd = addBlendCommand(app, blend_options, blend_alpha, blend_beta, blend_gamma, blend_spline);

  odeskin::SurfaceCommandOptions surface_options;
  CLI::App* surface_cmd = addSurfaceCommand(app, surface_options);

  odeskin::ReconstructCommandOptions reconstruct_options;
  CLI::App* reconstruct_cmd = addReconstructCommand(app, reconstruct_options);

  odeskin::CompareOptions compare_options;
  CompareCliValues compare_values;
  CLI::App* compare_cmd = addCompareCommand(app, compare_options, compare_values);

  odeskin::requireDecimalIntegers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line like every other failure, pointing at the help of the verb that was being parsed.
    std::string message = e.what();
    std::replace(message.begin(), message.end(), '\n', ' ');
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
      message = "unknown command '" + std::string(argv[1]) + "'";
    }
    const std::string help = app.get_subcommands().empty() ? "odeskin --help"
                                                           : "odeskin " + app.get_subcommands().front()->get_name() + " --help";
    std::cerr << "odeskin: error: " << message << " (see " << help << ")\n";
    return 2;
  }

  if (!app.get_subcommands().empty()) verb = app.get_subcommands().front()->get_name();
  odeskin::Console console{std::cout, std::cerr, quiet, odeskin::stderrIsTerminal()};
  if (info->parsed()) {
    if (!info_asset.empty()) return odeskin::runInfoCommand(info_asset, console);
    odeskin::Status status = odeskin::vk::printDeviceInfo(std::cout, device);
    return status.ok() ? 0 : fail(status);
  }
  if (demo_cmd->parsed()) {
    demo.backend = backendNamed(demo_backend);
    demo.device = device;
    demo.residual_space = residual == "posed" ? odeskin::ResidualSpace::kPosed : odeskin::ResidualSpace::kBind;
    return runDemoCommand(demo, quiet);
  }
  if (play_cmd->parsed()) {
    if (t_opt->count() > 0) play.t = play_t;
    if (fps_opt->count() > 0) play.fps = play_fps;
    if (seconds_opt->count() > 0) play.seconds = play_seconds;
    play.playback.backend = backendNamed(play_backend);
    play.playback.device = device;
    return odeskin::runPlayCommand(play, console);
  }
  if (render_cmd->parsed()) {
    if (render_values.t_opt->count() > 0) render.t = render_values.t;
    if (render_values.heat_opt->count() > 0) render.heat = render_values.heat;
    if (render_values.heat_max_opt->count() > 0) render.heat_max = render_values.heat_max;
    render.device = device;
    return odeskin::runRenderCommand(render, console);
  }
  if (fit_cmd->parsed()) {
    fit.residual_space = fit_residual == "posed" ? odeskin::ResidualSpace::kPosed : odeskin::ResidualSpace::kBind;
    fit.skinning = fit_skinning == "dqs" ? odeskin::SkinningMode::kDualQuaternion : odeskin::SkinningMode::kLinear;
    return odeskin::runFitCommand(fit, console);
  }
  if (export_cmd->parsed()) {
    if (export_cmd->get_option("--fps")->count() > 0) export_options.fps = export_fps;
    return odeskin::runExportCommand(export_options, console);
  }
  if (bench_cmd->parsed()) return odeskin::runBenchCommand(bench_options, console, device);
  if (evaluate_cmd->parsed()) return odeskin::runEvaluateCommand(evaluate_options, console, device);
  if (rig_cmd->parsed()) {
    rig_options.device = device;
    return odeskin::runRigCommand(rig_options, console);
  }
  if (blend_cmd->parsed()) {
    if (blend_cmd->get_option("--alpha")->count() > 0) blend_options.alpha = blend_alpha;
    if (blend_cmd->get_option("--beta")->count() > 0) blend_options.beta = blend_beta;
    if (blend_cmd->get_option("--gamma")->count() > 0) blend_options.gamma = blend_gamma;
    if (blend_cmd->get_option("--spline")->count() > 0) blend_options.spline_pieces = blend_spline;
    return odeskin::runBlendCommand(blend_options, console);
  }
  if (surface_cmd->parsed()) {
    surface_options.device = device;
    return odeskin::runSurfaceCommand(surface_options, console);
  }
  if (reconstruct_cmd->parsed()) return odeskin::runReconstructCommand(reconstruct_options, console);
  if (compare_cmd->parsed()) {
    if (compare_values.t_opt->count() > 0) compare_options.t = compare_values.t;
    if (compare_values.heat_max_opt->count() > 0) compare_options.heat_max = compare_values.heat_max;
    return odeskin::runCompareCommand(compare_options, console);
  }
  return 2;
}

// Reports what escaped a verb without allocating (the failure may be bad_alloc).
int reportEscaped(const std::string& verb, const char* problem, const char* detail) noexcept {
  std::fflush(stdout);  // std::cout is synchronised with stdio, so its output goes first
  std::fprintf(stderr, "odeskin: error: %s%s%s%s\n", verb.c_str(), verb.empty() ? "" : ": ", problem, detail);
  return 1;
}

}  // namespace

// Nothing the engine throws (it reports Status) is expected here; the catch turns what the standard
// library can still throw (std::bad_alloc for an input too large for memory, a library's exception)
// into exit status 1 and the usual one line, never an abort.
int main(int argc, char** argv) {
  std::string verb;
  odeskin::removeTemporariesOnSignal();
  int code = 1;
  try {
    code = run(argc, argv, verb);
  } catch (const std::bad_alloc&) {
    code = reportEscaped(verb, "out of memory (the input is too large for this machine)", "");
  } catch (const std::exception& e) {
    code = reportEscaped(verb, "unexpected failure: ", e.what());
  } catch (...) {
    code = reportEscaped(verb, "unexpected failure (an unknown exception)", "");
  }
  return odeskin::checkStandardOutput("odeskin: error: ", verb.c_str(), code);
}

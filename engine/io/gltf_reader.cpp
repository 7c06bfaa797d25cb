// SPDX-License-Identifier: MIT
#include "gltf_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include "../core/number_text.hpp"
#include "../core/smoothing_groups.hpp"
#include "../kernels/lbs_job.hpp"
#include "../offline/residual_fit.hpp"
#include "gltf_animation.hpp"
#include "gltf_dequantize.hpp"
#include "gltf_load.hpp"
#include "gltf_mesh.hpp"
#include "gltf_nodes.hpp"
#include "gltf_pose.hpp"
#include "gltf_skin.hpp"
#include "gltf_weld.hpp"

namespace odeskin {
namespace {

using namespace gltf;

// A key pose must be rigid: skin matrices that scale or shear more than this are refused.
constexpr double kRigidTolerance = 1e-4;
// The rest pose may move the mesh this far (of its box) from its buffers unremarked: float32
// inverse bind matrices round to about 1e-7; fit's default key tolerance is 1e-4.
constexpr double kRestPoseTolerance = 1e-5;
// Welded copies of a vertex must move together under each morph target: relative to the bounding
// box diagonal, looser than float round-off (6e-8) and far below a visible tear.
constexpr double kWeldedDeltaTolerance = 1e-5;

std::string nodeLabel(const tinygltf::Model& model, int node) {
  const std::string& name = model.nodes[static_cast<std::size_t>(node)].name;
  return "node " + std::to_string(node) + (name.empty() ? "" : " '" + name + "'");
}

// The node whose mesh we read: by name, else the first skinned mesh node, else the first mesh node.
Result<int> chooseMeshNode(const tinygltf::Model& model, const std::string& name) {
  int first_mesh = -1;
  int first_skinned = -1;
  std::string mesh_nodes;
  for (int i = 0; i < static_cast<int>(model.nodes.size()); ++i) {
    const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(i)];
    if (node.mesh < 0) continue;
    if (!name.empty() && node.name == name) return i;
    mesh_nodes += (mesh_nodes.empty() ? "'" : ", '") + node.name + "'";
    if (first_mesh < 0) first_mesh = i;
    if (first_skinned < 0 && node.skin >= 0) first_skinned = i;
  }
  if (!name.empty()) {
    return invalidArgument("no mesh node named '" + name + "' (mesh nodes: " + (mesh_nodes.empty() ? "none" : mesh_nodes) + ")");
  }
  if (first_mesh < 0) return parseError("no node has a mesh");
  return first_skinned >= 0 ? first_skinned : first_mesh;
}

// Animation by name, else by index written as text; empty: the first.
Result<int> chooseAnimation(const tinygltf::Model& model, const std::string& wanted) {
  std::string available;
  for (std::size_t i = 0; i < model.animations.size(); ++i) {
    if (!wanted.empty() && model.animations[i].name == wanted) return static_cast<int>(i);
    available += (available.empty() ? "" : ", ") + std::to_string(i) + " '" + model.animations[i].name + "'";
  }
  if (model.animations.empty()) return invalidArgument("poses at times need an animation, and the file has none");
  if (wanted.empty()) return 0;
  int index = -1;
  const auto [ptr, ec] = std::from_chars(wanted.data(), wanted.data() + wanted.size(), index);
  if (ec == std::errc() && ptr == wanted.data() + wanted.size() && index >= 0 &&
      index < static_cast<int>(model.animations.size())) {
    return index;
  }
  return invalidArgument("unknown animation '" + wanted + "' (available: " + available + ")");
}

// node.weights, else mesh.weights, else zeros (spec 3.7.2.2).
Result<std::vector<double>> defaultWeights(const tinygltf::Model& model, int node_index, std::size_t targets) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  const std::vector<double>& w = !node.weights.empty() ? node.weights : mesh.weights;
  if (w.empty()) return std::vector<double>(targets, 0.0);
  if (w.size() != targets) {
    return parseError(nodeLabel(model, node_index) + ": " + std::to_string(w.size()) + " default morph weights for " +
                      std::to_string(targets) + " targets");
  }
  for (double x : w) {
    if (!std::isfinite(x)) return parseError(nodeLabel(model, node_index) + ": a default morph weight is not finite");
  }
  return w;
}

// Each target's deltas on topology vertices; copies of a welded vertex must agree.
Result<std::vector<std::vector<Vec3>>> topologyDeltas(const MeshData& mesh, const Welded& welded) {
  Vec3 lo(0.0);
  Vec3 hi(0.0);
  if (!welded.positions.empty()) lo = hi = welded.positions.front();
  for (const Vec3& p : welded.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double tolerance = kWeldedDeltaTolerance * std::max(glm::length(hi - lo), 1e-300);
  std::vector<std::vector<Vec3>> out(mesh.target_deltas.size());
  for (std::size_t t = 0; t < out.size(); ++t) {
    const std::vector<Vec3>& render = mesh.target_deltas[t];
    out[t].resize(welded.positions.size());
    for (std::size_t v = 0; v < welded.positions.size(); ++v) out[t][v] = render[welded.first_render[v]];
    for (std::size_t r = 0; r < render.size(); ++r) {
      const std::uint32_t v = welded.topology_of_render[r];
      if (glm::length(render[r] - out[t][v]) > tolerance) {
        return parseError("morph target " + std::to_string(t) + " moves render vertices " +
                          std::to_string(welded.first_render[v]) + " and " + std::to_string(r) +
                          " (welded into topology vertex " + std::to_string(v) + ") apart");
      }
    }
  }
  return out;
}

std::string formatTime(double t) {
  std::ostringstream s;
  s.precision(9);
  s << t;
  return s.str();
}

struct Skinned {
  SkinData skin;
  std::vector<int> parents;
  std::vector<NodeTransform> rest;
  std::string rest_warning;  // when the nodes' rest pose skins the mesh away from its buffers
};

// Viewers show a skinned mesh through its joints, never as its buffers hold it. Where the joints'
// rest transforms and the inverse bind matrices do not cancel, the bind pose odeskin takes as key 0
// is not the shape the file shows at rest: say which joint moves the mesh, and by how much.
std::string restPoseWarning(const Skinned& s, const MeshData& mesh) {
  const std::vector<Vec3>& positions = mesh.positions;
  if (positions.empty()) return {};
  const std::vector<glm::dmat4> global = globalMatrices(s.rest, s.parents);
  std::vector<glm::dmat4> rest_skin;
  for (std::size_t j = 0; j < s.skin.joint_nodes.size(); ++j) {
    rest_skin.push_back(global[static_cast<std::size_t>(s.skin.joint_nodes[j])] * s.skin.inverse_bind[j]);
  }
  const double box = longestBoxSide(positions);
  // Each vertex skinned at rest as a viewer skins it; the joint of its largest weight is named.
  const std::size_t slots = 4 * mesh.influence_sets;
  double worst = 0.0;
  std::size_t worst_joint = 0;
  for (std::size_t r = 0; r < positions.size(); ++r) {
    glm::dvec4 moved(0.0);
    double total = 0.0, largest = -1.0;
    std::size_t dominant = 0;
    for (std::size_t k = 0; k < slots; ++k) {
      const double w = mesh.weights[r * slots + k];
      const std::uint32_t j = mesh.joints[r * slots + k];
      if (!(w > 0.0) || j >= rest_skin.size()) continue;
      moved += w * (rest_skin[j] * glm::dvec4(positions[r], 1.0));
      total += w;
      if (w > largest) largest = w, dominant = j;
    }
    if (!(total > 0.0)) continue;
    const double distance = glm::length(Vec3(moved) / total - positions[r]);
    if (distance > worst) worst = distance, worst_joint = dominant;
  }
  if (!(box > 0.0) || !(worst > kRestPoseTolerance * box)) return {};
  return "the nodes' rest pose moves the mesh by up to " + messageNumber(worst / box) + " of its box (joint " +
         std::to_string(worst_joint) + " '" + s.skin.skeleton.names[worst_joint] +
         "': its inverse bind matrix does not undo its rest transform), so key pose 0, the mesh as its buffers hold "
         "it, is not what viewers show at rest";
}

// The pose at `time_s`: morph with the animated (or default) weights, then skin with
// S_j = G_j x IBM_j; `key_pose` gets the rigid part of every S_j.
Status animatedPose(const Skinned& s, const Clip& clip, double time_s, int mesh_node,
                    const std::vector<Vec3>& base, const std::vector<std::vector<Vec3>>& deltas,
                    std::vector<double> weights, const Influences& influences, const std::string& label,
                    std::vector<Vec3>& pose, std::vector<RigidTransform>& key_pose) {
  std::vector<NodeTransform> nodes = s.rest;
  applyClip(clip, time_s, nodes, mesh_node, weights);
  const std::vector<glm::dmat4> global = globalMatrices(nodes, s.parents);
  const std::size_t bones = s.skin.joint_nodes.size();
  std::vector<BoneTransform> skin(bones);
  key_pose.resize(bones);
  for (std::size_t j = 0; j < bones; ++j) {
    const glm::dmat4 m = global[static_cast<std::size_t>(s.skin.joint_nodes[j])] * s.skin.inverse_bind[j];
    skin[j] = BoneTransform(m);
    double deviation = 0.0;
    const std::optional<RigidTransform> rigid = rigidPart(m, deviation);
    if (!rigid || deviation > kRigidTolerance) {
      return invalidArgument("joint " + std::to_string(j) + " '" + s.skin.skeleton.names[j] + "' in pose '" + label +
                             "' " + (rigid ? "scales or shears by " + messageNumber(deviation) : std::string("reflects")) +
                             "; key poses must be rigid");
    }
    key_pose[j] = *rigid;
  }
  const std::vector<Vec3> morphed = morph(base, deltas, weights);
  pose.resize(morphed.size());
  LbsJob job{morphed, influences, skin, pose};
  return job.run();
}

// The skin of node `mesh_node`. A scale every joint shares in the rest pose (the dequantization of
// KHR_mesh_quantization's integer grid, gltf_dequantize.hpp) moves from the skin into `mesh`.
Result<Skinned> readSkinned(const tinygltf::Model& model, int mesh_node, MeshData& mesh, DecodeBudget& budget) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(mesh_node)];
  Skinned s;
  ODESKIN_ASSIGN_OR_RETURN(s.parents, nodeParents(model));
  ODESKIN_ASSIGN_OR_RETURN(s.rest, restTransforms(model));
  ODESKIN_ASSIGN_OR_RETURN(s.skin, readSkin(model, node.skin, s.parents, budget));
  if (mesh.influence_sets == 0) {
    return parseError(nodeLabel(model, mesh_node) + " has a skin but mesh " + std::to_string(node.mesh) +
                      " has no JOINTS_0/WEIGHTS_0");
  }
  const std::vector<glm::dmat4> global = globalMatrices(s.rest, s.parents);
  std::vector<glm::dmat4> rest_skin;
  for (std::size_t j = 0; j < s.skin.joint_nodes.size(); ++j) {
    rest_skin.push_back(global[static_cast<std::size_t>(s.skin.joint_nodes[j])] * s.skin.inverse_bind[j]);
  }
  ODESKIN_ASSIGN_OR_RETURN(const std::optional<Dequantization> scale,
                           sharedSkinScale(rest_skin, s.skin.skeleton.names, kRigidTolerance,
                                           "skin " + std::to_string(node.skin)));
  if (scale) {
    dequantizeMesh(*scale, mesh);
    dequantizeInverseBinds(*scale, s.skin.inverse_bind);
    placeJoints(s.skin);
  }
  s.rest_warning = restPoseWarning(s, mesh);
  return s;
}

// An unskinned mesh is where its node's world transform puts it: read in world space, as viewers
// show it (a quantized one means something only there, its grid's dequantization being in that
// transform). A mirroring transform turns the triangles inside out, so their corners are reversed.
Status placeUnskinned(const tinygltf::Model& model, int mesh_node, MeshData& mesh) {
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<int> parents, nodeParents(model));
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<NodeTransform> rest, restTransforms(model));
  const glm::dmat4 world = globalMatrices(rest, parents)[static_cast<std::size_t>(mesh_node)];
  if (world == glm::dmat4(1.0)) return okStatus();
  const double det = glm::determinant(glm::dmat3(world));
  if (!std::isfinite(det)) {
    return parseError(nodeLabel(model, mesh_node) + ": its world transform scales the mesh beyond double precision "
                      "(determinant not finite)");
  }
  if (det == 0.0) return parseError(nodeLabel(model, mesh_node) + ": its world transform collapses the mesh (determinant 0)");
  Dequantization d;
  d.linear = glm::dmat3(world);
  d.offset = Vec3(world[3]);
  dequantizeMesh(d, mesh);
  if (det < 0.0) {
    for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) std::swap(mesh.triangles[t + 1], mesh.triangles[t + 2]);
  }
  return okStatus();
}

// An unskinned mesh at `time_s`: morphed with the animated (or default) weights, and moved as its
// node's world transform moves from the rest pose (`base` and `deltas` are already placed there,
// placeUnskinned). odeskin's own baked files are such meshes: a weights animation, no skin.
std::vector<Vec3> unskinnedPose(const Clip& clip, double time_s, int mesh_node, std::span<const NodeTransform> rest,
                                std::span<const int> parents, const std::vector<Vec3>& base,
                                const std::vector<std::vector<Vec3>>& deltas, std::vector<double> weights) {
  std::vector<NodeTransform> nodes(rest.begin(), rest.end());
  applyClip(clip, time_s, nodes, mesh_node, weights);
  const auto node = static_cast<std::size_t>(mesh_node);
  const glm::dmat4 moved = globalMatrices(nodes, parents)[node] * glm::inverse(globalMatrices(rest, parents)[node]);
  std::vector<Vec3> pose = morph(base, deltas, weights);
  if (moved != glm::dmat4(1.0)) {
    for (Vec3& p : pose) p = Vec3(moved * glm::dvec4(p, 1.0));
  }
  return pose;
}

// One pose (with its key pose, for a skinned mesh, and label) per requested time of the requested
// animation. `skinned`: null for an unskinned mesh.
Status appendAnimatedPoses(const tinygltf::Model& model, const GltfPoseRequest& request, const std::string& file,
                           const Skinned* skinned, int mesh_node, const std::vector<Vec3>& base,
                           const std::vector<std::vector<Vec3>>& deltas, const std::vector<double>& default_weights,
                           ExampleSet& out, DecodeBudget& budget) {
  ODESKIN_ASSIGN_OR_RETURN(const int animation, chooseAnimation(model, request.animation));
  ODESKIN_ASSIGN_OR_RETURN(const Clip clip, loadClip(model, animation, budget));
  const std::string name = clip.name.empty() ? "animation " + std::to_string(animation) : clip.name;
  const std::optional<std::pair<double, double>> span = keyframeSpan(clip);
  std::vector<int> parents;
  std::vector<NodeTransform> rest;
  if (skinned == nullptr) {
    ODESKIN_ASSIGN_OR_RETURN(parents, nodeParents(model));
    ODESKIN_ASSIGN_OR_RETURN(rest, restTransforms(model));
  }
  if (!span && !request.times.empty()) {
    out.warnings.push_back(name +
                           " animates no node's translation, rotation, scale or weights, so every pose at a "
                           "time is the nodes' rest pose");
  }
  for (double t : request.times) {
    // glTF holds the end keyframes outside them, so such a pose repeats the end's; legal, but
    // rarely what was meant (a time in frames, or in the wrong clip).
    if (span && (t < span->first || t > span->second)) {
      const double held = t < span->first ? span->first : span->second;
      out.warnings.push_back(formatTime(t) + " s is outside " + name + "'s keyframes (" +
                             formatTime(span->first) + " to " + formatTime(span->second) +
                             " s); glTF holds the end keyframe there, so this pose is the one at " + formatTime(held) +
                             " s");
    }
    const std::string label = file + " " + name + " at " + formatTime(t) + " s";
    if (skinned == nullptr) {
      out.poses.push_back(unskinnedPose(clip, t, mesh_node, rest, parents, base, deltas, default_weights));
      out.pose_labels.push_back(label);
      continue;
    }
    std::vector<Vec3> pose;
    std::vector<RigidTransform> key_pose;
    ODESKIN_TRY(animatedPose(*skinned, clip, t, mesh_node, base, deltas, default_weights, out.rig->influences,
                             label, pose, key_pose));
    out.poses.push_back(std::move(pose));
    out.pose_labels.push_back(label);
    out.rig->key_poses.push_back(std::move(key_pose));
  }
  return okStatus();
}

Result<ExampleSet> buildExamples(const tinygltf::Model& model, const GltfPoseRequest& request, const std::string& file) {
  ODESKIN_TRY(checkRequiredExtensions(model));
  ODESKIN_ASSIGN_OR_RETURN(const int mesh_node, chooseMeshNode(model, request.mesh));
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(mesh_node)];
  if (node.mesh >= static_cast<int>(model.meshes.size())) {
    return parseError(nodeLabel(model, mesh_node) + ": mesh " + std::to_string(node.mesh) + " does not exist");
  }
  if (node.skin >= static_cast<int>(model.skins.size())) {
    return parseError(nodeLabel(model, mesh_node) + ": skin " + std::to_string(node.skin) + " does not exist");
  }

  DecodeBudget budget(model);
  ODESKIN_ASSIGN_OR_RETURN(MeshData mesh, readMesh(model, node.mesh, usesMeshQuantization(model), budget));
  const std::size_t targets = mesh.target_deltas.size();
  for (int k : request.morph_targets) {
    if (k < 0 || static_cast<std::size_t>(k) >= targets) {
      return invalidArgument("morph target " + std::to_string(k) + " requested; mesh " + std::to_string(node.mesh) +
                             " has " + std::to_string(targets));
    }
  }
  std::optional<Skinned> skinned;
  if (node.skin >= 0) {
    ODESKIN_ASSIGN_OR_RETURN(skinned, readSkinned(model, mesh_node, mesh, budget));
  } else {
    ODESKIN_TRY(placeUnskinned(model, mesh_node, mesh));
  }
  const Welded welded = weldEqualPositions(mesh.positions);
  ODESKIN_ASSIGN_OR_RETURN(std::vector<std::vector<Vec3>> deltas, topologyDeltas(mesh, welded));
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<double> default_weights, defaultWeights(model, mesh_node, targets));

  ExampleSet out;
  out.faces = topologyTriangles(mesh.triangles, welded.topology_of_render);
  out.render.topology_of_render = welded.topology_of_render;
  out.render.faces = triangleFaces(mesh.triangles);
  out.rest_positions = morph(welded.positions, deltas, default_weights);
  // A file whose normals break the rules loses only its hard edges, with a word why.
  const auto unusable = std::find_if_not(mesh.normals.begin(), mesh.normals.end(), isUsableNormal);
  if (unusable == mesh.normals.end()) {
    out.render.normals = std::move(mesh.normals);
  } else {
    out.warnings.push_back("NORMAL of vertex " + std::to_string(unusable - mesh.normals.begin()) +
                           " is zero or not finite, so the mesh's hard edges (normal seams) are not kept");
  }
  // One primitive without a material needs no record: that is what the empty list means.
  if (mesh.primitives.size() > 1 || mesh.primitives.front().material >= 0) out.render.primitives = std::move(mesh.primitives);
  if (mesh.uv_warning.empty()) {
    out.render.uvs = std::move(mesh.uvs);
  } else {
    out.warnings.push_back("TEXCOORD_0 is not kept: " + mesh.uv_warning);
  }

  if (skinned && !skinned->rest_warning.empty()) out.warnings.push_back(skinned->rest_warning);
  if (skinned) {
    out.rig.emplace();
    out.rig->skeleton = skinned->skin.skeleton;
    std::string weights_warning;
    ODESKIN_ASSIGN_OR_RETURN(out.rig->influences,
                             topologyInfluences(mesh, welded, static_cast<std::uint32_t>(skinned->skin.joint_nodes.size()),
                                                &weights_warning));
    if (!weights_warning.empty()) out.warnings.push_back(weights_warning);
  }
  const std::vector<RigidTransform> identity(skinned ? skinned->skin.joint_nodes.size() : 0);

  if (request.include_bind_pose) {
    out.poses.push_back(out.rest_positions);
    out.pose_labels.push_back(file + " bind");
    if (out.rig) out.rig->key_poses.push_back(identity);
  }
  if (!request.times.empty()) {
    ODESKIN_TRY(appendAnimatedPoses(model, request, file, skinned ? &*skinned : nullptr, mesh_node, welded.positions,
                                    deltas, default_weights, out, budget));
  }
  for (int k : request.morph_targets) {
    std::vector<double> w = default_weights;
    w[static_cast<std::size_t>(k)] = 1.0;
    out.poses.push_back(morph(welded.positions, deltas, w));
    out.pose_labels.push_back(file + " target " + std::to_string(k));
    if (out.rig) out.rig->key_poses.push_back(identity);
  }
  if (out.rig) ODESKIN_TRY(validateRig(*out.rig, out.rest_positions.size(), out.poses.size()));
  return out;
}

// The request's own checks, before the file is read.
Status checkRequest(const std::string& source, const GltfPoseRequest& request) {
  const std::size_t poses =
      (request.include_bind_pose ? 1 : 0) + request.times.size() + request.morph_targets.size();
  const std::size_t needed = std::max<std::size_t>(request.min_poses, 1);
  if (poses < needed) {
    return invalidArgument(source + ": " + std::to_string(poses) + " example poses requested, at least " +
                           std::to_string(needed) + " are needed");
  }
  for (double t : request.times) {
    if (!std::isfinite(t)) return invalidArgument(source + ": a requested time is not finite");
  }
  return okStatus();
}

Result<ExampleSet> examplesNamingSource(const tinygltf::Model& model, const GltfPoseRequest& request,
                                        const std::string& source, const std::string& file) {
  Result<ExampleSet> examples = buildExamples(model, request, file);
  if (!examples.ok()) return Status(examples.status().code(), source + ": " + examples.status().message());
  for (std::string& w : examples->warnings) w = source + ": " + w;
  return examples;
}

}  // namespace

Result<ExampleSet> readGltfExamples(const std::filesystem::path& path, const GltfPoseRequest& request) {
  ODESKIN_TRY(checkRequest(path.string(), request));
  ODESKIN_ASSIGN_OR_RETURN(const tinygltf::Model model, loadModel(path));
  return examplesNamingSource(model, request, path.string(), path.filename().string());
}

Result<ExampleSet> parseGltfExamples(const std::string& bytes, const std::string& source,
                                     const GltfPoseRequest& request) {
  ODESKIN_TRY(checkRequest(source, request));
  ODESKIN_ASSIGN_OR_RETURN(const tinygltf::Model model, loadModelFromMemory(bytes, source));
  return examplesNamingSource(model, request, source, std::filesystem::path(source).filename().string());
}

}  // namespace odeskin

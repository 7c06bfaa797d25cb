// SPDX-License-Identifier: MIT
// glTF 2.0 (.gltf / .glb, through tinygltf) as example poses of a skinned mesh: the skin (joints,
// inverse bind matrices, JOINTS_0/WEIGHTS_0 in every allowed component type, normalised), poses
// sampled from an animation at given times (node TRS, LINEAR/STEP/CUBICSPLINE) and/or morph targets
// as poses. Sparse accessors are applied; vertices split at UV/normal seams are welded into topology
// vertices and the render layout is kept (ExampleSet::render).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "example_set.hpp"

namespace odeskin {

struct GltfPoseRequest {
  std::string mesh;                 // mesh node name, or empty: the first skinned mesh node (else the first mesh)
  std::string animation;            // name or index as text; empty: the first animation
  std::vector<double> times;        // seconds: one example pose per time (the animated joints and weights)
  std::vector<int> morph_targets;   // each: the bind mesh with that target's weight set to 1, in bind space
  bool include_bind_pose = true;    // pose 0 is the bind mesh (the mesh with its default morph weights)
  std::size_t min_poses = 2;        // fewest poses accepted: fitting needs 2, drawing one pose 1
};

// Example poses of one mesh, in this order: the bind pose (if asked), one pose per time, one per
// morph target; labels "<file> bind", "<file> <animation name> at <t> s" ("animation <i>" when it
// has no name), "<file> target <k>".
//
// Geometry: every primitive of the node's mesh (TRIANGLES only, indexed or not), concatenated into
// render vertices; render vertices with exactly equal POSITION are welded into topology vertices
// (see gltf_weld.hpp for why exact): rest_positions / faces are over topology vertices (triangles
// that weld to a segment are left out), render = {render vertex -> topology vertex, all triangles
// over render vertices, and every render vertex's NORMAL when all primitives have it, as stored:
// it tells hard edges from UV seams}. A skinned mesh is read in mesh space: glTF ignores its node's
// transform (its joints place it). An unskinned mesh is read in world space, as viewers show it:
// its node's world transform applies to positions, deltas and normals (a mirroring one reverses the
// triangles' corners, so they keep facing out). Bind space is that space with the
// default morph weights applied (node.weights, else mesh.weights, else zeros): rest_positions.
//
// Poses at times are computed as glTF specifies: morph (animated "weights" of the mesh node, else
// the defaults), then linear blend skinning with S_j = G_j x IBM_j, G_j the joint node's global
// transform under the animation's translation/rotation/scale channels. An unskinned mesh at a time
// is morphed the same way and moved as its node's world transform moves from the rest pose (a baked
// file of odeskin's is a weights animation of such a mesh). Morph-target and bind poses are not skinned.
//
// Rig (skinned meshes only): skeleton from the skin's joints (gltf_skin.hpp), influences from
// JOINTS_n/WEIGHTS_n of each topology vertex's first render vertex, normalised per vertex; key
// poses: the rigid part of every S_j (polar decomposition), identity for bind and morph poses.
//
// Warnings (ExampleSet::warnings, naming the file): a time outside the animation's keyframes
// (glTF holds the end keyframe there, so the pose repeats it), an animation that moves nothing
// odeskin reads, a zero or non-finite NORMAL (the normals are then dropped).
//
// Errors name the file. kInvalidArgument: fewer than max(min_poses, 1) poses, a non-finite time, an
// unknown animation (the message lists the available ones), a morph target out of range,
// an unknown mesh node name, an extensionsRequired entry odeskin does not handle (named; see
// gltf_load.hpp), a skin matrix that scales or shears by more than 1e-4 (naming joint and pose).
// kIoError: a missing or unreadable file. kParseError: tinygltf refuses the file (its message
// follows), or the data break the glTF rules odeskin relies on (accessor bounds and formats,
// joint indices, zero weight sums, welded copies of a vertex with different weights or deltas, an
// unskinned mesh node whose world transform collapses it...).
Result<ExampleSet> readGltfExamples(const std::filesystem::path& path, const GltfPoseRequest& request);

// readGltfExamples on a .gltf or .glb held in memory (GLB by its first four bytes); `source` stands
// for the path in the messages and labels. Buffers must be inside it (GLB chunk or data: URI):
// there is no folder to find external files in, and no file is read or written.
Result<ExampleSet> parseGltfExamples(const std::string& bytes, const std::string& source,
                                     const GltfPoseRequest& request);

}  // namespace odeskin

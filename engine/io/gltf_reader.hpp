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
  std::vector<double> times;        // seconds: one example pose per time (skinned with the animated joints)
  std::vector<int> morph_targets;   // each: the bind mesh plus that target at weight 1, skinned at the bind pose
  bool include_bind_pose = true;    // pose 0 is the bind mesh (the mesh with its default morph weights)
};

// Example poses of one mesh. Pose positions are computed as glTF specifies (morph, then skin with
// joint global transform x inverse bind matrix); the rig's key poses are those joint matrices as
// rigid transforms (kInvalidArgument naming the joint if one scales or shears beyond 1e-4).
// Fewer than 2 poses, a missing skin when times are asked for, an unknown animation, an
// extensionsRequired entry we do not implement (named), a bad accessor: errors naming the file.
Result<ExampleSet> readGltfExamples(const std::filesystem::path& path, const GltfPoseRequest& request);

}  // namespace odeskin

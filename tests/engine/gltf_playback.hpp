// SPDX-License-Identifier: MIT
// glTF 2.0 read and played independently of odeskin's writer, for the export tests: accessors with
// sparse substitution, LINEAR / STEP / CUBICSPLINE samplers with quaternion normalisation, the node
// hierarchy, morph targets, then linear skinning with joint matrix = world(joint) * IBM (the
// skinned mesh node's own transform ignored, as the specification says).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "engine/core/types.hpp"

namespace odeskin::testing {

// Every component of every element of accessor `index`, sparse values substituted (spec 3.6.2.3).
std::vector<double> readAccessor(const tinygltf::Model& m, int index);

// One animation channel: its target and its sampler's keys and values, decoded.
struct Channel {
  int node = -1;
  std::string path;
  std::string interpolation;
  std::vector<double> input, output;
};

// A decoded export: the mesh of its one skinned node, played at any time in seconds.
class GltfPlayback {
 public:
  explicit GltfPlayback(const std::filesystem::path& path);

  bool ok() const { return ok_ && mesh_node_ >= 0; }
  const tinygltf::Model& model() const { return model_; }
  const std::vector<Channel>& channels() const { return channels_; }
  int meshNode() const { return mesh_node_; }
  std::size_t vertexCount() const { return base_.size() / 3; }
  const std::vector<double>& joints() const { return joints_; }
  const std::vector<double>& weights() const { return weights_; }
  const std::vector<double>& inverseBinds() const { return ibm_; }

  bool hasTargetNormals() const { return !normal_targets_.empty(); }
  // Plays LINEAR rotations as Blender does (sample's `nlerp`) instead of glTF's slerp.
  void playRotationsAsNlerp(bool on) { nlerp_rotations_ = on; }

  std::vector<Vec3> positionsAt(double seconds) const;

  // The unit NORMALs before skinning: the base plus the weighted target deltas (when
  // `morph_normals` and the file has them), normalised as viewers do.
  std::vector<Vec3> bindNormalsAt(double seconds, bool morph_normals = true) const;

  // Skinned as three.js and Filament do: the blended joint matrix's linear part, then normalised.
  std::vector<Vec3> normalsAt(double seconds, bool morph_normals) const;

 private:
  // The animated state at one time: morph weights and the matrix that places each vertex.
  struct Pose {
    const GltfPlayback* file = nullptr;
    std::vector<double> morph;
    std::vector<glm::dmat4> joint_matrices;
    glm::dmat4 mesh_world{1.0};

    glm::dmat4 skin(std::size_t i) const;
  };

  static Vec3 at(const std::vector<double>& xyz, std::size_t i) { return Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]); }

  Pose poseAt(double seconds) const;

  bool ok_ = false;
  tinygltf::Model model_;
  std::vector<int> parents_;
  int mesh_node_ = -1;
  std::vector<double> base_;
  std::vector<std::vector<double>> targets_;
  std::vector<double> normals_;
  std::vector<std::vector<double>> normal_targets_;
  std::vector<double> default_weights_;
  std::vector<int> joint_nodes_;
  std::vector<double> ibm_, joints_, weights_;
  std::vector<Channel> channels_;
  bool nlerp_rotations_ = false;
};

}  // namespace odeskin::testing

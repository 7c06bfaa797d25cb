// SPDX-License-Identifier: MIT
// Puts the compact export together as one glTF 2.0 binary (ECOSYSTEM.md 2): the skinned mesh node
// at the scene root with identity transform (the spec ignores its transform; the validator warns on
// any), a skeleton root node holding the joint nodes, the skin with inverse bind matrices J_b^-1,
// morph targets (POSITION deltas with min/max, NORMAL deltas when given, sparse where that is
// smaller, names in mesh.extras.targetNames), and one animation "odeskin": the "weights" channel
// of the mesh node and translation and rotation channels of every joint, CUBICSPLINE or LINEAR as
// the keys were placed, times in seconds (t * segment_seconds) and tangents per second.
#pragma once

#include <filesystem>
#include <string>

#include "../core/status.hpp"
#include "../io/gltf_materials.hpp"
#include "../io/gltf_quantized.hpp"
#include "export_mesh.hpp"
#include "mode_targets.hpp"
#include "skeleton_keys.hpp"
#include "target_normals.hpp"
#include "weight_keys.hpp"

namespace odeskin {

struct GlbContents {
  const DeformAsset* asset = nullptr;
  const ExportMesh* mesh = nullptr;
  const ModeTargetSet* targets = nullptr;
  const WeightKeys* weights = nullptr;
  const SkeletonKeys* skeleton = nullptr;
  const TargetNormals* normals = nullptr;  // NORMAL deltas for every target, or none
  const gltf::MaterialLibrary* materials = nullptr;  // to dress the primitives with, or none
  std::string generator = "odeskin export";
  // KHR_mesh_quantization (gltf_quantized.hpp): 16-bit positions and position deltas on a
  // grid over the base shape's box, 8-bit normals and 16-bit normal deltas. The skeleton root node
  // then scales grid steps to mesh units, and the joints' translations and inverse bind matrices
  // are in grid steps (no scale in any inverse bind matrix, which Blender 3.4 would drop).
  bool quantize = false;
};

struct GlbSummary {
  std::size_t morph_targets = 0;
  std::size_t sparse_targets = 0;  // written as sparse accessors
  std::size_t buffer_bytes = 0;
  QuantizationCost quantization;  // at the weight keys; zeros unless quantized
};

// kInvalidArgument for more than 65536 joints, values that are not finite, key times that are not
// increasing once rounded to float32, or a buffer of 2 GiB or more (most tools break there);
// writeGlbAtomically's kIoError naming `path`.
Result<GlbSummary> writeExportGlb(const std::filesystem::path& path, const GlbContents& contents);

}  // namespace odeskin

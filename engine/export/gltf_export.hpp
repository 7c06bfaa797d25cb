// SPDX-License-Identifier: MIT
// `odeskin export`: a DeformAsset as one glTF 2.0 binary that any viewer plays with the motion of
// odeskin's player (issue 4.1, ECOSYSTEM.md 2, PIPELINE.md 3).
//
// Compact form (bind-space residual with linear blend skinning, the default fit): the base shape
// X + r^0, its skin (joints, inverse bind matrices, at most 4 influences per vertex), the skeletal
// animation of the player's bone transforms, and the analytic deformation as morph targets (one per
// segment, material, mode and gamma/psi, plus one key correction per segment, mode_targets.hpp)
// whose weights follow the time basis as CUBICSPLINE (or LINEAR) keys in [0, 1] (weight_keys.hpp). glTF applies
// morph targets before skinning and skins linearly, which is exactly the reference kernel's
// bind-space form; a posed-space residual or dual-quaternion skinning cannot be written that way.
//
// Baked form (--bake, and the fallback for the other assets): one morph target per frame of the
// played animation with LINEAR cross-fades between consecutive frames (gltf_baked_writer.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "../core/result.hpp"
#include "../offline/deform_asset.hpp"
#include "key_interpolation.hpp"

namespace odeskin {

struct GltfExportOptions {
  // Position error allowed from sampling the morph weights into keys, and separately from sampling
  // the skeleton, each as a fraction of the base shape's longest bounding-box side.
  double tolerance = 1e-5;
  bool bake = false;        // write the baked form even when the compact one is possible
  // Compact form: the weight and skeleton keys' interpolation (key_interpolation.hpp). LINEAR keys
  // meet the same tolerance with more keys, for importers that drop CUBICSPLINE tangents.
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
  // Compact form: NORMAL deltas in every morph target (target_normals.hpp), so viewers shade the
  // corrective deformation; without them they shade the skinned base shape. About doubles the
  // targets' bytes.
  bool target_normals = true;
  // KHR_mesh_quantization (gltf_quantized.hpp): 16-bit positions and position deltas, 8-bit
  // normals, 16-bit normal deltas; about two thirds of the bytes. The rounding's error is measured
  // into the report, apart from `tolerance`'s budget.
  bool quantize = false;
  // A glTF file whose materials, textures and images dress the output (gltf_materials.hpp): the
  // file the asset was fitted from, or any file with one material. Empty: no materials.
  std::filesystem::path materials;
  double bake_fps = 30.0;   // frames per second of the baked form (the last key is always a frame)
  std::string generator = "odeskin export";
  // Called with a stage name and its completed fraction in [0, 1] (for progress bars).
  std::function<void(std::string_view stage, double fraction)> progress;
};

struct GltfExportReport {
  bool baked = false;
  std::string bake_reason;         // why the compact form was not possible; empty when it was or --bake
  double box = 0.0;                // longest bounding-box side of the base shape (absolute)
  std::size_t vertices = 0;        // written (render vertices for a glTF-fitted asset)
  std::size_t morph_targets = 0;
  std::uintmax_t bytes = 0;        // of the written file
  std::size_t materials = 0;       // copied from options.materials (0 without)
  std::size_t images = 0;          // embedded with them
  // Materials whose textures were left out because the asset has no texture coordinates (an OBJ
  // fit, or a glTF whose TEXCOORD_0 could not be kept): gltf::dropTextures.
  std::size_t untextured_materials = 0;
  // Quantized only: the writer's QuantizationCost (gltf_quantized.hpp; at the weight keys, or a
  // bake's frames), its lengths as fractions of the box.
  bool quantized = false;
  double quantization_error = 0.0;
  double quantization_step = 0.0;
  double normal_quantization_p99_degrees = 0.0;
  double normal_quantization_max_degrees = 0.0;
  std::size_t float_deltas = 0;
  // Compact form only:
  std::size_t sparse_targets = 0;  // written as sparse accessors
  std::size_t merged_fields = 0;   // (material, mode) fields merged into a target with the same curve
  KeyInterpolation interpolation = KeyInterpolation::kCubicSpline;
  std::size_t weight_keys = 0;
  std::size_t skeleton_keys = 0;
  std::size_t joints = 0;
  double max_weight_error = 0.0;         // max |keyed - exact| of any morph weight (weights in [0, 1])
  double weight_position_error = 0.0;    // implied position error bound from it, / box
  double skeleton_position_error = 0.0;  // measured bound from the skeleton keys, / box
  double player_deviation = 0.0;         // mid-segment deviation bound from the player (mode_targets.hpp), / box
  bool target_normals = false;           // the targets carry NORMAL deltas
  // Their deviation from the exact bind-space normals between keys, degrees (TargetNormals).
  double normal_mean_degrees = 0.0;
  double normal_p99_degrees = 0.0;       // 99% of the vertices stay within this at every checked time
  double normal_max_degrees = 0.0;
  std::size_t normal_key_blended = 0;    // (vertex, segment) pairs that blend the two keys' normals only
  std::uint32_t max_influences = 0;      // in the asset; more than 4 are pruned
  std::uint32_t pruned_vertices = 0;
  double prune_error = 0.0;              // max LBS error of the pruning over the key poses, / box
  // Baked form only:
  std::size_t frames = 0;
};

// Empty when the compact form can represent `asset` exactly, else the reason (for the user).
std::string compactExportProblem(const DeformAsset& asset);

// Writes `path` through a temporary file and rename (no half-written file on failure). Errors:
// readMaterialLibrary's and primitiveMaterials' for options.materials;
// kInvalidArgument for options out of range (tolerance not in [1e-8, 0.01], fps not in (0, 1000]),
// a mesh beyond glTF's float32 range (gltf::checkFloat32Positions) and for assets the writers
// reject; DeformPlayer::create's errors; kIoError naming `path`.
Result<GltfExportReport> exportGltf(const DeformAsset& asset, const std::filesystem::path& path,
                                    const GltfExportOptions& options);

}  // namespace odeskin

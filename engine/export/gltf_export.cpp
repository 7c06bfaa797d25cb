// SPDX-License-Identifier: MIT
#include "gltf_export.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <numbers>
#include <system_error>

#include "../core/number_text.hpp"
#include "../io/gltf_buffer_builder.hpp"
#include "../offline/deform_player.hpp"
#include "../offline/residual_fit.hpp"
#include "baked_export.hpp"
#include "glb_assembly.hpp"

namespace odeskin {
namespace {

// Keys closer than this (in t) would collide once written as float32 seconds: 16 float32 ulps at
// the animation's end, and never below 1e-5 of a segment.
double minKeyGap(const DeformAsset& asset) {
  const double end_seconds = static_cast<double>(asset.segments.size()) * asset.segment_seconds;
  const double ulp = std::nextafter(static_cast<float>(end_seconds), std::numeric_limits<float>::infinity()) -
                     static_cast<float>(end_seconds);
  return std::max(1e-5, 16.0 * ulp / asset.segment_seconds);
}

std::vector<std::vector<BoneTransform>> keyBones(const DeformAsset& asset) {
  std::vector<std::vector<BoneTransform>> out;
  for (const std::vector<RigidTransform>& key : asset.key_poses) {
    std::vector<BoneTransform>& bones = out.emplace_back();
    // cppcheck-suppress invalidContainerReference ; false positive: bones is out.back(), and out does not grow inside this loop
    for (const RigidTransform& bone : key) bones.push_back(bone.matrix());
  }
  return out;
}

// The report's quantization figures: the writer's, lengths as fractions of the box.
void reportQuantization(const QuantizationCost& cost, GltfExportReport& report) {
  const double box = report.box > 0.0 ? report.box : 1.0;
  report.quantized = true;
  report.quantization_error = cost.position_error / box;
  report.quantization_step = cost.step / box;
  report.normal_quantization_p99_degrees = cost.normal_p99_degrees;
  report.normal_quantization_max_degrees = cost.normal_max_degrees;
  report.float_deltas = cost.float_deltas;
}

std::uintmax_t fileSize(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  return ec ? 0 : size;
}

}  // namespace

std::string compactExportProblem(const DeformAsset& asset) {
  if (asset.residual_space != ResidualSpace::kBind) {
    return "its residual is in posed space (added after skinning), but glTF applies morph targets before skinning";
  }
  if (asset.skinning != SkinningMode::kLinear) {
    return "it uses dual-quaternion skinning, but glTF skins by linear blending";
  }
  return {};
}

Result<GltfExportReport> exportGltf(const DeformAsset& asset, const std::filesystem::path& path,
                                    const GltfExportOptions& o) {
  // Below 1e-8 of the box float32 positions round more than the keys err, and keys only multiply.
  if (!(o.tolerance >= 1e-8 && o.tolerance <= 0.01)) {
    return invalidArgument("export: tolerance " + messageNumber(o.tolerance) + " outside [1e-8, 0.01]");
  }
  if (!(o.bake_fps > 0.0 && o.bake_fps <= 1000.0)) {
    return invalidArgument("export: bake fps " + messageNumber(o.bake_fps) + " outside (0, 1000]");
  }
  ODESKIN_ASSIGN_OR_RETURN(const DeformPlayer player, DeformPlayer::create(asset));
  std::optional<gltf::MaterialLibrary> materials;
  if (!o.materials.empty()) {
    ODESKIN_ASSIGN_OR_RETURN(materials, gltf::readMaterialLibrary(o.materials));
    // Checked before anything is computed; the writers ask again for the primitives they write.
    ODESKIN_TRY(gltf::primitiveMaterials(*materials, asset.render.primitives, 1).status());
  }
  GltfExportReport report;
  if (materials && asset.render.uvs.empty()) report.untextured_materials = gltf::dropTextures(*materials);
  const gltf::MaterialLibrary* library = materials ? &*materials : nullptr;
  if (library != nullptr) {
    report.materials = library->materials.size();
    report.images = library->images.size();
  }
  auto progress = [&](std::string_view stage, double fraction) {
    if (o.progress) o.progress(stage, fraction);
  };
  std::vector<Vec3> base(asset.vertexCount());
  for (std::size_t i = 0; i < base.size(); ++i) base[i] = asset.rest_positions[i] + asset.segments.front().base_residuals[i];
  report.box = longestBoxSide(base);
  ODESKIN_TRY(gltf::checkFloat32Positions(base, "export"));

  report.bake_reason = compactExportProblem(asset);
  if (o.bake || !report.bake_reason.empty()) {
    report.baked = true;
    ODESKIN_ASSIGN_OR_RETURN(const BakedExport baked, writeBakedExport(asset, player, path, o.bake_fps, o.generator,
                                                                        o.progress, library, o.quantize));
    report.frames = baked.frames;
    if (o.quantize) reportQuantization(baked.quantization, report);
    report.vertices = baked.vertices;
    report.morph_targets = baked.frames - 1;
    report.bytes = fileSize(path);
    return report;
  }

  const double box = report.box > 0.0 ? report.box : 1.0;
  progress("targets", 0.0);
  ModeTargetOptions target_options;
  target_options.keep_zero_corrections = o.target_normals;
  ODESKIN_ASSIGN_OR_RETURN(const ModeTargetSet targets, buildModeTargets(asset, player, target_options));
  TargetNormals normals;
  if (o.target_normals) {
    progress("target normals", 0.0);
    ODESKIN_ASSIGN_OR_RETURN(normals, buildTargetNormals(asset, base, targets));
  }
  progress("weight keys", 0.0);
  WeightKeyOptions weight_options;
  weight_options.position_tolerance = o.tolerance * box;
  weight_options.min_key_gap = minKeyGap(asset);
  weight_options.interpolation = o.interpolation;
  ODESKIN_ASSIGN_OR_RETURN(const WeightKeys weights,
                           placeWeightKeys(targets, static_cast<std::uint32_t>(asset.segments.size()), weight_options));
  progress("skeleton keys", 0.0);
  SkeletonKeyOptions skeleton_options;
  skeleton_options.position_tolerance = o.tolerance * box;
  skeleton_options.min_key_gap = weight_options.min_key_gap;
  skeleton_options.interpolation = o.interpolation;
  ODESKIN_ASSIGN_OR_RETURN(const SkeletonKeys skeleton, placeSkeletonKeys(asset, player, skeleton_options));
  const std::vector<std::vector<BoneTransform>> key_bones = keyBones(asset);
  ODESKIN_ASSIGN_OR_RETURN(const ExportMesh mesh, buildExportMesh(asset, base, key_bones));
  progress("writing", 0.0);
  GlbContents contents{&asset,    &mesh, &targets, &weights, &skeleton, o.target_normals ? &normals : nullptr,
                       library, o.generator, o.quantize};
  ODESKIN_ASSIGN_OR_RETURN(const GlbSummary summary, writeExportGlb(path, contents));
  progress("writing", 1.0);

  report.vertices = mesh.positions.size();
  report.morph_targets = summary.morph_targets;
  report.sparse_targets = summary.sparse_targets;
  report.merged_fields = targets.merged_fields;
  report.interpolation = o.interpolation;
  report.weight_keys = weights.weightCount() > 0 ? weights.times.size() : 0;
  report.skeleton_keys = skeleton.times.size();
  report.joints = asset.bone_count;
  report.max_weight_error = weights.max_weight_error;
  report.weight_position_error = weights.max_position_error / box;
  report.skeleton_position_error = skeleton.max_position_error / box;
  report.player_deviation = targets.max_player_deviation / box;
  report.target_normals = o.target_normals;
  constexpr double kDegrees = 180.0 / std::numbers::pi;
  report.normal_mean_degrees = normals.mean_angle * kDegrees;
  report.normal_p99_degrees = normals.vertex_p99_angle * kDegrees;
  report.normal_max_degrees = normals.max_angle * kDegrees;
  report.normal_key_blended = normals.key_blended;
  report.max_influences = mesh.max_influences;
  report.pruned_vertices = mesh.pruned_vertices;
  report.prune_error = mesh.max_prune_error / box;
  if (o.quantize) reportQuantization(summary.quantization, report);
  report.bytes = fileSize(path);
  return report;
}

}  // namespace odeskin

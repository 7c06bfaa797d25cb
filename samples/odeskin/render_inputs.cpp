// SPDX-License-Identifier: MIT
#include "render_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "asset_playback.hpp"
#include "engine/core/number_text.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/io/obj_reader.hpp"
#include "file_extension.hpp"

namespace odeskin {
namespace {

Result<RenderInput> loadAssetInput(const std::filesystem::path& path, const RenderInputOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(DeformAsset asset, loadAsset(path));
  const double t = options.t.value_or(0.0);
  const double t_end = static_cast<double>(asset.key_poses.size() - 1);
  if (!(t >= 0.0 && t <= t_end)) {
    return outOfRange(path.string() + ": --t " + numberText(t) + " is outside [0, " + numberText(t_end) + "] (" +
                      std::to_string(asset.key_poses.size()) + " key poses)");
  }
  if (options.skin_only) asset = skinOnlyAsset(asset);
  Result<AssetPlayback> playback = AssetPlayback::create(asset, PlaybackOptions{}, nullptr);
  if (!playback.ok()) return Status(playback.status().code(), path.string() + ": " + playback.status().message());
  RenderInput input;
  input.path = path;
  // Built with append: GCC 12's -Wrestrict misfires on chained std::string + here.
  input.label = path.filename().string();
  input.label.append(" t=").append(numberText(t));
  if (options.skin_only) input.label.append(" LBS");
  ODESKIN_TRY(playback->positionsAt(t, input.positions));
  input.faces = asset.faces;
  input.curves = asset.curves;
  if (!asset.render.obj_order) input.topology_of_render = asset.render.topology_of_render;
  return input;
}

Result<RenderInput> loadGltfInput(const std::filesystem::path& path, const RenderInputOptions& options) {
  GltfPoseRequest request;
  request.min_poses = 1;
  request.include_bind_pose = !options.t.has_value();
  if (options.t) request.times = {*options.t};
  ODESKIN_ASSIGN_OR_RETURN(ExampleSet examples, readGltfExamples(path, request));
  RenderInput input;
  input.path = path;
  input.label = path.filename().string();
  if (options.t) input.label.append(" ").append(numberText(*options.t)).append(" s");
  input.positions = std::move(examples.poses.front());
  input.faces = std::move(examples.faces);
  input.warnings = std::move(examples.warnings);
  input.topology_of_render = std::move(examples.render.topology_of_render);
  return input;
}

}  // namespace

Result<RenderInputKind> renderInputKind(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".obj") return RenderInputKind::kObj;
  if (isGltfFile(path)) return RenderInputKind::kGltf;
  if (ext == ".odsk") return RenderInputKind::kAsset;
  return invalidArgument(path.string() + ": unknown input format '" + ext + "' (expected .obj, .gltf, .glb or .odsk)");
}

Result<RenderInput> loadRenderInput(const std::filesystem::path& path, const RenderInputOptions& options) {
  ODESKIN_ASSIGN_OR_RETURN(const RenderInputKind kind, renderInputKind(path));
  if (options.skin_only && kind != RenderInputKind::kAsset) {
    return invalidArgument(path.string() + ": only a .odsk asset can be drawn skin-only (LBS)");
  }
  if (kind == RenderInputKind::kAsset) return loadAssetInput(path, options);
  if (kind == RenderInputKind::kGltf) return loadGltfInput(path, options);
  ODESKIN_ASSIGN_OR_RETURN(ObjMesh mesh, readObj(path));
  RenderInput input;
  input.path = path;
  input.label = path.filename().string();
  input.positions = std::move(mesh.positions);
  input.faces = std::move(mesh.faces);
  return input;
}

std::vector<Vec3> inVertexOrderOf(const RenderInput& input, const RenderInput& other) {
  const std::size_t count = input.positions.size();
  if (other.positions.size() != count && input.topology_of_render.size() == other.positions.size()) {
    std::vector<Vec3> welded(count);
    for (std::size_t r = 0; r < other.positions.size(); ++r) welded[input.topology_of_render[r]] = other.positions[r];
    return welded;
  }
  if (other.positions.size() != count && other.topology_of_render.size() == count) {
    std::vector<Vec3> split(count);
    for (std::size_t r = 0; r < count; ++r) split[r] = other.positions[other.topology_of_render[r]];
    return split;
  }
  return other.positions;
}

DeformAsset skinOnlyAsset(const DeformAsset& asset) {
  DeformAsset out = asset;
  for (DeformSegment& segment : out.segments) {
    std::fill(segment.base_residuals.begin(), segment.base_residuals.end(), Vec3(0.0));
    std::fill(segment.coefficients.begin(), segment.coefficients.end(), Vec3(0.0));
    std::fill(segment.rates.begin(), segment.rates.end(), Vec3(0.0));
    std::fill(segment.remainders.begin(), segment.remainders.end(), Vec3(0.0));
  }
  return out;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// The meshes `odeskin render` draws, from any of the files odeskin reads: an OBJ (as it is), a
// glTF/GLB (its mesh at the bind pose, or skinned at an animation time), or a .odsk asset played
// at a global time with the CPU reference (optionally with the residual switched off, plain LBS).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/iso_curve.hpp"
#include "engine/core/result.hpp"
#include "engine/core/types.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin {

enum class RenderInputKind { kObj, kGltf, kAsset };

// By extension, ignoring case: .obj, .gltf/.glb, .odsk. kInvalidArgument naming the file otherwise.
Result<RenderInputKind> renderInputKind(const std::filesystem::path& path);

struct RenderInputOptions {
  // Asset: global time in [0, K-1] (default 0). glTF: seconds into the animation (default: the
  // bind pose). OBJ: ignored.
  std::optional<double> t;
  bool skin_only = false;  // asset: skinning without the analytic residual (what LBS alone gives)
};

struct RenderInput {
  std::filesystem::path path;
  std::string label;               // "horse.odsk t=0.5 LBS", "horse-03.obj"
  std::vector<Vec3> positions;     // world space
  FaceList faces;                  // over positions (welded topology for glTF and assets)
  std::vector<IsoCurve> curves;    // assets: the iso-parametric curves, on these vertices
  std::vector<std::string> warnings;  // the reader's (ExampleSet::warnings), naming the file
  // glTF inputs and assets fitted from glTF: the welded vertex of each render vertex (UV and normal
  // seams split vertices there); empty when the input has no such layout.
  std::vector<std::uint32_t> topology_of_render;
};

// `other`'s positions in `input`'s vertex order, for per-vertex errors between them. They are
// `other.positions` unless the two differ only by a glTF render layout: an OBJ that `play` wrote
// from a seamed asset holds a vertex per render vertex, where the asset and its glTF hold one per
// welded vertex. Then one side is welded (any copy of a vertex: they have one position) or split
// to the other's order.
std::vector<Vec3> inVertexOrderOf(const RenderInput& input, const RenderInput& other);

// Errors name the file: readObj's, readGltfExamples' and loadAsset's; kOutOfRange when an asset's t
// lies outside [0, K-1] (naming the range); kInvalidArgument for skin_only on a non-asset.
Result<RenderInput> loadRenderInput(const std::filesystem::path& path, const RenderInputOptions& options);

// The asset with every residual term zeroed (base residuals, Fourier coefficients and rates,
// sparse remainders): playing it gives linear blend (or dual-quaternion) skinning of the bind mesh
// with the same interpolated bones, the baseline the analytic residual improves on.
DeformAsset skinOnlyAsset(const DeformAsset& asset);

}  // namespace odeskin

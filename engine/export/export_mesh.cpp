// SPDX-License-Identifier: MIT
#include "export_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "../core/render_primitives.hpp"
#include "../io/gltf_buffer_builder.hpp"

namespace odeskin {
namespace {

// Float32 weights whose float32 sum (in slot order, as the glTF-Validator adds them) is 1: the
// largest weight absorbs the rounding of the others.
std::array<float, kExportInfluences> float32Weights(std::span<const double> weights) {
  std::array<float, kExportInfluences> out{};
  double sum = 0.0;
  for (double w : weights) sum += w;
  for (std::size_t k = 0; k < weights.size(); ++k) out[k] = static_cast<float>(weights[k] / sum);
  for (int pass = 0; pass < 4; ++pass) {
    float total = 0.0f;
    for (float w : out) total += w;
    if (total == 1.0f) break;
    out[0] += 1.0f - total;
  }
  return out;
}

// The same bone twice in a row would be two non-zero weights of one joint (a validator error):
// such entries are summed.
Influences mergeDuplicateBones(const Influences& in) {
  Influences out;
  out.offsets.assign(1, 0);
  for (std::size_t i = 0; i + 1 < in.offsets.size(); ++i) {
    const std::size_t row = out.bones.size();
    for (std::uint32_t k = in.offsets[i]; k < in.offsets[i + 1]; ++k) {
      auto same = std::find(out.bones.begin() + static_cast<std::ptrdiff_t>(row), out.bones.end(), in.bones[k]);
      if (same != out.bones.end()) {
        out.weights[static_cast<std::size_t>(same - out.bones.begin())] += in.weights[k];
      } else {
        out.bones.push_back(in.bones[k]);
        out.weights.push_back(in.weights[k]);
      }
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

}  // namespace

Result<ExportMesh> buildExportMesh(const DeformAsset& asset, std::span<const Vec3> base_positions,
                                   std::span<const std::vector<BoneTransform>> key_bones) {
  const std::size_t v_count = asset.vertexCount();
  if (base_positions.size() != v_count) {
    return invalidArgument("export: " + std::to_string(base_positions.size()) + " base positions for " +
                           std::to_string(v_count) + " vertices");
  }
  ExportMesh mesh;
  const FaceList& faces = outputFaces(asset);
  if (asset.render.empty()) {
    mesh.source_vertex.resize(v_count);
    for (std::size_t i = 0; i < v_count; ++i) mesh.source_vertex[i] = static_cast<std::uint32_t>(i);
  } else {
    mesh.source_vertex = asset.render.topology_of_render;
  }
  std::size_t first_face = 0;
  for (const RenderPrimitive& primitive : primitiveRuns(asset.render.primitives, faces.faceCount())) {
    const std::vector<std::uint32_t> run = gltf::fanTriangles(faces, first_face, primitive.face_end);
    first_face = primitive.face_end;
    mesh.triangles.insert(mesh.triangles.end(), run.begin(), run.end());
    mesh.primitive_ends.push_back(static_cast<std::uint32_t>(mesh.triangles.size() / 3));
  }
  for (std::uint32_t index : mesh.triangles) {
    if (index >= mesh.source_vertex.size()) return invalidArgument("export: a face uses vertex " + std::to_string(index));
  }

  // Welded, so UV seams of a glTF input do not show as creases; across its hard edges, each side's own.
  mesh.normals = outputNormals(asset, base_positions);
  mesh.uvs = asset.render.uvs;
  mesh.positions.reserve(mesh.source_vertex.size());
  for (const std::uint32_t t : mesh.source_vertex) mesh.positions.push_back(base_positions[t]);

  const Influences merged = mergeDuplicateBones(asset.influences);
  mesh.max_influences = merged.maxInfluences();
  ODESKIN_ASSIGN_OR_RETURN(PrunedInfluences pruned,
                           pruneInfluences(merged, kExportInfluences, base_positions, key_bones));
  mesh.pruned_vertices = pruned.report.vertices_pruned;
  mesh.max_prune_error = pruned.report.max_position_error;
  const Influences& kept = pruned.influences;
  mesh.joints.reserve(mesh.source_vertex.size());
  mesh.weights.reserve(mesh.source_vertex.size());
  for (std::uint32_t t : mesh.source_vertex) {
    const std::uint32_t begin = kept.offsets[t];
    const std::uint32_t count = kept.offsets[t + 1] - begin;
    std::array<float, kExportInfluences> w =
        float32Weights(std::span<const double>(kept.weights).subspan(begin, count));
    std::array<std::uint32_t, kExportInfluences> j{};
    for (std::uint32_t k = 0; k < count; ++k) j[k] = w[k] > 0.0f ? kept.bones[begin + k] : 0u;
    mesh.joints.push_back(j);
    mesh.weights.push_back(w);
  }
  return mesh;
}

}  // namespace odeskin

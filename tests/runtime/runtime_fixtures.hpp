// SPDX-License-Identifier: MIT
// Fitted assets and double-precision references for the runtime tests: the cylinder with its libigl
// rig (3 segments, 420 vertices, fast) and the cat (9 segments, 7207 vertices, automatic rig), each
// fitted once per test program, with two material presets besides the asset's own.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../pipeline/dataset_fixtures.hpp"
#include "engine/kernels/packed_deform.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/offline/residual_fit.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "engine/runtime/deform_runtime.hpp"
#include "engine/runtime/runtime_asset.hpp"

namespace odeskin::testing {

// A preset with a lighter, stiffer skin, so each preset plays differently.
inline MaterialPreset springyPreset() { return MaterialPreset{"springy", {Material{200.0, 20.0, 1e4, 1e-3}}}; }

inline RuntimeAssetOptions presetOptions() {
  RuntimeAssetOptions options;
  options.presets = {staticPreset(), springyPreset()};
  return options;
}

// `asset` packed for the runtime with presetOptions()' presets.
inline RuntimeAsset makeAsset(const DeformAsset& asset) {
  Result<RuntimeAsset> r = RuntimeAsset::create(asset, presetOptions());
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}

inline DeformAsset fitOrDie(const Result<ExampleSet>& examples, const PipelineOptions& options) {
  EXPECT_TRUE(examples.ok()) << examples.status().toString();
  if (!examples.ok()) return DeformAsset{};
  Result<PipelineResult> fitted = runFitPipeline(*examples, options);
  EXPECT_TRUE(fitted.ok()) << fitted.status().toString();
  return fitted.ok() ? std::move(fitted->asset) : DeformAsset{};
}

// Fitted once: the cylinder with its given rig and the skin material.
inline const DeformAsset& cylinderAsset(SkinningMode skinning = SkinningMode::kLinear) {
  static std::unique_ptr<DeformAsset> assets[2];
  std::unique_ptr<DeformAsset>& slot = assets[skinning == SkinningMode::kLinear ? 0 : 1];
  if (!slot) {
    PipelineOptions options;
    options.material = skinMaterial();
    options.skinning = skinning;
    slot = std::make_unique<DeformAsset>(fitOrDie(cylinderWithRig(true, true), options));
  }
  return *slot;
}

inline const DeformAsset& catAsset() {
  static std::unique_ptr<DeformAsset> asset;
  if (!asset) {
    const auto paths = catPoses(10);
    PipelineOptions options;
    options.material = skinMaterial();
    asset = std::make_unique<DeformAsset>(fitOrDie(readObjSequence(paths), options));
  }
  return *asset;
}

// `asset` with a render layout like a glTF's split at seams (RenderLayout): render vertex r < V is
// topology vertex V - 1 - r (reversed, so a gather that ignored the map would show), and V + i a
// second copy of topology vertex i < 20, which the even-numbered faces use instead of the first.
inline DeformAsset withSeams(const DeformAsset& asset) {
  DeformAsset out = asset;
  const std::uint32_t v = static_cast<std::uint32_t>(asset.vertexCount());
  const std::uint32_t seam = std::min<std::uint32_t>(20, v);
  out.render.topology_of_render.resize(v + seam);
  for (std::uint32_t r = 0; r < v; ++r) out.render.topology_of_render[r] = v - 1 - r;
  for (std::uint32_t i = 0; i < seam; ++i) out.render.topology_of_render[v + i] = i;
  out.render.faces = asset.faces;
  for (std::size_t f = 0; f < asset.faces.faceCount(); ++f) {
    for (std::uint32_t k = asset.faces.face_offsets[f]; k < asset.faces.face_offsets[f + 1]; ++k) {
      const std::uint32_t i = asset.faces.indices[k];
      out.render.faces.indices[k] = f % 2 == 0 && i < seam ? v + i : v - 1 - i;
    }
  }
  return out;
}

// The bind mesh's vertex normals, area-weighted over the topology's polygon fans (not normalised).
inline std::vector<Vec3> bindVertexNormals(const DeformAsset& asset) {
  std::vector<Vec3> normals(asset.vertexCount(), Vec3(0.0));
  const FaceList& faces = asset.faces;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t a = faces.indices[faces.face_offsets[f]];
    for (std::uint32_t k = faces.face_offsets[f] + 1; k + 1 < faces.face_offsets[f + 1]; ++k) {
      const std::uint32_t b = faces.indices[k], c = faces.indices[k + 1];
      const Vec3 n = glm::cross(asset.rest_positions[b] - asset.rest_positions[a], asset.rest_positions[c] - asset.rest_positions[a]);
      for (const std::uint32_t i : {a, b, c}) normals[i] += n;
    }
  }
  return normals;
}

// What a runtime test reads of an instance.
enum class Output { kPositions, kNormals, kTangents };

inline std::vector<gpu::Float4> readOutput(DeformRuntime& rt, std::uint64_t frame, std::uint32_t instance, Output what) {
  std::vector<gpu::Float4> out(rt.outputVertexCount());
  const Status status = what == Output::kPositions ? rt.readPositions(frame, instance, out)
                        : what == Output::kNormals ? rt.readNormals(frame, instance, out)
                                                   : rt.readTangents(frame, instance, out);
  EXPECT_TRUE(status.ok()) << status.toString();
  return out;
}

// Bind tangents for every render vertex of `asset`, as an engine's glTF would give them: unit,
// orthogonal to the bind vertex normal (area-weighted, over the topology's polygon fans), turning
// round the surface from vertex to vertex, a seam's second copy (withSeams) pointing another way
// than its first, and every third vertex left-handed (w = -1).
inline std::vector<gpu::Float4> bindTangents(const DeformAsset& asset) {
  const std::vector<Vec3> normals = bindVertexNormals(asset);
  const std::size_t count = asset.render.empty() ? asset.vertexCount() : asset.render.topology_of_render.size();
  std::vector<gpu::Float4> out(count);
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t i = asset.render.empty() ? r : asset.render.topology_of_render[r];
    const double turn = 0.37 * static_cast<double>(i) + (r >= asset.vertexCount() ? 1.5 : 0.0);
    const Vec3 n = glm::normalize(normals[i]);
    const Vec3 axis = glm::normalize(Vec3(std::cos(turn), std::sin(turn), 0.5));
    Vec3 t = axis - n * glm::dot(n, axis);
    if (glm::length(t) < 1e-3) t = glm::cross(n, Vec3(0.0, 0.0, 1.0));  // axis along the normal
    t = glm::normalize(t);
    out[r] = gpu::Float4{static_cast<float>(t.x), static_cast<float>(t.y), static_cast<float>(t.z), r % 3 == 0 ? -1.0f : 1.0f};
  }
  return out;
}

inline constexpr std::uint32_t kHardCopies = 10;  // topology vertices 0-9

// One bind normal per render vertex of `asset` (withSeams), as a glTF's NORMAL: the area-weighted
// normal, turned 40 degrees about the bind tangent for the second copies of vertices 0-9 (a hard
// edge there; a UV seam only at 10-19).
inline std::vector<gpu::Float4> hardEdgeNormals(const DeformAsset& asset) {
  const std::vector<gpu::Float4> tangents = bindTangents(asset);
  const std::vector<Vec3> normals = bindVertexNormals(asset);
  const std::uint32_t v = static_cast<std::uint32_t>(asset.vertexCount());
  std::vector<gpu::Float4> out(asset.render.topology_of_render.size());
  for (std::size_t r = 0; r < out.size(); ++r) {
    const std::uint32_t i = asset.render.topology_of_render[r];
    Vec3 n = glm::normalize(normals[i]);
    if (r >= v && i < kHardCopies) {
      const Vec3 t(tangents[r].x, tangents[r].y, tangents[r].z);
      n = std::cos(0.7) * n + std::sin(0.7) * glm::normalize(t);
    }
    out[r] = gpu::Float4{static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z), 0.0f};
  }
  return out;
}

// `asset` packed with presetOptions()' presets and bindTangents(asset).
inline RuntimeAsset makeAssetWithTangents(const DeformAsset& asset) {
  RuntimeAssetOptions options = presetOptions();
  options.render_tangents = bindTangents(asset);
  Result<RuntimeAsset> r = RuntimeAsset::create(asset, options);
  EXPECT_TRUE(r.ok()) << r.status().toString();
  return std::move(r).value();
}

// The double-precision reference of one instance: preset `preset` of `runtime_asset` at (segment,
// tau), with `bones` from the engine (rounded float matrices, as the runtime gets them) or, when
// empty, the asset's key paths in double.
inline std::vector<Vec3> referencePositions(const RuntimeAsset& runtime_asset, std::uint32_t preset,
                                            std::uint32_t segment, double tau,
                                            std::span<const gpu::BoneMatrix> bones = {}) {
  const DeformAsset& source = runtime_asset.source();
  DeformAsset variant;
  if (preset > 0) {
    MaterialPreset p = presetOptions().presets[preset - 1];
    Result<DeformAsset> made = assetWithPreset(source, p);
    EXPECT_TRUE(made.ok()) << made.status().toString();
    variant = std::move(made).value();
  }
  const DeformAsset& played = preset == 0 ? source : variant;
  Result<DeformPlayer> player = DeformPlayer::create(played);
  EXPECT_TRUE(player.ok());
  std::vector<Vec3> out(played.vertexCount());
  std::vector<ModeBasisValue> basis(player->basisSize());
  std::vector<BoneTransform> matrices(played.bone_count);
  player->basisAt(tau, basis);
  if (bones.empty()) {
    player->bonesAt(played, segment, tau, matrices);
  } else {
    for (std::size_t b = 0; b < matrices.size(); ++b) matrices[b] = fromGpuBone(bones[b]);
  }
  EXPECT_TRUE(referenceJob(played, segment, basis, matrices, out).run().ok());
  return out;
}

// The bits of one output entry, for exact comparisons (-0 and +0, NaNs told apart).
inline std::array<std::uint32_t, 4> bitsOf(const gpu::Float4& f) {
  return {std::bit_cast<std::uint32_t>(f.x), std::bit_cast<std::uint32_t>(f.y), std::bit_cast<std::uint32_t>(f.z),
          std::bit_cast<std::uint32_t>(f.w)};
}

// Max |a - b| over the vertices, and the vertex where it occurs.
struct WorstGap {
  double gap = 0.0;
  std::size_t vertex = 0;
};

inline WorstGap worstGap(std::span<const Vec3> expected, std::span<const gpu::Float4> actual) {
  WorstGap w;
  for (std::size_t i = 0; i < expected.size() && i < actual.size(); ++i) {
    const double d = glm::length(Vec3(actual[i].x, actual[i].y, actual[i].z) - expected[i]);
    if (!(d <= w.gap)) w = {d, i};
  }
  return w;
}

inline WorstGap worstGap(std::span<const gpu::Float4> expected, std::span<const gpu::Float4> actual) {
  WorstGap w;
  for (std::size_t i = 0; i < expected.size() && i < actual.size(); ++i) {
    // cppcheck-suppress cppcheckError ; cppcheck 2.10 gives up here ("cyclic reverse analysis"): a tool limit, not a finding
    const double d = std::max({std::fabs(double{expected[i].x} - actual[i].x), std::fabs(double{expected[i].y} - actual[i].y),
                               std::fabs(double{expected[i].z} - actual[i].z), std::fabs(double{expected[i].w} - actual[i].w)});
    if (!(d <= w.gap)) w = {d, i};
  }
  return w;
}

// A rigid world placement (rotation about y, then a translation) composed after `bones`: what an
// engine hands over when it wants world-space output.
inline std::vector<gpu::BoneMatrix> placed(std::span<const gpu::BoneMatrix> bones, double angle, const Vec3& offset) {
  const glm::dmat3 rotation(std::cos(angle), 0.0, -std::sin(angle), 0.0, 1.0, 0.0, std::sin(angle), 0.0, std::cos(angle));
  std::vector<gpu::BoneMatrix> out(bones.size());
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const gpu::Float4 rows[3] = {bones[b].row0, bones[b].row1, bones[b].row2};
    gpu::Float4 placed_rows[3];
    for (int r = 0; r < 3; ++r) {
      double values[4];
      for (int c = 0; c < 4; ++c) {
        double v = 0.0;
        for (int k = 0; k < 3; ++k) {
          const gpu::Float4& row = rows[k];
          const double m = c == 0 ? row.x : c == 1 ? row.y : c == 2 ? row.z : row.w;
          v += rotation[k][r] * m;
        }
        values[c] = v + (c == 3 ? offset[r] : 0.0);
      }
      placed_rows[r] = gpu::Float4{static_cast<float>(values[0]), static_cast<float>(values[1]),
                                   static_cast<float>(values[2]), static_cast<float>(values[3])};
    }
    out[b] = gpu::BoneMatrix{placed_rows[0], placed_rows[1], placed_rows[2]};
  }
  return out;
}

}  // namespace odeskin::testing

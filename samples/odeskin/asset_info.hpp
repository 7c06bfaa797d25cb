// SPDX-License-Identifier: MIT
// `odeskin info ASSET`: what a fitted asset holds and how its size compares with the two obvious
// alternatives, storing every example pose and baking a 30 fps vertex animation of the same length.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>

#include "console.hpp"
#include "engine/offline/deform_asset.hpp"

namespace odeskin {

inline constexpr double kBakedFps = 30.0;

struct AssetStats {
  std::size_t vertices = 0;           // V topology vertices
  std::size_t render_vertices = 0;    // glTF render vertices (== V without a render layout)
  std::size_t hard_edge_vertices = 0; // topology vertices the input's normals put on a hard edge
  bool texcoords = false;             // the input's TEXCOORD_0 (or OBJ vt) travels to the exports
  bool obj_layout = false;            // the render layout came from an OBJ's vt/vn corners
  std::size_t primitives = 0;         // the input's glTF primitives it records (0: none recorded)
  std::size_t faces = 0;
  std::size_t curves = 0;             // C
  std::size_t parts = 0;              // distinct IsoCurve::part values (0 when curves are not stored)
  int terms = 0;                      // N
  std::size_t key_poses = 0;          // K
  std::size_t segments = 0;           // K - 1
  std::uint32_t bones = 0;
  std::size_t materials = 0;
  double seconds = 0.0;               // playback length, segments x segment_seconds
  std::size_t coefficient_floats = 0; // segments x C x (2N+2) x 3 (the d^s; rates as many again)
  std::size_t remainders = 0;         // sparse remainders over all segments
  std::uintmax_t file_bytes = 0;      // the .odsk file
  std::size_t gpu_bytes = 0;          // packDeformAsset(asset).byteSize()
  std::size_t pose_bytes = 0;         // K x V x 3 float32: every example pose
  // In double: a huge segment length makes them larger than std::size_t holds, or infinite.
  double baked_frames = 0.0;          // round(seconds x 30) + 1
  double baked_bytes = 0.0;           // baked_frames x V x 3 float32
  double ratio_to_poses = 0.0;        // file_bytes / pose_bytes
  double ratio_to_baked = 0.0;        // file_bytes / baked_bytes
};

// Counts and sizes of a valid asset; file_bytes is the size of the file it was loaded from.
AssetStats assetStats(const DeformAsset& asset, std::uintmax_t file_bytes);

// "key: value" lines, one per fact.
void printAssetStats(std::ostream& out, const std::filesystem::path& path, const AssetStats& stats);

// Loads `path`, prints its stats to console.out. Exit status as console.hpp.
int runInfoCommand(const std::filesystem::path& path, Console& console);

}  // namespace odeskin

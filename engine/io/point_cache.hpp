// SPDX-License-Identifier: MIT
// Point caches: every frame's vertex positions in one binary file, for tools that animate a mesh
// they already hold by replacing its vertices frame by frame. The file holds no faces: it animates
// a mesh with the same vertices in the same order (`odeskin play ASSET --t 0 -o base.obj`).
//   PC2 (3ds Max's Point Cache, Blender's Mesh Cache modifier, Houdini): a 32-byte header
//       ("POINTCACHE2", version 1, vertex count, first frame, frames per sample, sample count),
//       then float32 x, y, z per vertex per sample, little-endian.
//   MDD (LightWave, Modo, Blender's Mesh Cache modifier, Houdini): the sample and vertex counts,
//       every sample's time in seconds, then float32 x, y, z per vertex per sample, big-endian.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

enum class PointCacheFormat { kPc2, kMdd };

inline constexpr std::size_t kPc2HeaderBytes = 32;
// One file's float data is at most this many bytes (4 GiB): the counts are 32-bit, and a cache that
// large is a typo in --fps or --seconds more often than a wish.
inline constexpr std::uint64_t kMaxPointCacheDataBytes = std::uint64_t{1} << 32;

// Empty when `samples` frames of `vertices` vertices fit one point cache, else why not (no
// vertices, no frames, or over kMaxPointCacheDataBytes, with the size it would need).
std::string pointCacheSizeProblem(std::size_t samples, std::size_t vertices);

// When the samples are shown: sample k at scene frame start_frame + k, at `fps` frames per second
// (PC2 keeps the frames, MDD the seconds (start_frame + k) / fps).
struct PointCacheTiming {
  double fps = 24.0;
  double start_frame = 0.0;
};

// Collects frames as float32 in the format's byte order (12 bytes a vertex, half of what the
// double frames would hold) and writes them as one file.
class PointCacheBuilder {
 public:
  // `samples`: the frames that will be added, so their memory is taken once.
  PointCacheBuilder(PointCacheFormat format, std::size_t vertices, std::size_t samples);

  // kInvalidArgument for a frame whose vertex count is not the builder's, or a coordinate that is
  // not a finite float32 (naming the frame and vertex).
  Status add(std::span<const Vec3> positions);

  // Writes every added frame to `path` through writeFileAtomically. kInvalidArgument naming the
  // path when pointCacheSizeProblem refuses the size, or fps (positive) or start_frame is not a
  // finite float32 (nor is a sample's time, for MDD); kIoError naming the path when it cannot be
  // written.
  Status write(const std::filesystem::path& path, const PointCacheTiming& timing);

  std::size_t samples() const { return samples_; }

 private:
  PointCacheFormat format_;
  std::size_t vertices_;
  std::size_t samples_ = 0;
  std::string data_;  // the samples' float32 values; write() puts the header before them for the write
};

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// Point caches: every frame's vertex positions in one binary file, for tools that animate a mesh
// they already hold by replacing its vertices frame by frame (Blender's Mesh Cache modifier, 3ds
// Max's Point Cache, Houdini). PC2 is the format they all read: a 32-byte header ("POINTCACHE2",
// version 1, vertex count, first frame, frames per sample, sample count) and then float32 x, y, z
// per vertex per sample, little-endian. The file holds no faces: it animates a mesh with the same
// vertices in the same order (`odeskin play ASSET --t 0 -o base.obj`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

inline constexpr std::size_t kPc2HeaderBytes = 32;
// One file's float data is at most this many bytes (4 GiB): the counts are 32-bit, and a cache that
// large is a typo in --fps or --seconds more often than a wish.
inline constexpr std::uint64_t kMaxPc2DataBytes = std::uint64_t{1} << 32;

// Empty when `samples` frames of `vertices` vertices fit one PC2 file, else why not (no vertices,
// no frames, or over kMaxPc2DataBytes, with the size it would need).
std::string pc2SizeProblem(std::size_t samples, std::size_t vertices);

// Collects frames as float32 (12 bytes a vertex, half of what the double frames would hold) and
// writes them as one PC2 file.
class Pc2Builder {
 public:
  // `samples`: the frames that will be added, so their memory is taken once.
  Pc2Builder(std::size_t vertices, std::size_t samples);

  // kInvalidArgument for a frame whose vertex count is not the builder's, or a coordinate that is
  // not a finite float32 (naming the frame and vertex).
  Status add(std::span<const Vec3> positions);

  // Writes every added frame to `path` through writeFileAtomically: sample k is shown at scene
  // frame start_frame + k * sample_frames. kInvalidArgument naming the path when pc2SizeProblem
  // refuses the size or the frame numbers are not finite (sample_frames positive) float32;
  // kIoError naming the path when it cannot be written.
  Status write(const std::filesystem::path& path, double start_frame = 0.0, double sample_frames = 1.0);

  std::size_t samples() const { return samples_; }

 private:
  std::size_t vertices_;
  std::size_t samples_ = 0;
  std::string data_;  // the whole file: 32 header bytes (filled by write), then little-endian float32
};

}  // namespace odeskin

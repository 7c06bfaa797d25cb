// SPDX-License-Identifier: MIT
// Points of a mesh found by their parameters: the triangle of the disk (mesh_network_disk.hpp) that
// holds a given (u, v), and the point's barycentric coordinates in it. A MeshPoint is a fixed
// combination of three disk vertices, so the same point can be read on any pose of the mesh: the
// curve samples of a network extracted from a neutral face move with each expression (thesis 4.7).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh_network_disk.hpp"

namespace odeskin {

struct MeshPoint {
  std::array<std::uint32_t, 3> vertex{};  // disk vertices (mesh vertices, then hole centres)
  std::array<double, 3> weight{};         // barycentric coordinates, >= 0, summing to 1
};

// The point on a pose: sum of weight * position. Precondition: disk_positions covers the vertices.
inline Vec3 pointPosition(const MeshPoint& p, std::span<const Vec3> disk_positions) {
  return p.weight[0] * disk_positions[p.vertex[0]] + p.weight[1] * disk_positions[p.vertex[1]] +
         p.weight[2] * disk_positions[p.vertex[2]];
}

// A bucket grid over the unit square of a disk's parameters.
class DiskLocator {
 public:
  // Precondition: disk.uv and disk.triangles as parameteriseDisk leaves them.
  explicit DiskLocator(const MeshDisk& disk);

  // The point at (u, v), clamped to [0, 1]^2. The triangle holding it; a point that rounding puts
  // just outside every triangle takes the nearest one, its coordinates clamped to it.
  MeshPoint locate(Vec2 uv) const;

 private:
  const MeshDisk* disk_ = nullptr;
  std::uint32_t cells_ = 1;                   // cells per side
  std::vector<std::uint32_t> cell_offsets_;   // cells_^2 + 1
  std::vector<std::uint32_t> cell_triangles_;
};

}  // namespace odeskin

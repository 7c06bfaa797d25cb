// SPDX-License-Identifier: MIT
// Procedural meshes for the curve-rig tests: a closed tube along x (rings of quads split into
// triangles, capped by fans), the same bent round a circle, and a flat triangulated grid.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/core/types.hpp"

namespace odeskin::testing {

struct TestMesh {
  std::vector<Vec3> positions;
  FaceList faces;
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    faces.indices.insert(faces.indices.end(), {a, b, c});
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  }
};

// `rings` rings of `sides` vertices at x = 0 .. length, radius r, closed by a vertex at each end;
// outward facing triangles.
inline TestMesh closedTube(std::uint32_t rings, std::uint32_t sides, double length, double r) {
  TestMesh m;
  for (std::uint32_t i = 0; i < rings; ++i) {
    const double x = length * static_cast<double>(i) / static_cast<double>(rings - 1);
    for (std::uint32_t k = 0; k < sides; ++k) {
      const double a = 2.0 * std::numbers::pi * (static_cast<double>(k) + 0.5 * (i % 2)) / static_cast<double>(sides);
      m.positions.push_back(Vec3(x, r * std::cos(a), r * std::sin(a)));
    }
  }
  auto at = [&](std::uint32_t i, std::uint32_t k) { return i * sides + k % sides; };
  for (std::uint32_t i = 0; i + 1 < rings; ++i) {
    for (std::uint32_t k = 0; k < sides; ++k) {
      m.triangle(at(i, k), at(i + 1, k), at(i, k + 1));
      m.triangle(at(i, k + 1), at(i + 1, k), at(i + 1, k + 1));
    }
  }
  const auto first = static_cast<std::uint32_t>(m.positions.size());
  m.positions.push_back(Vec3(-0.5 * r, 0.0, 0.0));
  m.positions.push_back(Vec3(length + 0.5 * r, 0.0, 0.0));
  for (std::uint32_t k = 0; k < sides; ++k) {
    m.triangle(first, at(0, k), at(0, k + 1));
    m.triangle(first + 1, at(rings - 1, k + 1), at(rings - 1, k));
  }
  return m;
}

// closedTube(rings, sides, length, r) bent round a circle of radius `bend` in the xy plane: x
// along the tube becomes the angle x / bend, y the distance in from the circle. length = 1.5 pi
// bend curls it three quarters of the way round, like a cat asleep.
inline TestMesh bentTube(std::uint32_t rings, std::uint32_t sides, double length, double r, double bend) {
  TestMesh m = closedTube(rings, sides, length, r);
  for (Vec3& p : m.positions) {
    const double angle = p.x / bend;
    p = Vec3((bend - p.y) * std::cos(angle), (bend - p.y) * std::sin(angle), p.z);
  }
  return m;
}

// An n x n grid of unit squares in the z = 0 plane, each split along the same diagonal.
inline TestMesh flatGrid(std::uint32_t n) {
  TestMesh m;
  for (std::uint32_t j = 0; j <= n; ++j) {
    for (std::uint32_t i = 0; i <= n; ++i) m.positions.push_back(Vec3(i, j, 0.0));
  }
  auto at = [&](std::uint32_t i, std::uint32_t j) { return j * (n + 1) + i; };
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      m.triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return m;
}

}  // namespace odeskin::testing

// SPDX-License-Identifier: MIT
// computeVertexNormals (one register per vertex on x86-64) against the scalar glm form it stands
// for, bit for bit: the cat's corner lists on its rest and perturbed positions, and a small mesh
// with a long fan, a strip, degenerate and non-finite triangles and a vertex in no triangle.
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "engine/runtime/instance_outputs.hpp"
#include "runtime_fixtures.hpp"

namespace odeskin {
namespace {

struct Corners {
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> offsets;
  std::vector<gpu::Corner> corners;
};

// The corner lists of triangles over `v` vertices, as RuntimeAsset builds them.
Corners cornersOf(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::uint32_t v) {
  FaceList faces;
  for (const auto& t : triangles) {
    faces.indices.insert(faces.indices.end(), t.begin(), t.end());
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  }
  Corners out;
  buildCorners(faces, v, out.triangles, out.offsets, out.corners);
  return out;
}

bool sameBits(const std::vector<gpu::Float4>& a, const std::vector<gpu::Float4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::Float4)) == 0;
}

// The scalar form: glm's cross products summed over the corners, then glm::length and a division.
std::vector<gpu::Float4> scalarNormals(std::span<const std::uint32_t> offsets, std::span<const gpu::Corner> corners,
                                       const std::vector<gpu::Float4>& positions) {
  auto at = [&](std::uint32_t i) { return glm::vec3(positions[i].x, positions[i].y, positions[i].z); };
  std::vector<gpu::Float4> out(positions.size());
  for (std::uint32_t i = 0; i < positions.size(); ++i) {
    glm::vec3 n(0.0f);
    for (std::uint32_t k = offsets[i]; k < offsets[i + 1]; ++k) n += glm::cross(at(corners[k].next) - at(i), at(corners[k].prev) - at(i));
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f);
    out[i] = gpu::Float4{n.x, n.y, n.z, 0.0f};
  }
  return out;
}

void expectBitIdentical(std::span<const std::uint32_t> offsets, std::span<const gpu::Corner> corners,
                        const std::vector<gpu::Float4>& positions, const char* what) {
  std::vector<gpu::Float4> got(positions.size(), gpu::Float4{1.0f, 2.0f, 3.0f, 4.0f});
  computeVertexNormals(offsets, corners, positions, got);
  EXPECT_TRUE(sameBits(got, scalarNormals(offsets, corners, positions))) << what;
}

std::vector<gpu::Float4> float4s(std::span<const Vec3> points) {
  std::vector<gpu::Float4> out;
  for (const Vec3& p : points) out.push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z), 1.0f});
  return out;
}

TEST(VertexNormals, TheCatsNormalsAreBitIdentical) {
  const Result<RuntimeAsset> asset = RuntimeAsset::create(testing::catAsset());
  ASSERT_TRUE(asset.ok()) << asset.status().toString();
  std::vector<gpu::Float4> positions = float4s(asset->source().rest_positions);
  expectBitIdentical(asset->cornerOffsets(), asset->corners(), positions, "rest");
  std::mt19937 random(7);
  std::uniform_real_distribution<float> jitter(-0.01f, 0.01f);
  for (gpu::Float4& p : positions) {
    p.x += jitter(random);
    p.y += jitter(random);
    p.z += jitter(random);
  }
  expectBitIdentical(asset->cornerOffsets(), asset->corners(), positions, "perturbed");
}

TEST(VertexNormals, OddMeshesAreBitIdentical) {
  // A fan of 40 triangles round vertex 0, a strip, a degenerate triangle, a vertex in no triangle,
  // and triangles with an infinite corner.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Vec3> points{Vec3(0.0, 0.0, 0.3)};
  constexpr std::uint32_t kFan = 40;
  for (std::uint32_t k = 0; k < kFan; ++k) {
    const double a = 2.0 * 3.141592653589793 * k / kFan;
    points.emplace_back(std::cos(a), std::sin(a), 0.05 * (k % 3));
    triangles.push_back({0, 1 + k, 1 + (k + 1) % kFan});
  }
  const auto strip = static_cast<std::uint32_t>(points.size());
  for (std::uint32_t k = 0; k < 12; ++k) points.emplace_back(0.5 * k, 3.0 + 0.1 * (k % 2), 0.01 * k * k);
  for (std::uint32_t k = 0; k + 2 < 12; ++k) triangles.push_back({strip + k, strip + k + 1, strip + k + 2});
  const auto flat = static_cast<std::uint32_t>(points.size());
  points.emplace_back(5.0, 5.0, 5.0);
  points.emplace_back(6.0, 6.0, 6.0);
  points.emplace_back(7.0, 7.0, 7.0);  // on one line: zero area, no normal
  triangles.push_back({flat, flat + 1, flat + 2});
  points.emplace_back(9.0, 9.0, 9.0);  // in no triangle
  const auto bad = static_cast<std::uint32_t>(points.size());
  points.emplace_back(1.0, 0.0, 0.0);
  points.emplace_back(0.0, 1.0, 0.0);
  points.emplace_back(std::numeric_limits<double>::infinity(), 0.0, 0.0);
  triangles.push_back({bad, bad + 1, bad + 2});
  // An infinite vertex whose one corner gives a normal of (0, NaN, NaN).
  const auto far = static_cast<std::uint32_t>(points.size());
  points.emplace_back(std::numeric_limits<double>::infinity(), 0.0, 0.0);
  points.emplace_back(0.0, 1.0, 1.0);
  points.emplace_back(0.0, -1.0, -1.0);
  triangles.push_back({far, far + 1, far + 2});
  const auto v = static_cast<std::uint32_t>(points.size());
  const Corners c = cornersOf(triangles, v);
  const std::vector<gpu::Float4> positions = float4s(points);
  expectBitIdentical(c.offsets, c.corners, positions, "odd mesh");
  std::vector<gpu::Float4> normals(v);
  computeVertexNormals(c.offsets, c.corners, positions, normals);
  EXPECT_EQ(normals[flat].x, 0.0f);
  EXPECT_EQ(normals[flat + 3].z, 0.0f);  // the vertex in no triangle
  EXPECT_GT(normals[0].z, 0.99f);        // the fan's centre looks up
  EXPECT_EQ(normals[far].x, 0.0f);
  EXPECT_TRUE(std::isnan(normals[far].y));
}

}  // namespace
}  // namespace odeskin

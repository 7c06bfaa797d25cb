// SPDX-License-Identifier: MIT
#include "gltf_weld.hpp"

#include <array>
#include <bit>
#include <unordered_map>

namespace odeskin::gltf {
namespace {

using Key = std::array<double, 3>;

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (double x : k) h = (h ^ std::bit_cast<std::uint64_t>(x)) * 0x100000001b3ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace

Welded weldEqualPositions(std::span<const Vec3> render_positions) {
  Welded w;
  w.topology_of_render.reserve(render_positions.size());
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  index.reserve(render_positions.size());
  for (std::size_t r = 0; r < render_positions.size(); ++r) {
    const Vec3& p = render_positions[r];
    // Adding +0.0 turns -0.0 into +0.0, so the two zeros share a key (and a hash).
    const Key key{p.x + 0.0, p.y + 0.0, p.z + 0.0};
    const auto [it, inserted] = index.try_emplace(key, static_cast<std::uint32_t>(w.positions.size()));
    if (inserted) {
      w.positions.push_back(p);
      w.first_render.push_back(static_cast<std::uint32_t>(r));
    }
    w.topology_of_render.push_back(it->second);
  }
  return w;
}

FaceList triangleFaces(std::span<const std::uint32_t> triangles) {
  FaceList faces;
  faces.indices.assign(triangles.begin(), triangles.end());
  faces.face_offsets.reserve(triangles.size() / 3 + 1);
  for (std::size_t f = 1; f <= triangles.size() / 3; ++f) faces.face_offsets.push_back(static_cast<std::uint32_t>(3 * f));
  return faces;
}

FaceList topologyTriangles(std::span<const std::uint32_t> render_triangles,
                           std::span<const std::uint32_t> topology_of_render) {
  std::vector<std::uint32_t> kept;
  kept.reserve(render_triangles.size());
  for (std::size_t f = 0; f + 2 < render_triangles.size(); f += 3) {
    const std::uint32_t a = topology_of_render[render_triangles[f]];
    const std::uint32_t b = topology_of_render[render_triangles[f + 1]];
    const std::uint32_t c = topology_of_render[render_triangles[f + 2]];
    if (a == b || b == c || a == c) continue;
    kept.insert(kept.end(), {a, b, c});
  }
  return triangleFaces(kept);
}

}  // namespace odeskin::gltf

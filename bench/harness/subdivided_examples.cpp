// SPDX-License-Identifier: MIT
#include "subdivided_examples.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>

namespace odeskin::bench {
namespace {

// The midpoint rows: each edge's new vertex blends its two ends' influence rows half and half.
Influences subdivideInfluences(const Influences& in, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges) {
  Influences out = in;
  for (const auto& [a, b] : edges) {
    std::map<std::uint32_t, double> row;
    for (std::uint32_t end : {a, b}) {
      for (std::uint32_t k = in.offsets[end]; k < in.offsets[end + 1]; ++k) row[in.bones[k]] += 0.5 * in.weights[k];
    }
    for (const auto& [bone, weight] : row) {
      out.bones.push_back(bone);
      out.weights.push_back(weight);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

}  // namespace

Result<ExampleSet> subdivideMidpoint(const ExampleSet& ex) {
  const std::size_t v_count = ex.rest_positions.size();
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_vertex;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;  // new vertex v_count + i joins edges[i]
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::minmax(a, b);
    const auto [it, inserted] =
        edge_vertex.emplace(std::pair(key.first, key.second), static_cast<std::uint32_t>(v_count + edges.size()));
    if (inserted) edges.emplace_back(key.first, key.second);
    return it->second;
  };
  ExampleSet out;
  for (std::size_t f = 0; f < ex.faces.faceCount(); ++f) {
    const std::uint32_t begin = ex.faces.face_offsets[f];
    if (ex.faces.face_offsets[f + 1] - begin != 3) {
      return invalidArgument("subdivideMidpoint: face " + std::to_string(f) + " is not a triangle");
    }
    const std::uint32_t a = ex.faces.indices[begin], b = ex.faces.indices[begin + 1], c = ex.faces.indices[begin + 2];
    if (a >= v_count || b >= v_count || c >= v_count) {
      return invalidArgument("subdivideMidpoint: face " + std::to_string(f) + " has a vertex out of range");
    }
    const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    for (const std::array<std::uint32_t, 3>& tri : {std::array{a, ab, ca}, std::array{ab, b, bc},
                                                    std::array{ca, bc, c}, std::array{ab, bc, ca}}) {
      out.faces.indices.insert(out.faces.indices.end(), tri.begin(), tri.end());
      out.faces.face_offsets.push_back(static_cast<std::uint32_t>(out.faces.indices.size()));
    }
  }
  auto extend = [&](const std::vector<Vec3>& positions) {
    std::vector<Vec3> p = positions;
    p.reserve(v_count + edges.size());
    for (const auto& [a, b] : edges) p.push_back(0.5 * (positions[a] + positions[b]));
    return p;
  };
  out.rest_positions = extend(ex.rest_positions);
  for (const std::vector<Vec3>& pose : ex.poses) out.poses.push_back(extend(pose));
  out.pose_labels = ex.pose_labels;
  if (ex.rig) {
    Rig rig = *ex.rig;
    if (rig.influences.vertexCount() == v_count) rig.influences = subdivideInfluences(rig.influences, edges);
    out.rig = std::move(rig);
  }
  return out;
}

}  // namespace odeskin::bench

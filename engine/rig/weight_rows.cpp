// SPDX-License-Identifier: MIT
#include "weight_rows.hpp"
#include "../core/parallel.hpp"

#include <algorithm>


namespace odeskin {

Status checkFaces(const FaceList& faces, std::size_t vertex_count, const std::string& who) {
  if (faces.face_offsets.empty() || faces.face_offsets[0] != 0 || faces.face_offsets.back() != faces.indices.size()) {
    return invalidArgument(who + ": face offsets do not start at 0 and end at the index count " +
                           std::to_string(faces.indices.size()));
  }
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    if (faces.face_offsets[f + 1] < faces.face_offsets[f] + 3) {
      return invalidArgument(who + ": face " + std::to_string(f) + " has fewer than 3 corners");
    }
    for (std::uint32_t c = faces.face_offsets[f]; c < faces.face_offsets[f + 1]; ++c) {
      if (faces.indices[c] >= vertex_count) {
        return invalidArgument(who + ": face " + std::to_string(f) + " uses vertex " + std::to_string(faces.indices[c]) +
                               " of " + std::to_string(vertex_count));
      }
    }
  }
  return okStatus();
}

void smoothRows(std::vector<WeightRow>& rows, const VertexAdjacency& adjacency, int iterations, double lambda) {
  std::vector<WeightRow> next(rows.size());
  for (int it = 0; it < iterations; ++it) {
    parallelFor(std::size_t{0}, rows.size(), [&](std::size_t i) {
      const auto ring = adjacency.of(static_cast<std::uint32_t>(i));
      WeightRow& out = next[i];
      out.clear();
      if (ring.empty()) {
        out = rows[i];
        return;
      }
      const double share = lambda / static_cast<double>(ring.size());
      for (const BoneWeight& e : rows[i]) out.push_back({e.bone, (1.0 - lambda) * e.weight});
      for (const std::uint32_t j : ring) {
        for (const BoneWeight& e : rows[j]) out.push_back({e.bone, share * e.weight});
      }
      std::sort(out.begin(), out.end(), [](const BoneWeight& a, const BoneWeight& b) { return a.bone < b.bone; });
      std::size_t kept = 0;
      for (std::size_t e = 0; e < out.size(); ++e) {
        if (kept > 0 && out[kept - 1].bone == out[e].bone) {
          out[kept - 1].weight += out[e].weight;
        } else {
          out[kept++] = out[e];
        }
      }
      out.resize(kept);
    });
    rows.swap(next);
  }
}

Influences pruneRows(const std::vector<WeightRow>& rows, int max_influences) {
  Influences out;
  out.offsets.reserve(rows.size() + 1);
  WeightRow row;
  for (const WeightRow& source : rows) {
    row = source;
    std::stable_sort(row.begin(), row.end(), [](const BoneWeight& a, const BoneWeight& b) { return a.weight > b.weight; });
    while (!row.empty() && !(row.back().weight > 0.0)) row.pop_back();
    if (row.size() > static_cast<std::size_t>(max_influences)) row.resize(static_cast<std::size_t>(max_influences));
    std::sort(row.begin(), row.end(), [](const BoneWeight& a, const BoneWeight& b) { return a.bone < b.bone; });
    double sum = 0.0;
    for (const BoneWeight& e : row) sum += e.weight;
    for (const BoneWeight& e : row) {
      out.bones.push_back(e.bone);
      out.weights.push_back(e.weight / sum);
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.bones.size()));
  }
  return out;
}

}  // namespace odeskin

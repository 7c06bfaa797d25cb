// SPDX-License-Identifier: MIT
#include "weight_rows.hpp"
#include "../core/parallel.hpp"

#include <algorithm>


namespace odeskin {
namespace {

// Vertices per chunk of a smoothing step (a few hundred entries each), each with its own output buffer.
constexpr std::size_t kSmoothGrain = 64;

}  // namespace

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
  if (iterations <= 0) return;
  std::uint32_t bones = 0;
  for (const WeightRow& row : rows) {
    for (const BoneWeight& e : row) bones = std::max(bones, e.bone + 1);
  }
  // The rows are smoothed as compressed rows (one array of entries, an offset per row): a ring
  // reads its neighbours' rows from one block instead of one heap allocation each.
  const std::size_t count = rows.size();
  std::vector<std::uint32_t> offsets(count + 1, 0);
  std::vector<BoneWeight> entries;
  for (std::size_t i = 0; i < count; ++i) {
    entries.insert(entries.end(), rows[i].begin(), rows[i].end());
    offsets[i + 1] = static_cast<std::uint32_t>(entries.size());
  }
  std::vector<std::uint32_t> next_offsets(count + 1, 0);
  std::vector<BoneWeight> next_entries;
  // A chunk's rows are written to its own buffer first (their lengths are known only once summed).
  const std::size_t chunks = (count + kSmoothGrain - 1) / kSmoothGrain;
  std::vector<std::vector<BoneWeight>> chunk_entries(chunks);
  for (int it = 0; it < iterations; ++it) {
    // Each row is summed bone by bone in one fixed order (the vertex, then its neighbours in the
    // adjacency's order) into a dense per-chunk array: no sort of the ring's entries, and a sum that
    // does not depend on how a sort leaves equal bones.
    parallelFor(std::size_t{0}, chunks, [&](std::size_t chunk) {
      std::vector<double> sum(bones, 0.0);
      std::vector<char> used(bones, 0);
      std::vector<std::uint32_t> touched;
      std::vector<BoneWeight>& out = chunk_entries[chunk];
      out.clear();
      const std::size_t end = std::min(count, (chunk + 1) * kSmoothGrain);
      for (std::size_t i = chunk * kSmoothGrain; i < end; ++i) {
        const auto ring = adjacency.of(static_cast<std::uint32_t>(i));
        if (ring.empty()) {
          out.insert(out.end(), entries.begin() + offsets[i], entries.begin() + offsets[i + 1]);
          next_offsets[i + 1] = offsets[i + 1] - offsets[i];
          continue;
        }
        auto add = [&](std::size_t row, double scale) {
          for (std::uint32_t k = offsets[row]; k < offsets[row + 1]; ++k) {
            const BoneWeight& e = entries[k];
            if (!used[e.bone]) {
              used[e.bone] = 1;
              touched.push_back(e.bone);
            }
            sum[e.bone] += scale * e.weight;
          }
        };
        add(i, 1.0 - lambda);
        const double share = lambda / static_cast<double>(ring.size());
        for (const std::uint32_t j : ring) add(j, share);
        std::sort(touched.begin(), touched.end());
        for (const std::uint32_t b : touched) {
          out.push_back({b, sum[b]});
          sum[b] = 0.0;
          used[b] = 0;
        }
        next_offsets[i + 1] = static_cast<std::uint32_t>(touched.size());
        touched.clear();
      }
    });
    for (std::size_t i = 0; i < count; ++i) next_offsets[i + 1] += next_offsets[i];
    next_entries.resize(next_offsets[count]);
    parallelFor(std::size_t{0}, chunks, [&](std::size_t chunk) {
      std::copy(chunk_entries[chunk].begin(), chunk_entries[chunk].end(),
                next_entries.begin() + next_offsets[chunk * kSmoothGrain]);
    });
    offsets.swap(next_offsets);
    entries.swap(next_entries);
  }
  for (std::size_t i = 0; i < count; ++i) rows[i].assign(entries.begin() + offsets[i], entries.begin() + offsets[i + 1]);
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

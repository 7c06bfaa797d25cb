// SPDX-License-Identifier: MIT
#include "weight_rows.hpp"
#include "../core/parallel.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>


namespace odeskin {
namespace {

// Vertices per chunk of a smoothing step (a few hundred entries each), each with its own output buffer.
constexpr std::size_t kSmoothGrain = 64;

// Rows as one array of entries and an offset per row: a ring reads its neighbours' rows from one
// block instead of one heap allocation each.
struct CompressedRows {
  std::vector<std::uint32_t> offsets;
  std::vector<BoneWeight> entries;
};

// Row i after one umbrella step, appended to `out`. It is summed bone by bone in one fixed order
// (the vertex, then its neighbours in the adjacency's order) into `sum`, dense over the bones: no
// sort of the ring's entries, and a sum that does not depend on how a sort leaves equal bones.
// The bones the row takes are marked in a bit set, so that they come out in order and the sum
// needs no branch on whether a bone is new: one register with at most 64 bones (kOneWord), else
// `present`, one word per 64 bones. `sum` and `present` are zero on entry and on return.
template <bool kOneWord>
void smoothRow(const CompressedRows& rows, std::uint32_t i, std::span<const std::uint32_t> ring, double lambda,
               std::span<double> sum, std::span<std::uint64_t> present, std::vector<BoneWeight>& out) {
  std::uint64_t bits = 0;
  auto first_word = static_cast<std::uint32_t>(present.size());
  std::uint32_t last_word = 0;
  auto add = [&](std::uint32_t row, double scale) {
    for (std::uint32_t k = rows.offsets[row]; k < rows.offsets[row + 1]; ++k) {
      const BoneWeight& e = rows.entries[k];
      if constexpr (kOneWord) {
        bits |= std::uint64_t{1} << e.bone;
      } else {
        const std::uint32_t word = e.bone / 64;
        present[word] |= std::uint64_t{1} << (e.bone % 64);
        first_word = std::min(first_word, word);
        last_word = std::max(last_word, word);
      }
      sum[e.bone] += scale * e.weight;
    }
  };
  add(i, 1.0 - lambda);
  const double share = lambda / static_cast<double>(ring.size());
  for (const std::uint32_t j : ring) add(j, share);
  auto emit = [&](std::uint32_t word, std::uint64_t word_bits) {
    for (; word_bits != 0; word_bits &= word_bits - 1) {
      const std::uint32_t b = 64 * word + static_cast<std::uint32_t>(std::countr_zero(word_bits));
      out.push_back({b, sum[b]});
      sum[b] = 0.0;
    }
  };
  if constexpr (kOneWord) {
    emit(0, bits);
  } else {
    for (std::uint32_t word = first_word; word <= last_word; ++word) {
      emit(word, present[word]);
      present[word] = 0;
    }
  }
}

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
  const std::uint32_t words = (bones + 63) / 64;
  const std::size_t count = rows.size();
  CompressedRows current;
  current.offsets.assign(count + 1, 0);
  for (std::size_t i = 0; i < count; ++i) {
    current.entries.insert(current.entries.end(), rows[i].begin(), rows[i].end());
    current.offsets[i + 1] = static_cast<std::uint32_t>(current.entries.size());
  }
  CompressedRows next;
  next.offsets.assign(count + 1, 0);
  // A chunk's rows are written to its own buffer first (their lengths are known only once summed).
  const std::size_t chunks = (count + kSmoothGrain - 1) / kSmoothGrain;
  std::vector<std::vector<BoneWeight>> chunk_entries(chunks);
  for (int it = 0; it < iterations; ++it) {
    parallelFor(std::size_t{0}, chunks, [&](std::size_t chunk) {
      std::vector<double> sum(bones, 0.0);
      std::vector<std::uint64_t> present(words, 0);
      std::vector<BoneWeight>& out = chunk_entries[chunk];
      out.clear();
      const std::size_t end = std::min(count, (chunk + 1) * kSmoothGrain);
      for (std::size_t i = chunk * kSmoothGrain; i < end; ++i) {
        const std::size_t before = out.size();
        const auto ring = adjacency.of(static_cast<std::uint32_t>(i));
        if (ring.empty()) {
          out.insert(out.end(), current.entries.begin() + current.offsets[i], current.entries.begin() + current.offsets[i + 1]);
        } else if (words <= 1) {
          smoothRow<true>(current, static_cast<std::uint32_t>(i), ring, lambda, sum, present, out);
        } else {
          smoothRow<false>(current, static_cast<std::uint32_t>(i), ring, lambda, sum, present, out);
        }
        next.offsets[i + 1] = static_cast<std::uint32_t>(out.size() - before);
      }
    });
    for (std::size_t i = 0; i < count; ++i) next.offsets[i + 1] += next.offsets[i];
    next.entries.resize(next.offsets[count]);
    parallelFor(std::size_t{0}, chunks, [&](std::size_t chunk) {
      std::copy(chunk_entries[chunk].begin(), chunk_entries[chunk].end(),
                next.entries.begin() + next.offsets[chunk * kSmoothGrain]);
    });
    std::swap(current, next);
  }
  for (std::size_t i = 0; i < count; ++i) {
    rows[i].assign(current.entries.begin() + current.offsets[i], current.entries.begin() + current.offsets[i + 1]);
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

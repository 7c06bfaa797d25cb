// SPDX-License-Identifier: MIT
#include "face_fans.hpp"

#include <algorithm>
#include <limits>
#include <optional>

namespace odeskin {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Every face corner, grouped by its vertex: the vertex before and after it in the face, and the
// corner's position in faces.indices (where OpenMesh creates the edge to `next`).
struct Corners {
  // One record per corner, so that placing a corner in its vertex's group writes one cache line.
  struct Corner {
    std::uint32_t prev, next, position, prev_position;
  };
  std::vector<std::uint32_t> offsets;  // V + 1
  std::vector<Corner> at;

  std::uint32_t begin(std::uint32_t v) const { return offsets[v]; }
  std::uint32_t end(std::uint32_t v) const { return offsets[v + 1]; }
};

// false when an index is out of range or a face is too short (the corners are then not built).
bool buildCorners(const FaceList& faces, std::size_t vertex_count, Corners& c) {
  if (faces.face_offsets.empty() || faces.face_offsets.front() != 0 || faces.face_offsets.back() != faces.indices.size()) {
    return false;
  }
  c.offsets.assign(vertex_count + 1, 0);
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    if (faces.face_offsets[f + 1] < faces.face_offsets[f] + 3) return false;
  }
  for (std::uint32_t v : faces.indices) {
    if (v >= vertex_count) return false;
    ++c.offsets[v + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) c.offsets[v + 1] += c.offsets[v];
  const std::size_t total = faces.indices.size();
  c.at.resize(total);
  std::vector<std::uint32_t> fill(c.offsets.begin(), c.offsets.end() - 1);
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    const std::uint32_t begin = faces.face_offsets[f];
    const std::uint32_t n = faces.face_offsets[f + 1] - begin;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t v = faces.indices[begin + i];
      const std::uint32_t before = begin + (i == 0 ? n - 1 : i - 1);
      c.at[fill[v]++] = {faces.indices[before], faces.indices[begin + (i + 1 == n ? 0 : i + 1)], begin + i, before};
    }
  }
  return true;
}

bool repeatsVertex(const FaceList& faces, std::size_t f, std::vector<std::uint32_t>& scratch) {
  const std::uint32_t begin = faces.face_offsets[f];
  const std::uint32_t end = faces.face_offsets[f + 1];
  if (end - begin <= 4) {
    for (std::uint32_t i = begin; i < end; ++i) {
      for (std::uint32_t j = i + 1; j < end; ++j) {
        if (faces.indices[i] == faces.indices[j]) return true;
      }
    }
    return false;
  }
  scratch.assign(faces.indices.begin() + begin, faces.indices.begin() + end);
  std::sort(scratch.begin(), scratch.end());
  return std::adjacent_find(scratch.begin(), scratch.end()) != scratch.end();
}

// The corners around v form one fan: corner g follows corner f when f's edge v -> w is g's edge
// w -> v (the two faces share the edge); with every directed edge used once each corner has at
// most one follower, and one fan is one chain (or one cycle) through all of them.
// `open`: the fan's first corner (its in-edge has no face on the other side), or kNone for a closed
// fan or none.
bool oneFan(const Corners& c, std::uint32_t v, std::uint32_t& open) {
  const std::uint32_t begin = c.begin(v);
  const std::uint32_t count = c.end(v) - begin;
  open = count == 1 ? begin : kNone;
  if (count <= 1) return true;
  std::uint32_t links = 0;
  std::uint32_t start = begin;  // a corner no other follows, when the fan is open
  for (std::uint32_t f = begin; f < begin + count; ++f) {
    bool followed = false;
    for (std::uint32_t g = begin; g < begin + count; ++g) {
      if (g == f) continue;
      if (c.at[g].next == c.at[f].next || c.at[g].prev == c.at[f].prev) return false;  // a directed edge twice
      if (c.at[g].next == c.at[f].prev) followed = true;
    }
    if (followed) ++links;
    else start = f;
  }
  if (links + 1 < count) return false;  // two or more open fans
  if (links + 1 == count) open = start;
  // Walk the followers from `start` (any corner of a cycle): one fan reaches every corner.
  std::uint32_t seen = 1;
  for (std::uint32_t f = start;;) {
    std::uint32_t follower = kNone;
    for (std::uint32_t g = begin; g < begin + count; ++g) {
      if (c.at[g].prev == c.at[f].next) follower = g;
    }
    if (follower == kNone || follower == start) break;
    if (++seen > count) return false;
    f = follower;
  }
  return seen == count;
}

}  // namespace

std::optional<std::vector<std::vector<std::uint32_t>>> simpleManifoldBoundaryLoops(const FaceList& faces,
                                                                                    std::size_t vertex_count) {
  Corners c;
  if (!buildCorners(faces, vertex_count, c)) return std::nullopt;
  std::vector<std::uint32_t> scratch;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    if (repeatsVertex(faces, f, scratch)) return std::nullopt;
  }
  // An open fan's first corner at v has the in-edge a -> v with no face on its other side: the
  // boundary half-edge v -> a leaves v, made with the edge at corner a's position.
  struct Halfedge {
    std::uint32_t from, to, position;
  };
  std::vector<Halfedge> boundary;
  std::vector<std::uint32_t> leaving(vertex_count, kNone);
  for (std::uint32_t v = 0; v < vertex_count; ++v) {
    std::uint32_t open = kNone;
    if (!oneFan(c, v, open)) return std::nullopt;
    if (open == kNone) continue;
    leaving[v] = static_cast<std::uint32_t>(boundary.size());
    boundary.push_back({v, c.at[open].prev, c.at[open].prev_position});
  }
  std::vector<std::uint32_t> order(boundary.size());
  for (std::uint32_t h = 0; h < order.size(); ++h) order[h] = h;
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t x, std::uint32_t y) { return boundary[x].position < boundary[y].position; });
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<char> seen(boundary.size(), 0);
  for (std::uint32_t start : order) {
    if (seen[start]) continue;
    std::vector<std::uint32_t> loop;
    std::uint32_t h = start;
    do {
      seen[h] = 1;
      loop.push_back(boundary[h].from);
      h = leaving[boundary[h].to];
    } while (h != kNone && h != start && !seen[h]);
    loops.push_back(std::move(loop));
  }
  return loops;
}

bool isSimpleManifold(const FaceList& faces, std::size_t vertex_count) {
  return simpleManifoldBoundaryLoops(faces, vertex_count).has_value();
}

std::vector<std::vector<std::uint32_t>> boundaryLoopsOfFaces(const FaceList& faces, std::size_t vertex_count) {
  return simpleManifoldBoundaryLoops(faces, vertex_count).value_or(std::vector<std::vector<std::uint32_t>>{});
}

}  // namespace odeskin

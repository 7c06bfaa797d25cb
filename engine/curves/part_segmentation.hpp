// SPDX-License-Identifier: MIT
// Body parts of a rigged mesh (thesis 6.3.1): every vertex goes to its dominant bone (largest
// weight); each connected patch of one bone is a part, and patches too small to carry a curve
// join the neighbour they share most edges with. Seams are the connected sets of edges between two
// parts; a breadth-first tree over the seams gives each part a parent and an entry seam.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/types.hpp"
#include "../kernels/influences.hpp"
#include "../mesh/adjacency.hpp"
#include "../rig/rig.hpp"

namespace odeskin {

struct Seam {
  std::uint32_t parts[2] = {0, 0};     // parts[0] < parts[1]
  std::vector<std::uint32_t> vertices;  // the end vertices of its cross edges, both sides
  std::size_t cross_edges = 0;
  Vec3 centroid{0.0};  // mean of the cross edges' midpoints
  Vec3 normal{0.0};    // unit, the seam's plane normal pointing from parts[0] into parts[1]
  bool significant = false;  // enough cross edges to place a cut plane on

  Vec3 normalInto(std::uint32_t part) const { return part == parts[1] ? normal : -normal; }
  std::uint32_t other(std::uint32_t part) const { return part == parts[0] ? parts[1] : parts[0]; }
};

struct Part {
  std::uint32_t bone = 0;
  std::vector<std::uint32_t> vertices;
  Vec3 centroid{0.0};
  Vec3 axis{1.0, 0.0, 0.0};  // unit: the bone's head -> tail, or the principal axis of the vertices
  double extent = 0.0;        // bounding-box diagonal
  std::vector<std::uint32_t> seams;  // significant seams, the entry seam first
  std::int32_t parent = -1;
  std::int32_t entry_seam = -1;
};

struct Segmentation {
  std::vector<std::uint32_t> vertex_part;  // V
  std::vector<Part> parts;
  std::vector<Seam> seams;
  std::vector<std::uint32_t> order;  // every part once, breadth first from each tree's root
};

// `influences` validated for rest.size() vertices and the skeleton's bones. Parts with fewer than
// `tiny_part` vertices are merged into a neighbour; seams with fewer than `min_seam_edges` cross
// edges are not significant.
Segmentation segmentParts(std::span<const Vec3> rest, const VertexAdjacency& adjacency, const Skeleton& skeleton,
                          const Influences& influences, std::size_t tiny_part, std::size_t min_seam_edges);

// Principal axes of points (Eigen's self-adjoint solver): eigenvalues ascending, unit vectors.
struct PrincipalAxes {
  Vec3 values{0.0};
  Vec3 axes[3] = {Vec3(1.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), Vec3(0.0, 0.0, 1.0)};
};
PrincipalAxes principalAxes(std::span<const Vec3> points);

}  // namespace odeskin

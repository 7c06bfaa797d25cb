// SPDX-License-Identifier: MIT
#include "part_segmentation.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include <Eigen/Eigenvalues>
#include <glm/geometric.hpp>
#include "../core/disjoint_sets.hpp"

namespace odeskin {
namespace {

// A seam's plane is the bisector of its two parts' axes when that is within 25 degrees of the
// plane fitted to the seam.
constexpr double kBisectorCos = 0.906;

std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

std::vector<std::uint32_t> dominantBones(const Influences& influences) {
  std::vector<std::uint32_t> bones(influences.vertexCount(), 0);
  for (std::size_t i = 0; i < bones.size(); ++i) {
    double best = -1.0;
    for (std::uint32_t k = influences.offsets[i]; k < influences.offsets[i + 1]; ++k) {
      const std::uint32_t bone = influences.bones[k];
      const double w = influences.weights[k];
      if (w > best || (w == best && bone < bones[i])) {
        best = w;
        bones[i] = bone;
      }
    }
  }
  return bones;
}

// Renumbers labels to 0..R-1 in order of first appearance; returns R.
std::uint32_t compactLabels(std::vector<std::uint32_t>& labels, std::vector<std::uint32_t>* remap_out = nullptr) {
  std::vector<std::uint32_t> remap(labels.size(), std::numeric_limits<std::uint32_t>::max());
  std::uint32_t next = 0;
  for (std::uint32_t& l : labels) {
    if (remap[l] == std::numeric_limits<std::uint32_t>::max()) remap[l] = next++;
    l = remap[l];
  }
  if (remap_out) *remap_out = std::move(remap);
  return next;
}

// Connected patches of equal dominant bone; `patch_bone` receives each patch's bone.
std::vector<std::uint32_t> bonePatches(const VertexAdjacency& adjacency, const std::vector<std::uint32_t>& bones,
                                       std::vector<std::uint32_t>& patch_bone) {
  DisjointSets sets(bones.size());
  for (std::uint32_t i = 0; i < bones.size(); ++i) {
    for (std::uint32_t j : adjacency.of(i)) {
      if (bones[j] == bones[i]) sets.unite(i, j);
    }
  }
  std::vector<std::uint32_t> labels(bones.size());
  for (std::uint32_t i = 0; i < bones.size(); ++i) labels[i] = sets.find(i);
  const std::uint32_t count = compactLabels(labels);
  patch_bone.assign(count, 0);
  for (std::size_t i = 0; i < labels.size(); ++i) patch_bone[labels[i]] = bones[i];
  return labels;
}

// A patch too small to carry a curve of its own is noise in the weights (an island where two
// weights are nearly equal) or a bone with almost no skin: it joins the neighbour it shares most
// edges with, and a merged group keeps the bone of its largest member. Repeats until stable.
void mergeTinyPatches(const VertexAdjacency& adjacency, std::vector<std::uint32_t>& labels,
                      std::vector<std::uint32_t>& patch_bone, std::size_t tiny) {
  for (int pass = 0; pass < 64; ++pass) {
    const std::size_t count = patch_bone.size();
    std::vector<std::size_t> sizes(count, 0);
    for (std::uint32_t l : labels) ++sizes[l];
    std::vector<std::uint64_t> cross;  // (tiny patch, neighbour) per directed cross edge
    for (std::uint32_t i = 0; i < labels.size(); ++i) {
      if (sizes[labels[i]] >= tiny) continue;
      for (std::uint32_t j : adjacency.of(i)) {
        if (labels[j] != labels[i]) cross.push_back((static_cast<std::uint64_t>(labels[i]) << 32) | labels[j]);
      }
    }
    if (cross.empty()) return;
    std::sort(cross.begin(), cross.end());
    DisjointSets sets(count);
    for (std::size_t k = 0; k < cross.size();) {
      const auto patch = static_cast<std::uint32_t>(cross[k] >> 32);
      std::uint32_t best = 0;
      std::size_t best_count = 0;
      while (k < cross.size() && static_cast<std::uint32_t>(cross[k] >> 32) == patch) {
        const std::uint64_t key = cross[k];
        const auto neighbour = static_cast<std::uint32_t>(key & 0xffffffffu);
        std::size_t n = 0;
        for (; k < cross.size() && cross[k] == key; ++k) ++n;
        if (n > best_count || (n == best_count && sizes[neighbour] > sizes[best])) {
          best = neighbour;
          best_count = n;
        }
      }
      sets.unite(patch, best);
    }
    std::vector<std::uint32_t> largest(count);
    for (std::uint32_t p = 0; p < count; ++p) largest[p] = p;
    for (std::uint32_t p = 0; p < count; ++p) {
      const std::uint32_t root = sets.find(p);
      if (sizes[p] > sizes[largest[root]]) largest[root] = p;
    }
    std::vector<std::uint32_t> group(count);
    for (std::uint32_t p = 0; p < count; ++p) group[p] = sets.find(p);
    for (std::uint32_t& l : labels) l = group[l];
    std::vector<std::uint32_t> remap;
    const std::uint32_t merged = compactLabels(labels, &remap);
    std::vector<std::uint32_t> bones(merged);
    for (std::uint32_t p = 0; p < count; ++p) {
      // cppcheck-suppress containerOutOfBounds ; false positive: compactLabels filled remap through its pointer
      if (group[p] == p) bones[remap[p]] = patch_bone[largest[p]];
    }
    patch_bone = std::move(bones);
    if (merged == count) return;
  }
}

void describePart(std::span<const Vec3> rest, const Skeleton& skeleton, Part& part) {
  Vec3 lo(std::numeric_limits<double>::infinity());
  Vec3 hi(-std::numeric_limits<double>::infinity());
  Vec3 sum(0.0);
  std::vector<Vec3> points;
  points.reserve(part.vertices.size());
  for (std::uint32_t i : part.vertices) {
    sum += rest[i];
    lo = glm::min(lo, rest[i]);
    hi = glm::max(hi, rest[i]);
    points.push_back(rest[i]);
  }
  part.centroid = sum / static_cast<double>(part.vertices.size());
  part.extent = glm::length(hi - lo);
  const Vec3 bone = skeleton.tails[part.bone] - skeleton.heads[part.bone];
  // A bone shorter than a millionth of its part has no usable direction (tails unknown).
  if (glm::length(bone) > 1e-6 * part.extent && glm::length(bone) > 0.0) {
    part.axis = glm::normalize(bone);
  } else if (points.size() >= 2) {
    part.axis = principalAxes(points).axes[2];
  }
}

// Centroid, plane normal (from parts[0] into parts[1]) and significance of a seam from the
// midpoints of its cross edges and the sum of their directions (parts[0] side to parts[1] side).
void describeSeam(const std::vector<Vec3>& midpoints, Vec3 across, const std::vector<Part>& parts,
                  std::size_t min_seam_edges, Seam& seam) {
  Vec3 sum(0.0);
  for (const Vec3& m : midpoints) sum += m;
  seam.centroid = sum / static_cast<double>(midpoints.size());
  // A ring-like seam is close to a plane (one small principal value); otherwise the mean
  // cross-edge direction is the best guess at the direction across it.
  const PrincipalAxes pca = principalAxes(midpoints);
  if (!(glm::length(across) > 0.0)) across = parts[seam.parts[1]].centroid - parts[seam.parts[0]].centroid;
  if (pca.values[0] <= 0.25 * pca.values[1] && pca.values[1] > 0.0) {
    seam.normal = pca.axes[0];
  } else if (glm::length(across) > 0.0) {
    seam.normal = glm::normalize(across);
  } else {
    seam.normal = parts[seam.parts[1]].axis;
  }
  if (glm::dot(seam.normal, across) < 0.0) seam.normal = -seam.normal;
  // Two limb segments meeting at a joint are best split by the plane bisecting their axes; a
  // jagged seam (equal weights alternating along a ring) tilts its fitted plane, so the bisector
  // wins whenever it is close to it.
  Vec3 a = parts[seam.parts[0]].axis;
  Vec3 b = parts[seam.parts[1]].axis;
  if (glm::dot(a, seam.normal) < 0.0) a = -a;
  if (glm::dot(b, seam.normal) < 0.0) b = -b;
  if (glm::length(a + b) > 1e-9 && glm::dot(glm::normalize(a + b), seam.normal) > kBisectorCos) {
    seam.normal = glm::normalize(a + b);
  }
  seam.significant = seam.cross_edges >= min_seam_edges;
}

// Seams: per pair of parts, the connected components of their cross edges.
std::vector<Seam> findSeams(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                            const std::vector<std::uint32_t>& vertex_part, const std::vector<Part>& parts,
                            std::size_t min_seam_edges) {
  struct CrossEdge {
    std::uint64_t key;
    std::uint32_t u, v;  // u in the lower part
  };
  std::vector<CrossEdge> edges;
  for (std::uint32_t i = 0; i < vertex_part.size(); ++i) {
    for (std::uint32_t j : adjacency.of(i)) {
      if (j <= i || vertex_part[i] == vertex_part[j]) continue;
      const bool lower = vertex_part[i] < vertex_part[j];
      edges.push_back({pairKey(vertex_part[i], vertex_part[j]), lower ? i : j, lower ? j : i});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const CrossEdge& a, const CrossEdge& b) {
    return a.key != b.key ? a.key < b.key : (a.u != b.u ? a.u < b.u : a.v < b.v);
  });
  std::vector<Seam> seams;
  for (std::size_t begin = 0; begin < edges.size();) {
    std::size_t end = begin;
    while (end < edges.size() && edges[end].key == edges[begin].key) ++end;
    std::vector<std::uint32_t> verts;
    for (std::size_t k = begin; k < end; ++k) {
      verts.push_back(edges[k].u);
      verts.push_back(edges[k].v);
    }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    auto local = [&](std::uint32_t x) {
      return static_cast<std::uint32_t>(std::lower_bound(verts.begin(), verts.end(), x) - verts.begin());
    };
    DisjointSets sets(verts.size());
    for (std::size_t k = begin; k < end; ++k) sets.unite(local(edges[k].u), local(edges[k].v));
    std::vector<std::uint32_t> component(verts.size());
    for (std::uint32_t k = 0; k < verts.size(); ++k) component[k] = sets.find(k);
    const std::size_t first = seams.size();
    std::vector<std::int32_t> seam_of(verts.size(), -1);
    for (std::uint32_t k = 0; k < verts.size(); ++k) {
      if (seam_of[component[k]] < 0) {
        seam_of[component[k]] = static_cast<std::int32_t>(seams.size());
        Seam seam;
        seam.parts[0] = static_cast<std::uint32_t>(edges[begin].key >> 32);
        seam.parts[1] = static_cast<std::uint32_t>(edges[begin].key & 0xffffffffu);
        seams.push_back(seam);
      }
      seams[static_cast<std::size_t>(seam_of[component[k]])].vertices.push_back(verts[k]);
    }
    std::vector<std::vector<Vec3>> midpoints(seams.size() - first);
    std::vector<Vec3> across(seams.size() - first, Vec3(0.0));
    for (std::size_t k = begin; k < end; ++k) {
      const auto s = static_cast<std::size_t>(seam_of[component[local(edges[k].u)]]);
      ++seams[s].cross_edges;
      midpoints[s - first].push_back(0.5 * (rest[edges[k].u] + rest[edges[k].v]));
      across[s - first] += rest[edges[k].v] - rest[edges[k].u];
    }
    for (std::size_t s = first; s < seams.size(); ++s) {
      describeSeam(midpoints[s - first], across[s - first], parts, min_seam_edges, seams[s]);
    }
    begin = end;
  }
  return seams;
}

// Breadth-first over significant seams; each tree's root is the part with the most seams (a
// torso), ties going to the larger part.
void buildTree(Segmentation& seg) {
  std::vector<char> seen(seg.parts.size(), 0);
  for (;;) {
    std::int64_t root = -1;
    for (std::uint32_t p = 0; p < seg.parts.size(); ++p) {
      if (seen[p]) continue;
      if (root < 0) {
        root = p;
        continue;
      }
      const Part& a = seg.parts[p];
      const Part& b = seg.parts[static_cast<std::size_t>(root)];
      if (a.seams.size() > b.seams.size() || (a.seams.size() == b.seams.size() && a.vertices.size() > b.vertices.size())) {
        root = p;
      }
    }
    if (root < 0) return;
    std::size_t head = seg.order.size();
    seg.order.push_back(static_cast<std::uint32_t>(root));
    seen[static_cast<std::size_t>(root)] = 1;
    for (; head < seg.order.size(); ++head) {
      const std::uint32_t p = seg.order[head];
      for (std::uint32_t s : seg.parts[p].seams) {
        const std::uint32_t q = seg.seams[s].other(p);
        if (seen[q]) continue;
        seen[q] = 1;
        seg.parts[q].parent = static_cast<std::int32_t>(p);
        seg.parts[q].entry_seam = static_cast<std::int32_t>(s);
        seg.order.push_back(q);
      }
    }
  }
}

}  // namespace

PrincipalAxes principalAxes(std::span<const Vec3> points) {
  PrincipalAxes out;
  if (points.empty()) return out;
  Vec3 mean(0.0);
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& p : points) {
    const Eigen::Vector3d d(p.x - mean.x, p.y - mean.y, p.z - mean.z);
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov / static_cast<double>(points.size()));
  for (int k = 0; k < 3; ++k) {
    out.values[k] = std::max(0.0, solver.eigenvalues()[k]);
    const Eigen::Vector3d a = solver.eigenvectors().col(k);
    out.axes[k] = Vec3(a.x(), a.y(), a.z());
  }
  return out;
}

Segmentation segmentParts(std::span<const Vec3> rest, const VertexAdjacency& adjacency, const Skeleton& skeleton,
                          const Influences& influences, std::size_t tiny_part, std::size_t min_seam_edges) {
  Segmentation seg;
  std::vector<std::uint32_t> patch_bone;
  seg.vertex_part = bonePatches(adjacency, dominantBones(influences), patch_bone);
  mergeTinyPatches(adjacency, seg.vertex_part, patch_bone, tiny_part);
  seg.parts.resize(patch_bone.size());
  for (std::uint32_t i = 0; i < seg.vertex_part.size(); ++i) seg.parts[seg.vertex_part[i]].vertices.push_back(i);
  for (std::size_t p = 0; p < seg.parts.size(); ++p) {
    seg.parts[p].bone = patch_bone[p];
    describePart(rest, skeleton, seg.parts[p]);
  }
  seg.seams = findSeams(rest, adjacency, seg.vertex_part, seg.parts, min_seam_edges);
  for (std::uint32_t s = 0; s < seg.seams.size(); ++s) {
    if (!seg.seams[s].significant) continue;
    seg.parts[seg.seams[s].parts[0]].seams.push_back(s);
    seg.parts[seg.seams[s].parts[1]].seams.push_back(s);
  }
  buildTree(seg);
  for (Part& part : seg.parts) {
    auto entry = std::find(part.seams.begin(), part.seams.end(), static_cast<std::uint32_t>(part.entry_seam));
    if (part.entry_seam >= 0 && entry != part.seams.end()) std::rotate(part.seams.begin(), entry, entry + 1);
  }
  return seg;
}

}  // namespace odeskin

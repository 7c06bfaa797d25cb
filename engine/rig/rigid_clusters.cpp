// SPDX-License-Identifier: MIT
// Rigid motion clustering (bones as vertex groups that move rigidly, as in James & Twigg 2005),
// grown one batch of clusters at a time where the fit is worst, like SSDR's initialisation (Le &
// Deng 2012, section 4):
//  1. Start with one cluster: the whole mesh, one Kabsch transform per pose.
//  2. Seed new clusters in the clusters with the largest total error, each at its worst vertex,
//     with the Kabsch transforms of the kSeedPatch vertices nearest it on the mesh graph.
//  3. Lloyd rounds: each vertex joins the cluster whose transforms best reproduce it over all poses,
//     each cluster keeps only its largest connected piece (cluster_connectivity.hpp), and the
//     transforms are refitted by Kabsch. A cluster left with fewer than kMinClusterSize vertices
//     or collinear ones is re-seeded at the worst vertex.
//  4. Repeat 2-3 until the requested count, or, for an automatic count, until the RMS error stops
//     improving (see growthStops).
//  5. Clusters that still cannot hold a bone are dropped (finalise), so the count can come out
//     below the requested one on meshes with too few distinct rigid parts.
#include "rigid_clusters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <optional>
#include <span>

#include <tbb/blocked_range.h>

#include <Eigen/Dense>

#include "bone_fit.hpp"
#include "cluster_connectivity.hpp"
#include "../core/parallel.hpp"

namespace odeskin {
namespace {

constexpr std::size_t kSeedPatch = 24;
constexpr std::size_t kMinClusterSize = 6;
// Automatic count: a clustering whose RMS error is below kGoodEnoughRms of the box reproduces the
// poses far below visible error, so more bones would only split rigid parts. Otherwise growth
// continues while a batch buys at least kMinGainPerCluster of relative RMS improvement per added
// cluster (over the best count so far; a Lloyd round can land in a worse local minimum, so the
// first min_clusters are always grown). On cat-poses and horse-gallop the gain is still 1.4-2.5%
// per cluster at 27 -> 32 clusters, so they reach max_clusters.
constexpr double kGoodEnoughRms = 1e-3;
constexpr double kMinGainPerCluster = 0.01;

using Transforms = std::vector<std::vector<RigidTransform>>;  // K x C

// Per-pose Kabsch of `members` (rest -> pose k), or nothing when their points are degenerate:
// weightedKabsch with unit weights, to the bit (times 1 is exact), with the rest side's centroid
// and offsets formed once for all poses.
std::optional<std::vector<RigidTransform>> fitMembers(const MotionData& m, std::span<const std::uint32_t> members) {
  if (members.empty()) return std::nullopt;
  Vec3 from_sum(0.0);
  for (const std::uint32_t i : members) from_sum += m.rest[i];
  const auto count = static_cast<double>(members.size());
  const Vec3 from_centroid = from_sum / count;
  std::vector<Eigen::Vector3d> from(members.size());
  for (std::size_t e = 0; e < members.size(); ++e) {
    const Vec3 d = m.rest[members[e]] - from_centroid;
    from[e] = {d.x, d.y, d.z};
  }
  std::vector<RigidTransform> out;
  for (const std::vector<Vec3>& pose : *m.poses) {
    Vec3 to_sum(0.0);
    for (const std::uint32_t i : members) to_sum += pose[i];
    const Vec3 to_centroid = to_sum / count;
    Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
    for (std::size_t e = 0; e < members.size(); ++e) {
      const Vec3 d = pose[members[e]] - to_centroid;
      h.noalias() += from[e] * Eigen::Vector3d(d.x, d.y, d.z).transpose();
    }
    Result<RigidTransform> fit = kabschFromCovariance(h, from_centroid, to_centroid);
    if (!fit.ok()) return std::nullopt;
    out.push_back(fit.value());
  }
  return out;
}

// Up to `count` vertices nearest `seed` on the mesh graph (breadth first).
std::vector<std::uint32_t> patchAround(const MotionData& m, std::uint32_t seed, std::size_t count) {
  std::vector<std::uint32_t> patch{seed};
  std::vector<char> seen(m.vertexCount(), 0);
  seen[seed] = 1;
  for (std::size_t head = 0; head < patch.size() && patch.size() < count; ++head) {
    for (const std::uint32_t j : m.adjacency->of(patch[head])) {
      if (seen[j]) continue;
      seen[j] = 1;
      patch.push_back(j);
      if (patch.size() == count) break;
    }
  }
  return patch;
}

// The pose whose vertices move farthest from the bind mesh (sum of squared displacements): the
// one whose error term best tells a wrong cluster from the right one (an example pose equal to
// the bind mesh gives every cluster an error near 0).
std::size_t mostMovedPose(const MotionData& m) {
  std::size_t best = 0;
  double best_motion = -1.0;
  for (std::size_t k = 0; k < m.poseCount(); ++k) {
    double motion = 0.0;
    for (std::size_t i = 0; i < m.vertexCount(); ++i) {
      const Vec3 d = (*m.poses)[k][i] - m.rest[i];
      motion += glm::dot(d, d);
    }
    if (motion > best_motion) {
      best_motion = motion;
      best = k;
    }
  }
  return best;
}

// |T_c x - p|^2 for n transforms T_c held entry by entry (entry (column, row) at a[(3 column + row) n
// + c]), with the arithmetic of glm's product (its translation times w = 1 is exact) and dot in
// their order, into e[0, n).
void transformErrors(const double* __restrict a, std::size_t n, const Vec3& rest, const Vec3& pose, double* __restrict e) {
  const double x = rest.x, y = rest.y, z = rest.z;
  const double px = pose.x, py = pose.y, pz = pose.z;
  for (std::size_t c = 0; c < n; ++c) {
    const double dx = a[c] * x + a[3 * n + c] * y + a[6 * n + c] * z + a[9 * n + c] - px;
    const double dy = a[n + c] * x + a[4 * n + c] * y + a[7 * n + c] * z + a[10 * n + c] - py;
    const double dz = a[2 * n + c] * x + a[5 * n + c] * y + a[8 * n + c] * z + a[11 * n + c] - pz;
    e[c] = dx * dx + dy * dy + dz * dz;
  }
}

// Every vertex's fit error in every cluster for one set of transforms: sum over poses k, in
// order, of |T_{k,c} x_i - p_ki|^2.
class ClusterFit {
 public:
  ClusterFit(const MotionData& m, const Transforms& t, std::size_t probe)
      : m_(m), probe_(probe), clusters_(t[0].size()), probe_entries_(12 * clusters_) {
    const std::size_t poses = t.size();
    matrices_.resize(clusters_ * poses);
    for (std::size_t c = 0; c < clusters_; ++c) {
      for (std::size_t k = 0; k < poses; ++k) matrices_[c * poses + k] = t[k][c].matrix();
      const BoneTransform& at_probe = matrices_[c * poses + probe];
      for (int col = 0; col < 4; ++col) {
        for (int row = 0; row < 3; ++row) probe_entries_[(3 * col + row) * clusters_ + c] = at_probe[col][row];
      }
    }
  }

  std::size_t clusterCount() const { return clusters_; }

  double error(std::size_t c, std::size_t i) const {
    double e = 0.0;
    for (std::size_t k = 0; k < m_.poseCount(); ++k) e += term(c, i, k);
    return e;
  }

  // The probe pose's term of vertex i in every cluster, into `out` (clusterCount() values): the
  // arithmetic of term() (glm's product and dot, in their order), cluster by cluster in one loop
  // the compiler vectorises.
  void probeTerms(std::size_t i, std::span<double> out) const {
    const Vec3 p = (*m_.poses)[probe_][i];
    transformErrors(probe_entries_.data(), clusters_, m_.rest[i], p, out.data());
  }

  // The error, or any value above stop_above once it is known to exceed it (callers only compare
  // it with stop_above). The probe pose's term alone (`probe_term`, from probeTerms) is a lower
  // bound of the sum (adding non-negative terms never rounds below a partial sum), so it decides
  // first; below stop_above, the sum is the one error() forms, stopped as soon as it passes.
  double errorUpTo(std::size_t c, std::size_t i, double probe_term, double stop_above) const {
    if (probe_term > stop_above) return probe_term;
    double e = 0.0;
    for (std::size_t k = 0; k < m_.poseCount() && e <= stop_above; ++k) e += k == probe_ ? probe_term : term(c, i, k);
    return e;
  }
  double errorUpTo(std::size_t c, std::size_t i, double stop_above) const {
    return errorUpTo(c, i, term(c, i, probe_), stop_above);
  }

 private:
  double term(std::size_t c, std::size_t i, std::size_t k) const {
    const Vec3 d = matrices_[c * m_.poseCount() + k] * glm::dvec4(m_.rest[i], 1.0) - (*m_.poses)[k][i];
    return glm::dot(d, d);
  }

  const MotionData& m_;
  std::size_t probe_;
  std::size_t clusters_;
  std::vector<BoneTransform> matrices_;  // C x K
  std::vector<double> probe_entries_;    // the probe pose's matrices, entry (column, row) major, then cluster
};

void assignBest(const MotionData& m, const ClusterFit& fit, std::vector<std::uint32_t>& labels) {
  parallelFor(tbb::blocked_range<std::size_t>(0, m.vertexCount(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<double> probe(fit.clusterCount());
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      fit.probeTerms(i, probe);
      std::uint32_t best = labels[i];
      double best_error = fit.error(best, i);
      for (std::size_t c = 0; c < probe.size(); ++c) {
        if (c == labels[i]) continue;
        const double e = fit.errorUpTo(c, i, probe[c], best_error);
        if (e < best_error) {
          best_error = e;
          best = static_cast<std::uint32_t>(c);
        }
      }
      labels[i] = best;
    }
  });
}

void computeErrors(const MotionData& m, const Transforms& t, Clustering& out) {
  const ClusterFit fit(m, t, 0);
  out.vertex_error.resize(m.vertexCount());
  parallelFor(std::size_t{0}, m.vertexCount(), [&](std::size_t i) { out.vertex_error[i] = fit.error(out.labels[i], i); });
  const double total = std::accumulate(out.vertex_error.begin(), out.vertex_error.end(), 0.0);
  out.rms_error = std::sqrt(total / static_cast<double>(m.vertexCount() * m.poseCount())) / m.box;
}

// Seeds a cluster at the worst vertex `allowed` and not yet `used`, marking its patch used;
// nothing if no such vertex gives a non-degenerate patch.
template <typename Allowed>
std::optional<std::vector<RigidTransform>> seedCluster(const MotionData& m, const Clustering& c, Allowed allowed,
                                                       std::vector<char>& used) {
  std::vector<std::uint32_t> order;
  for (std::uint32_t i = 0; i < m.vertexCount(); ++i) {
    if (!used[i] && allowed(i)) order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return c.vertex_error[a] > c.vertex_error[b];
  });
  for (const std::uint32_t s : order) {
    if (used[s]) continue;
    const std::vector<std::uint32_t> patch = patchAround(m, s, kSeedPatch);
    for (const std::uint32_t i : patch) used[i] = 1;
    if (auto fit = fitMembers(m, patch)) return fit;
  }
  return std::nullopt;
}

// Finds where Lloyd rounds cycle. Keeping a cluster connected can leave the rounds in a cycle (a
// few hundred of the cat's vertices flipping between two clusters until the cap; the cycles seen
// in the cat and horse fits were 2 rounds long). A round's labels and transforms are all the next
// round depends on, so once a round repeats an earlier one, the state the cap would stop at is one
// of the cycle's, and it is taken from there instead of being recomputed.
class RoundCycles {
 public:
  // Whether round `round`'s state `c` repeats one of the kHorizon rounds before it; if it does,
  // `c` becomes the state round `last` would leave.
  bool skipToLast(std::size_t round, std::size_t last, Clustering& c) {
    for (std::size_t period = 2; period <= std::min(kHorizon, round); ++period) {
      if (!at(round - period).sameAs(c)) continue;
      const std::size_t at_last = round - period + (last - round) % period;
      if (at_last != round - period) {
        c.labels = at(at_last).labels;
        c.transforms = at(at_last).transforms;
      }
      return true;
    }
    State& state = at(round);  // copied into the storage of round - kHorizon
    state.labels = c.labels;
    state.transforms = c.transforms;
    return false;
  }

 private:
  static constexpr std::size_t kHorizon = 4;

  struct State {
    std::vector<std::uint32_t> labels;
    Transforms transforms;

    // Equal to the bit, so that the rounds from both states are the same rounds.
    bool sameAs(const Clustering& c) const {
      if (labels != c.labels) return false;
      for (std::size_t k = 0; k < transforms.size(); ++k) {
        const std::size_t bytes = transforms[k].size() * sizeof(RigidTransform);
        if (std::memcmp(transforms[k].data(), c.transforms[k].data(), bytes) != 0) return false;
      }
      return true;
    }
  };

  State& at(std::size_t round) { return recent_[round % kHorizon]; }

  std::array<State, kHorizon> recent_;
};

// Lloyd rounds at a fixed count, until no label changes or options.iterations rounds (or the
// state they would end with, RoundCycles); leaves the errors up to date.
void lloyd(const MotionData& m, std::size_t probe, const ClusterOptions& options, Clustering& c) {
  const int iterations = options.iterations;
  const std::size_t clusters = c.clusterCount();
  // cppcheck-suppress variableScope ; declared outside the loop so its storage is reused each iteration
  std::vector<std::uint32_t> previous;
  RoundCycles cycles;
  for (int it = 0; it < iterations; ++it) {
    ++c.lloyd_rounds;
    const ClusterFit errors(m, c.transforms, probe);
    previous = c.labels;
    assignBest(m, errors, c.labels);
    keepClustersConnected(*m.adjacency, clusters, c.labels, [&](std::uint32_t cluster, std::uint32_t i, double stop_above) {
      return errors.errorUpTo(cluster, i, stop_above);
    });
    if (it > 0 && c.labels == previous) break;
    std::vector<std::vector<std::uint32_t>> members(clusters);
    for (std::uint32_t i = 0; i < m.vertexCount(); ++i) members[c.labels[i]].push_back(i);
    std::vector<char> failed(clusters, 0);
    parallelFor(std::size_t{0}, clusters, [&](std::size_t b) {
      std::optional<std::vector<RigidTransform>> fit;
      if (members[b].size() >= kMinClusterSize) fit = fitMembers(m, members[b]);
      if (!fit) {
        failed[b] = 1;
        return;
      }
      for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k][b] = (*fit)[k];
    });
    if (std::find(failed.begin(), failed.end(), 1) != failed.end()) {
      computeErrors(m, c.transforms, c);
      std::vector<char> used(m.vertexCount(), 0);
      for (std::size_t b = 0; b < clusters; ++b) {
        if (!failed[b]) continue;
        if (auto seed = seedCluster(m, c, [](std::uint32_t) { return true; }, used)) {
          for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k][b] = (*seed)[k];
        }
      }
    }
    const auto round = static_cast<std::size_t>(it);
    if (options.skip_cycles && cycles.skipToLast(round, static_cast<std::size_t>(iterations) - 1, c)) break;
  }
  computeErrors(m, c.transforms, c);
}

bool growthStops(const ClusterOptions& options, std::size_t previous_count, double best_rms, const Clustering& c) {
  if (c.rms_error <= kGoodEnoughRms) return true;
  const double added = static_cast<double>(c.clusterCount() - previous_count);
  const double gain = (best_rms - c.rms_error) / best_rms / added;
  return c.clusterCount() >= static_cast<std::size_t>(options.min_clusters) && gain < kMinGainPerCluster;
}

// One more assignment, then clusters too small or too flat to hold a bone are dropped (their
// vertices go to the best remaining cluster) until every cluster fits; labels, transforms and
// errors then agree. `whole` is the whole mesh's fit, the last resort.
void finalise(const MotionData& m, std::size_t probe, const std::vector<RigidTransform>& whole, Clustering& c) {
  for (;;) {
    const std::size_t clusters = c.clusterCount();
    const ClusterFit errors(m, c.transforms, probe);
    assignBest(m, errors, c.labels);
    keepClustersConnected(*m.adjacency, clusters, c.labels, [&](std::uint32_t cluster, std::uint32_t i, double stop_above) {
      return errors.errorUpTo(cluster, i, stop_above);
    });
    std::vector<std::vector<std::uint32_t>> members(clusters);
    for (std::uint32_t i = 0; i < m.vertexCount(); ++i) members[c.labels[i]].push_back(i);
    std::vector<char> keep(clusters, 0);
    parallelFor(std::size_t{0}, clusters, [&](std::size_t b) {
      if (members[b].size() < kMinClusterSize) return;
      if (auto fit = fitMembers(m, members[b])) {
        keep[b] = 1;
        for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k][b] = (*fit)[k];
      }
    });
    std::vector<std::uint32_t> renumber(clusters, 0);
    std::uint32_t kept = 0;
    for (std::size_t b = 0; b < clusters; ++b) {
      if (keep[b]) renumber[b] = kept++;
    }
    if (kept == clusters) break;
    for (std::vector<RigidTransform>& pose : c.transforms) {
      std::vector<RigidTransform> next;
      for (std::size_t b = 0; b < clusters; ++b) {
        if (keep[b]) next.push_back(pose[b]);
      }
      pose = std::move(next);
    }
    if (kept == 0) {
      for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k] = {whole[k]};
    }
    for (std::uint32_t& label : c.labels) label = renumber[label];
    if (kept == 0) break;
  }
  computeErrors(m, c.transforms, c);
}

}  // namespace

Result<Clustering> clusterRigidMotion(const MotionData& m, const ClusterOptions& options) {
  Clustering c;
  c.labels.assign(m.vertexCount(), 0);
  std::vector<std::uint32_t> all(m.vertexCount());
  std::iota(all.begin(), all.end(), 0u);
  std::optional<std::vector<RigidTransform>> whole = fitMembers(m, all);
  if (!whole) return degenerate("auto rig: the mesh's vertices are collinear in some pose");
  c.transforms.resize(m.poseCount());
  for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k].push_back((*whole)[k]);
  computeErrors(m, c.transforms, c);
  const std::size_t target = options.clusters > 0 ? static_cast<std::size_t>(options.clusters)
                                                  : static_cast<std::size_t>(options.max_clusters);
  if (options.clusters == 1 || (options.clusters == 0 && c.rms_error <= kGoodEnoughRms)) return c;
  double best_rms = c.rms_error;
  const std::size_t probe = mostMovedPose(m);
  while (c.clusterCount() < target) {
    // Split where the error is: seeds go to the clusters with the largest total error.
    const std::size_t clusters = c.clusterCount();
    const std::size_t batch = std::min(target - clusters, std::max<std::size_t>(1, clusters / 4));
    std::vector<double> cluster_error(clusters, 0.0);
    for (std::size_t i = 0; i < m.vertexCount(); ++i) cluster_error[c.labels[i]] += c.vertex_error[i];
    std::vector<std::size_t> ranked(clusters);
    std::iota(ranked.begin(), ranked.end(), std::size_t{0});
    std::sort(ranked.begin(), ranked.end(), [&](std::size_t a, std::size_t b) { return cluster_error[a] > cluster_error[b]; });
    std::vector<char> used(m.vertexCount(), 0);
    std::size_t added = 0;
    for (std::size_t r = 0; r < ranked.size() && added < batch; ++r) {
      auto inside = [&](std::uint32_t i) { return c.labels[i] == ranked[r]; };
      if (auto seed = seedCluster(m, c, inside, used)) {
        for (std::size_t k = 0; k < m.poseCount(); ++k) c.transforms[k].push_back((*seed)[k]);
        ++added;
      }
    }
    if (added == 0) break;
    lloyd(m, probe, options, c);
    if (options.clusters == 0 && growthStops(options, clusters, best_rms, c)) break;
    best_rms = std::min(best_rms, c.rms_error);
  }
  finalise(m, probe, *whole, c);
  return c;
}

}  // namespace odeskin

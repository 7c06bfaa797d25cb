// SPDX-License-Identifier: MIT
#include "vertex_binding.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <queue>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>

#include "median_split.hpp"
#include "../core/parallel.hpp"

namespace odeskin {
namespace {

// A neighbour's curve extends a part's sequence when its plane is within 35 degrees of the end
// plane's, lies beyond that end by more than a tenth of a spacing and not further aside than the
// end curve's radius (or a spacing).
constexpr double kAlignedCos = 0.82;
constexpr double kMinAhead = 0.1;
// A vertex blends two curves only if its parameters on them differ by at most this.
constexpr double kMaxParameterMismatch = 0.1;
// Vertices per cluster of the pair search, and the relative slack of its bounds; parts with at most
// kPairsWithoutClusters pairs of planes are not clustered but cut in chunks of kChunkVertices.
constexpr std::uint32_t kClusterVertices = 32;
constexpr long kPairsWithoutClusters = 16;
constexpr std::uint32_t kChunkVertices = 256;
constexpr double kBoundSlack = 1e-9;
// Curves with at most this many segments are scanned behind two levels of balls (each holding
// kBallFanout consecutive segments, or balls) rather than searched through a tree: on the cat
// subdivided up to 1.8 million vertices, whose curves reach a few hundred segments, the scan
// spends less time than the tree did from 128 segments on.
constexpr std::size_t kScanSegments = 4096;
constexpr std::size_t kBallFanout = 8;

bool inSequence(const std::vector<Station>& seq, std::uint32_t curve) {
  return std::any_of(seq.begin(), seq.end(), [&](const Station& s) { return s.curve == curve; });
}

std::vector<Station> extendedSequence(std::uint32_t p, const Segmentation& seg, const CurveLayout& layout,
                                      double spacing) {
  const std::vector<Station>& seq = layout.sequences[p];
  std::vector<Station> out = seq;
  if (seq.empty()) return out;
  for (int end = 0; end < 2; ++end) {
    const Station& s = end == 0 ? seq.front() : seq.back();
    const CurveDraft& own = layout.curves[s.curve];
    const double ahead_sign = end == 0 ? -1.0 : 1.0;
    std::optional<Station> best;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::uint32_t seam : seg.parts[p].seams) {
      for (const Station& t : layout.sequences[seg.seams[seam].other(p)]) {
        if (inSequence(seq, t.curve)) continue;
        const double aligned = glm::dot(t.plane.normal, s.plane.normal);
        const Vec3 offset = t.plane.origin - s.plane.origin;
        const double along = glm::dot(s.plane.normal, offset);
        const double aside = glm::length(offset - along * s.plane.normal);
        if (std::abs(aligned) < kAlignedCos || ahead_sign * along <= kMinAhead * spacing ||
            aside > std::max(own.radius, spacing) ||
            glm::dot(layout.curves[t.curve].orientation, own.orientation) <= 0.0) {
          continue;
        }
        const double distance = glm::length(offset);
        if (distance < best_distance) {
          best_distance = distance;
          best = Station{t.curve, {t.plane.origin, aligned < 0.0 ? -t.plane.normal : t.plane.normal}};
        }
      }
    }
    if (!best) continue;
    if (end == 0) out.insert(out.begin(), *best);
    else out.push_back(*best);
  }
  return out;
}

// Segment j of a curve (from point j to the next, the last of a closed curve back to the first),
// with what the nearest-point search reads precomputed.
struct Segment {
  Vec3 p0{0.0};
  Vec3 step{0.0};
  double len2 = 0.0;
  double v0 = 0.0, v1 = 0.0;
  Vec3 mid{0.0};      // p0 + step / 2
  double half = 0.0;  // |step| / 2: the segment lies within `half` of `mid`
};

std::vector<Segment> curveSegments(const std::vector<Vec3>& pos, const CurveDraft& curve) {
  const std::size_t n = pos.size();
  const std::size_t count = curve.closed ? n : (n > 0 ? n - 1 : 0);
  std::vector<Segment> out(count);
  for (std::size_t j = 0; j < count; ++j) {
    Segment& g = out[j];
    g.p0 = pos[j];
    g.step = pos[(j + 1) % n] - g.p0;
    g.len2 = glm::dot(g.step, g.step);
    g.v0 = curve.v[j];
    g.v1 = j + 1 == n ? 1.0 : curve.v[j + 1];
    g.mid = g.p0 + 0.5 * g.step;
    g.half = 0.5 * std::sqrt(g.len2);
  }
  return out;
}

// The point of a segment nearest to q: its squared distance and where it is on the segment.
struct SegmentHit {
  double dist2 = std::numeric_limits<double>::infinity();
  double s = 0.0;
  std::size_t j = std::numeric_limits<std::size_t>::max();  // none
};

SegmentHit segmentHit(const Segment& g, std::size_t j, const Vec3& q) {
  const double s = g.len2 > 0.0 ? std::clamp(glm::dot(q - g.p0, g.step) / g.len2, 0.0, 1.0) : 0.0;
  const Vec3 d = g.p0 + s * g.step - q;
  return {glm::dot(d, d), s, j};
}

// v at a hit (0 for none).
double hitParameter(const std::vector<Segment>& segments, const SegmentHit& hit) {
  if (hit.j >= segments.size()) return 0.0;
  const Segment& g = segments[hit.j];
  return g.v0 + hit.s * (g.v1 - g.v0);
}

// Far more than the rounding of any distance between points of a curve's segments: 1e-9 of their
// largest coordinate. Distance bounds are loosened by it, so that a bound never excludes a segment
// the exact test would find as near.
double roundingPad(const std::vector<Segment>& segments) {
  double extent = 0.0;
  for (const Segment& g : segments) {
    const Vec3 far = glm::max(glm::abs(g.p0), glm::abs(g.p0 + g.step));
    extent = std::max({extent, far.x, far.y, far.z});
  }
  return 1e-9 * extent;
}

// A ball around kBallFanout consecutive items (the last ball: those left), each item a segment (its
// midpoint and half length) or a smaller ball: every item lies inside, with a margin far beyond
// rounding, so a point further than d + radius from the centre is further than d from every item.
struct Ball {
  Vec3 centre{0.0};
  double radius = 0.0;
};

std::vector<Ball> enclosingBalls(const std::vector<Ball>& items, double pad) {
  std::vector<Ball> out;
  out.reserve((items.size() + kBallFanout - 1) / kBallFanout);
  for (std::size_t first = 0; first < items.size(); first += kBallFanout) {
    const std::size_t end = std::min(items.size(), first + kBallFanout);
    Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (std::size_t j = first; j < end; ++j) {
      lo = glm::min(lo, items[j].centre);
      hi = glm::max(hi, items[j].centre);
    }
    Ball ball{0.5 * (lo + hi), 0.0};
    for (std::size_t j = first; j < end; ++j) {
      ball.radius = std::max(ball.radius, glm::length(items[j].centre - ball.centre) + items[j].radius);
    }
    ball.radius = ball.radius * (1.0 + 1e-9) + pad;
    out.push_back(ball);
  }
  return out;
}

// A curve's balls: `fine` around its segments, `coarse` around the fine ones.
struct CurveBalls {
  std::vector<Ball> fine;
  std::vector<Ball> coarse;
};

CurveBalls curveBalls(const std::vector<Segment>& segments, double pad) {
  std::vector<Ball> items;
  items.reserve(segments.size());
  for (const Segment& g : segments) items.push_back({g.mid, g.half});
  CurveBalls out;
  out.fine = enclosingBalls(items, pad);
  out.coarse = enclosingBalls(out.fine, pad);
  return out;
}

// Nearest-segment queries on one curve: a bounding-box tree over its segments, which finds the
// segment a scan in index order would (the first of equally near ones) in about log(points) steps
// instead of one step per point (a curve has ~sqrt(V) points, and every vertex asks twice).
class SegmentTree {
 public:
  SegmentTree() = default;  // no segments
  explicit SegmentTree(const std::vector<Segment>& segments) {
    const std::size_t count = segments.size();
    if (count == 0) return;
    std::vector<Vec3> lo(count), hi(count), centre(count);
    for (std::size_t j = 0; j < count; ++j) {
      const Vec3 p1 = segments[j].p0 + segments[j].step;
      lo[j] = glm::min(segments[j].p0, p1);
      hi[j] = glm::max(segments[j].p0, p1);
      centre[j] = 0.5 * (lo[j] + hi[j]);
    }
    // Rounding puts a computed point of a segment at most a few ulps of the coordinates outside its
    // box; padding the boxes far beyond that keeps every box distance a lower bound.
    pad_ = roundingPad(segments);
    order_.resize(count);
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.reserve(count);
    build(lo, hi, centre, 0, static_cast<std::uint32_t>(count));
  }

  // The segment a scan in index order finds nearest to q (the first of equally near ones); no
  // segment (j out of range) for a curve without segments.
  // `seed`: a segment to try first (any index; one near q makes the search prune at once).
  SegmentHit nearest(const std::vector<Segment>& segments, const Vec3& q,
                     std::size_t seed = std::numeric_limits<std::size_t>::max()) const {
    SegmentHit best;
    if (nodes_.empty()) return best;
    if (seed < segments.size()) best = segmentHit(segments[seed], seed, q);
    struct Entry {
      std::uint32_t node;
      double distance2;
    };
    Entry stack[64];
    int top = 0;
    stack[top++] = {0, boxDistance2(nodes_[0], q)};
    while (top > 0) {
      const Entry entry = stack[--top];
      if (entry.distance2 > best.dist2 * (1.0 + 1e-12)) continue;
      const Node& node = nodes_[entry.node];
      if (node.count > 0) {
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
          const std::size_t j = order_[k];
          const SegmentHit hit = segmentHit(segments[j], j, q);
          const bool found = best.j != std::numeric_limits<std::size_t>::max();
          if (hit.dist2 < best.dist2 || (found && hit.dist2 == best.dist2 && j < best.j)) best = hit;
        }
        continue;
      }
      // Nearer child last, so that it is searched first.
      const Entry first{entry.node + 1, boxDistance2(nodes_[entry.node + 1], q)};
      const Entry second{node.right, boxDistance2(nodes_[node.right], q)};
      stack[top++] = first.distance2 < second.distance2 ? second : first;
      stack[top++] = first.distance2 < second.distance2 ? first : second;
    }
    return best;
  }

 private:
  struct Node {
    Vec3 lo{0.0}, hi{0.0};
    std::uint32_t first = 0, count = 0;  // leaf: range of order_
    std::uint32_t right = 0;             // inner: second child (the first follows the node)
  };
  static constexpr std::uint32_t kLeafSegments = 4;

  double boxDistance2(const Node& node, const Vec3& q) const {
    const Vec3 below = glm::max(node.lo - pad_ - q, Vec3(0.0));
    const Vec3 above = glm::max(q - node.hi - pad_, Vec3(0.0));
    const Vec3 d = below + above;
    return glm::dot(d, d);
  }

  std::uint32_t build(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi, const std::vector<Vec3>& centre,
                      std::uint32_t first, std::uint32_t last) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Vec3 box_lo(std::numeric_limits<double>::infinity()), box_hi(-std::numeric_limits<double>::infinity());
    Vec3 c_lo = box_lo, c_hi = box_hi;
    for (std::uint32_t k = first; k < last; ++k) {
      box_lo = glm::min(box_lo, lo[order_[k]]);
      box_hi = glm::max(box_hi, hi[order_[k]]);
      c_lo = glm::min(c_lo, centre[order_[k]]);
      c_hi = glm::max(c_hi, centre[order_[k]]);
    }
    nodes_[index].lo = box_lo;
    nodes_[index].hi = box_hi;
    if (last - first <= kLeafSegments) {
      nodes_[index].first = first;
      nodes_[index].count = last - first;
      return index;
    }
    const Vec3 spread = c_hi - c_lo;
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const std::uint32_t middle = first + (last - first) / 2;
    std::nth_element(order_.begin() + first, order_.begin() + middle, order_.begin() + last,
                     [&](std::uint32_t a, std::uint32_t b) { return centre[a][axis] < centre[b][axis]; });
    build(lo, hi, centre, first, middle);
    nodes_[index].right = build(lo, hi, centre, middle, last);
    return index;
  }

  double pad_ = 0.0;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

// x moved onto `plane` along its normal.
Vec3 projectOnto(const Plane& plane, const Vec3& x) { return x - glm::dot(x - plane.origin, plane.normal) * plane.normal; }

// v as a parameter of the (closed or open) curve.
double wrapParameter(const CurveDraft& curve, double v) {
  if (curve.closed && v >= 1.0) v -= 1.0;
  return std::clamp(v, 0.0, 1.0);
}

// Vertices near one another have their nearest segments near one another: the nearest segment of
// the previous query on a curve seeds the next query's search (any seed gives the same answer).
class SeedCache {
 public:
  std::uint32_t& operator[](std::uint32_t curve) {
    for (auto& [c, j] : slots_) {
      if (c == curve) return j;
    }
    next_ = (next_ + 1) % kSlots;
    slots_[next_] = {curve, kNone};
    return slots_[next_].second;
  }

 private:
  static constexpr std::size_t kSlots = 8;
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::pair<std::uint32_t, std::uint32_t> slots_[kSlots] = {{kNone, kNone}, {kNone, kNone}, {kNone, kNone}, {kNone, kNone},
                                                           {kNone, kNone}, {kNone, kNone}, {kNone, kNone}, {kNone, kNone}};
  std::size_t next_ = 0;
};

double blendParameters(double va, double vb, double w, bool closed) {
  if (!closed) return std::clamp((1.0 - w) * va + w * vb, 0.0, 1.0);
  double diff = vb - va;
  diff -= std::round(diff);  // the short way round, in [-0.5, 0.5]
  double v = va + w * diff;
  v -= std::floor(v);
  return v < 1.0 ? v : 0.0;
}

// The part whose curves each vertex uses: its own if it has any, else the first part with curves
// reached along mesh edges (-1 where none is).
// `all_sources`: queue every source, as the plain algorithm does (the reference search).
std::vector<std::int32_t> bindingParts(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                                       const Segmentation& seg, const std::vector<std::vector<Station>>& ext,
                                       bool all_sources) {
  const std::size_t count = rest.size();
  std::vector<std::int32_t> label(count, -1);
  std::vector<double> dist(count, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  // Vertices of curved parts are sources at distance 0. Only those next to a vertex of a part
  // without curves can relax anything (all others' neighbours are sources too), so only they are
  // queued; they leave the queue in the same order as when every source was queued.
  for (std::uint32_t i = 0; i < count; ++i) {
    if (ext[seg.vertex_part[i]].empty()) continue;
    label[i] = static_cast<std::int32_t>(seg.vertex_part[i]);
    dist[i] = 0.0;
  }
  for (std::uint32_t i = 0; i < count; ++i) {
    if (label[i] < 0) continue;
    const auto of = adjacency.of(i);
    if (all_sources || std::any_of(of.begin(), of.end(), [&](std::uint32_t j) { return label[j] < 0; })) {
      queue.push({0.0, i});
    }
  }
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > dist[i]) continue;
    for (std::uint32_t j : adjacency.of(i)) {
      const double nd = d + glm::length(rest[j] - rest[i]);
      if (nd < dist[j]) {
        dist[j] = nd;
        label[j] = label[i];
        queue.push({nd, j});
      }
    }
  }
  return label;
}

class Binder {
 public:
  // kExhaustive: every parameter by a scan of the whole curve; kPrunedTrees: every curve's nearest
  // segment through its tree.
  Binder(std::span<const Vec3> rest, const CurveLayout& layout, double spacing, BindingSearch search)
      : layout_(layout), spacing_(spacing), exhaustive_(search == BindingSearch::kExhaustive),
        positions_(layout.curves.size()) {
    segments_.reserve(layout.curves.size());
    trees_.reserve(layout.curves.size());
    balls_.reserve(layout.curves.size());
    uses_tree_.reserve(layout.curves.size());
    for (std::size_t c = 0; c < layout.curves.size(); ++c) {
      for (const CurvePoint& point : layout.curves[c].points) positions_[c].push_back(curvePointPosition(rest, point));
      segments_.push_back(curveSegments(positions_[c], layout.curves[c]));
      pads_.push_back(roundingPad(segments_[c]));
      // Curves up to kScanSegments are scanned (scanNearest) and need no tree.
      uses_tree_.push_back(search == BindingSearch::kPrunedTrees || segments_[c].size() > kScanSegments ? 1 : 0);
      if (uses_tree_.back()) {
        trees_.emplace_back(segments_[c]);
        balls_.emplace_back();
      } else {
        trees_.emplace_back();
        balls_.push_back(curveBalls(segments_[c], pads_[c]));
      }
    }
  }

  // v of the point of the curve nearest to x moved onto `plane` along its normal.
  double parameter(std::uint32_t curve, const Plane& plane, const Vec3& x, SeedCache* seeds = nullptr) const {
    const std::vector<Segment>& segments = segments_[curve];
    const Vec3 q = projectOnto(plane, x);
    if (exhaustive_) {
      SegmentHit best;
      for (std::size_t j = 0; j < segments.size(); ++j) {
        const SegmentHit hit = segmentHit(segments[j], j, q);
        if (hit.dist2 < best.dist2) best = hit;
      }
      return wrapParameter(layout_.curves[curve], hitParameter(segments, best));
    }
    std::uint32_t no_seed = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t& seed = seeds ? (*seeds)[curve] : no_seed;
    const SegmentHit hit = uses_tree_[curve] ? trees_[curve].nearest(segments, q, seed) : scanNearest(curve, q, seed);
    if (hit.j < segments.size()) seed = static_cast<std::uint32_t>(hit.j);
    return wrapParameter(layout_.curves[curve], hitParameter(segments, hit));
  }

  // A short curve's nearest segment by a scan that starts from `seed` and rejects, without the
  // exact test, every segment whose midpoint is further than sqrt(best) + half + pad: the first of
  // equally near segments, as the tree finds it. A ball further than sqrt(best) + pad + its radius
  // holds only segments that test would reject, and is passed over whole.
  SegmentHit scanNearest(std::uint32_t curve, const Vec3& q, std::size_t seed) const {
    const std::vector<Segment>& segments = segments_[curve];
    const double pad = pads_[curve];
    SegmentHit best;
    double reach = std::numeric_limits<double>::infinity();
    auto consider = [&](std::size_t j) {
      const Segment& g = segments[j];
      const Vec3 e = q - g.mid;
      const double bound = reach + g.half;
      if (glm::dot(e, e) > bound * bound) return;
      const SegmentHit hit = segmentHit(g, j, q);
      if (hit.dist2 < best.dist2 || (hit.dist2 == best.dist2 && j < best.j)) {
        best = hit;
        reach = std::sqrt(best.dist2) + pad;
      }
    };
    auto beyond = [&](const Ball& ball) {
      const Vec3 e = q - ball.centre;
      const double bound = reach + ball.radius;
      return glm::dot(e, e) > bound * bound;
    };
    if (seed < segments.size()) consider(seed);
    const CurveBalls& balls = balls_[curve];
    for (std::size_t g = 0; g < balls.coarse.size(); ++g) {
      if (beyond(balls.coarse[g])) continue;
      const std::size_t fine_end = std::min(balls.fine.size(), (g + 1) * kBallFanout);
      for (std::size_t b = g * kBallFanout; b < fine_end; ++b) {
        if (beyond(balls.fine[b])) continue;
        const std::size_t end = std::min(segments.size(), (b + 1) * kBallFanout);
        for (std::size_t j = b * kBallFanout; j < end; ++j) consider(j);
      }
    }
    return best;
  }

  CurveBinding alone(std::uint32_t curve, const Plane& plane, const Vec3& x, SeedCache* seeds = nullptr) const {
    return {curve, curve, 0.0, parameter(curve, plane, x, seeds)};
  }

  // Not connected to any curved part: the curve with the nearest point, alone.
  CurveBinding nearestCurve(const Vec3& x) const {
    std::uint32_t best_curve = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t c = 0; c < layout_.curves.size(); ++c) {
      for (const Vec3& p : positions_[c]) {
        if (glm::length(p - x) < best) {
          best = glm::length(p - x);
          best_curve = c;
        }
      }
    }
    const CurveDraft& curve = layout_.curves[best_curve];
    return alone(best_curve, {curve.centroid, curve.orientation}, x);
  }

  // The vertex at x of a part whose extended sequence is `seq`; `candidates` holds, ascending, at
  // least every pair k (stations k, k+1) that can have x between its planes (see bindVertices).
  CurveBinding bind(const std::vector<Station>& seq, std::span<const std::uint32_t> candidates, const Vec3& x,
                    SeedCache& seeds) const {
    auto distance = [&](std::size_t k) { return glm::dot(seq[k].plane.normal, x - seq[k].plane.origin); };
    // The tightest pair of consecutive planes with the vertex between them (rounding must not
    // push a vertex on a plane, a rim or a ring, out of its pair); curves of opposite sense,
    // where two parts' conventions meet, cannot share v and are not paired.
    const double on_plane = 1e-9 * spacing_;
    std::size_t pair = seq.size();
    double best_gap = std::numeric_limits<double>::infinity();
    double d_pair = 0.0;
    for (std::uint32_t k : candidates) {
      const double dk = distance(k);
      const double dk1 = distance(k + 1);
      if (dk < -on_plane || dk1 > on_plane) continue;
      const double gap = std::max(0.0, dk - dk1);
      if (gap < best_gap) {
        best_gap = gap;
        pair = k;
        d_pair = dk;
      }
    }
    if (pair == seq.size()) {
      // Beyond the sequence (a tip, a rim) or between planes that do not pair: the nearest plane.
      std::size_t nearest = 0;
      double nearest_distance = std::abs(distance(0));
      for (std::size_t k = 1; k < seq.size(); ++k) {
        const double dk = std::abs(distance(k));
        if (dk < nearest_distance) {
          nearest = k;
          nearest_distance = dk;
        }
      }
      return alone(seq[nearest].curve, seq[nearest].plane, x, &seeds);
    }
    const Station& sa = seq[pair];
    const Station& sb = seq[pair + 1];
    const CurveDraft& ca = layout_.curves[sa.curve];
    const CurveDraft& cb = layout_.curves[sb.curve];
    const double w = best_gap > 0.0 ? std::clamp(d_pair / best_gap, 0.0, 1.0) : 0.0;
    const double va = parameter(sa.curve, sa.plane, x, &seeds);
    const double vb = parameter(sb.curve, sb.plane, x, &seeds);
    const bool both_closed = ca.closed && cb.closed;
    // One v serves both series only where the curves' parameters agree at this vertex (an arc
    // next to a full ring, or two rings whose starts drifted apart, do not): else the nearer
    // curve alone.
    if (std::abs(both_closed ? va - vb - std::round(va - vb) : va - vb) > kMaxParameterMismatch) {
      return w <= 0.5 ? CurveBinding{sa.curve, sa.curve, 0.0, va} : CurveBinding{sb.curve, sb.curve, 0.0, vb};
    }
    return {sa.curve, sb.curve, w, blendParameters(va, vb, w, both_closed)};
  }

  // Pairs k of `seq` whose curves run the same way round (the others never pair).
  std::vector<char> pairable(const std::vector<Station>& seq) const {
    std::vector<char> out(!seq.empty() ? seq.size() - 1 : 0, 0);
    for (std::size_t k = 0; k + 1 < seq.size(); ++k) {
      out[k] = glm::dot(layout_.curves[seq[k].curve].orientation, layout_.curves[seq[k + 1].curve].orientation) > 0.0;
    }
    return out;
  }

 private:
  const CurveLayout& layout_;
  double spacing_;
  bool exhaustive_;
  std::vector<std::vector<Vec3>> positions_;
  std::vector<std::vector<Segment>> segments_;
  std::vector<double> pads_;
  std::vector<SegmentTree> trees_;
  std::vector<char> uses_tree_;
  std::vector<CurveBalls> balls_;  // of the curves scanned (none for those with a tree)
};

}  // namespace

std::vector<CurveBinding> bindVertices(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                                       const Segmentation& seg, const CurveLayout& layout, double spacing,
                                       BindingSearch search) {
  const bool exhaustive = search == BindingSearch::kExhaustive;
  std::vector<std::vector<Station>> ext(seg.parts.size());
  for (std::uint32_t p = 0; p < seg.parts.size(); ++p) ext[p] = extendedSequence(p, seg, layout, spacing);
  const std::vector<std::int32_t> part_of = bindingParts(rest, adjacency, seg, ext, exhaustive);
  const Binder binder(rest, layout, spacing, search);
  std::vector<CurveBinding> bindings(rest.size());
  std::vector<std::vector<char>> pairable(seg.parts.size());
  for (std::uint32_t p = 0; p < seg.parts.size(); ++p) pairable[p] = binder.pairable(ext[p]);
  if (exhaustive) {
    std::vector<std::vector<std::uint32_t>> every_pair(seg.parts.size());
    for (std::uint32_t p = 0; p < seg.parts.size(); ++p) {
      for (std::uint32_t k = 0; k < pairable[p].size(); ++k) {
        if (pairable[p][k]) every_pair[p].push_back(k);
      }
    }
    SeedCache unused;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const auto p = static_cast<std::size_t>(part_of[i]);
      bindings[i] = part_of[i] < 0 ? binder.nearestCurve(rest[i]) : binder.bind(ext[p], every_pair[p], rest[i], unused);
    }
    return bindings;
  }

  // A part's sequence has ~extent / spacing stations, which grows with the mesh's resolution, and
  // a vertex lies between few of them. Vertices are grouped in small clusters (a k-d split of each
  // part's vertices); a pair of planes that cannot enclose any point of a cluster's bounding
  // sphere (each signed distance moves by at most the radius) is not tried for its vertices, so
  // the pair each vertex gets is the one a scan of every pair finds.
  // Parts with few pairs skip the clustering: every vertex tries all of them.
  std::vector<std::vector<std::uint32_t>> members(seg.parts.size());
  std::vector<std::uint32_t> unconnected;
  for (std::uint32_t i = 0; i < rest.size(); ++i) {
    if (part_of[i] < 0) unconnected.push_back(i);
    else members[static_cast<std::size_t>(part_of[i])].push_back(i);
  }
  struct Cluster {
    std::uint32_t part = 0;
    std::uint32_t first = 0, last = 0;  // range of members[part]
    bool every_pair = false;            // no bounds: try every pair
  };
  std::vector<Cluster> clusters;
  for (std::uint32_t p = 0; p < seg.parts.size(); ++p) {
    std::vector<std::uint32_t>& verts = members[p];
    if (std::count(pairable[p].begin(), pairable[p].end(), 1) <= kPairsWithoutClusters) {
      for (std::uint32_t first = 0; first < verts.size(); first += kChunkVertices) {
        clusters.push_back({p, first, std::min<std::uint32_t>(first + kChunkVertices, static_cast<std::uint32_t>(verts.size())), true});
      }
      continue;
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges{{0u, static_cast<std::uint32_t>(verts.size())}};
    while (!ranges.empty()) {
      const auto [first, last] = ranges.back();
      ranges.pop_back();
      if (last - first <= kClusterVertices) {
        if (last > first) clusters.push_back({p, first, last, false});
        continue;
      }
      const std::uint32_t middle = splitAtMedian(verts, rest, first, last);
      ranges.emplace_back(first, middle);
      ranges.emplace_back(middle, last);
    }
  }
  parallelFor(tbb::blocked_range<std::size_t>(0, clusters.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::uint32_t> candidates;
    SeedCache seeds;
    for (std::size_t c = r.begin(); c < r.end(); ++c) {
      const Cluster& cluster = clusters[c];
      const std::vector<Station>& seq = ext[cluster.part];
      const std::vector<std::uint32_t>& verts = members[cluster.part];
      if (cluster.every_pair) {
        candidates.clear();
        for (std::uint32_t k = 0; k < pairable[cluster.part].size(); ++k) {
          if (pairable[cluster.part][k]) candidates.push_back(k);
        }
        for (std::uint32_t k = cluster.first; k < cluster.last; ++k) {
          bindings[verts[k]] = binder.bind(seq, candidates, rest[verts[k]], seeds);
        }
        continue;
      }
      Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
      for (std::uint32_t k = cluster.first; k < cluster.last; ++k) {
        lo = glm::min(lo, rest[verts[k]]);
        hi = glm::max(hi, rest[verts[k]]);
      }
      const Vec3 centre = 0.5 * (lo + hi);
      const double radius = 0.5 * glm::length(hi - lo);
      const double on_plane = 1e-9 * spacing;
      candidates.clear();
      for (std::size_t k = 0; k + 1 < seq.size(); ++k) {
        if (!pairable[cluster.part][k]) continue;
        const Plane& a = seq[k].plane;
        const Plane& b = seq[k + 1].plane;
        // Far more than the rounding of either signed distance.
        const double slack_a = kBoundSlack * (radius + glm::length(centre - a.origin) + glm::length(a.origin));
        const double slack_b = kBoundSlack * (radius + glm::length(centre - b.origin) + glm::length(b.origin));
        if (glm::dot(a.normal, centre - a.origin) + radius + slack_a < -on_plane) continue;
        if (glm::dot(b.normal, centre - b.origin) - radius - slack_b > on_plane) continue;
        candidates.push_back(static_cast<std::uint32_t>(k));
      }
      for (std::uint32_t k = cluster.first; k < cluster.last; ++k) {
        const std::uint32_t i = verts[k];
        bindings[i] = binder.bind(seq, candidates, rest[i], seeds);
      }
    }
  });
  parallelFor(std::size_t{0}, unconnected.size(), [&](std::size_t k) {
    bindings[unconnected[k]] = binder.nearestCurve(rest[unconnected[k]]);
  });
  return bindings;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "vertex_binding.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <queue>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// A neighbour's curve extends a part's sequence when its plane is within 35 degrees of the end
// plane's, lies beyond that end by more than a tenth of a spacing and not further aside than the
// end curve's radius (or a spacing).
constexpr double kAlignedCos = 0.82;
constexpr double kMinAhead = 0.1;
// A vertex blends two curves only if its parameters on them differ by at most this.
constexpr double kMaxParameterMismatch = 0.1;

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

// v of the point of the curve nearest to x moved onto `plane` along its normal.
double parameterAt(const std::vector<Vec3>& pos, const CurveDraft& curve, const Plane& plane, const Vec3& x) {
  const Vec3 q = x - glm::dot(x - plane.origin, plane.normal) * plane.normal;
  const std::size_t n = pos.size();
  double best = std::numeric_limits<double>::infinity();
  double v = 0.0;
  for (std::size_t j = 0; j + (curve.closed ? 0 : 1) < n; ++j) {
    const Vec3& p0 = pos[j];
    const Vec3 seg = pos[(j + 1) % n] - p0;
    const double v0 = curve.v[j];
    const double v1 = j + 1 == n ? 1.0 : curve.v[j + 1];
    const double len2 = glm::dot(seg, seg);
    const double s = len2 > 0.0 ? std::clamp(glm::dot(q - p0, seg) / len2, 0.0, 1.0) : 0.0;
    const Vec3 d = p0 + s * seg - q;
    const double dist2 = glm::dot(d, d);
    if (dist2 < best) {
      best = dist2;
      v = v0 + s * (v1 - v0);
    }
  }
  if (curve.closed && v >= 1.0) v -= 1.0;
  return std::clamp(v, 0.0, 1.0);
}

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
std::vector<std::int32_t> bindingParts(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                                       const Segmentation& seg, const std::vector<std::vector<Station>>& ext) {
  const std::size_t count = rest.size();
  std::vector<std::int32_t> label(count, -1);
  std::vector<double> dist(count, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (ext[seg.vertex_part[i]].empty()) continue;
    label[i] = static_cast<std::int32_t>(seg.vertex_part[i]);
    dist[i] = 0.0;
    queue.push({0.0, i});
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
  Binder(std::span<const Vec3> rest, const CurveLayout& layout, double spacing)
      : layout_(layout), spacing_(spacing), positions_(layout.curves.size()) {
    for (std::size_t c = 0; c < layout.curves.size(); ++c) {
      for (const CurvePoint& point : layout.curves[c].points) positions_[c].push_back(curvePointPosition(rest, point));
    }
  }

  CurveBinding alone(std::uint32_t curve, const Plane& plane, const Vec3& x) const {
    return {curve, curve, 0.0, parameterAt(positions_[curve], layout_.curves[curve], plane, x)};
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

  CurveBinding bind(const std::vector<Station>& seq, const Vec3& x) {
    d_.resize(seq.size());
    for (std::size_t k = 0; k < seq.size(); ++k) d_[k] = glm::dot(seq[k].plane.normal, x - seq[k].plane.origin);
    // The tightest pair of consecutive planes with the vertex between them (rounding must not
    // push a vertex on a plane, a rim or a ring, out of its pair); curves of opposite sense,
    // where two parts' conventions meet, cannot share v and are not paired.
    const double on_plane = 1e-9 * spacing_;
    std::size_t pair = seq.size();
    double best_gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k + 1 < seq.size(); ++k) {
      if (d_[k] < -on_plane || d_[k + 1] > on_plane) continue;
      if (glm::dot(layout_.curves[seq[k].curve].orientation, layout_.curves[seq[k + 1].curve].orientation) <= 0.0) continue;
      const double gap = std::max(0.0, d_[k] - d_[k + 1]);
      if (gap < best_gap) {
        best_gap = gap;
        pair = k;
      }
    }
    if (pair == seq.size()) {
      // Beyond the sequence (a tip, a rim) or between planes that do not pair: the nearest plane.
      std::size_t nearest = 0;
      for (std::size_t k = 1; k < seq.size(); ++k) {
        if (std::abs(d_[k]) < std::abs(d_[nearest])) nearest = k;
      }
      return alone(seq[nearest].curve, seq[nearest].plane, x);
    }
    const Station& sa = seq[pair];
    const Station& sb = seq[pair + 1];
    const CurveDraft& ca = layout_.curves[sa.curve];
    const CurveDraft& cb = layout_.curves[sb.curve];
    const double w = best_gap > 0.0 ? std::clamp(d_[pair] / best_gap, 0.0, 1.0) : 0.0;
    const double va = parameterAt(positions_[sa.curve], ca, sa.plane, x);
    const double vb = parameterAt(positions_[sb.curve], cb, sb.plane, x);
    const bool both_closed = ca.closed && cb.closed;
    // One v serves both series only where the curves' parameters agree at this vertex (an arc
    // next to a full ring, or two rings whose starts drifted apart, do not): else the nearer
    // curve alone.
    if (std::abs(both_closed ? va - vb - std::round(va - vb) : va - vb) > kMaxParameterMismatch) {
      return w <= 0.5 ? CurveBinding{sa.curve, sa.curve, 0.0, va} : CurveBinding{sb.curve, sb.curve, 0.0, vb};
    }
    return {sa.curve, sb.curve, w, blendParameters(va, vb, w, both_closed)};
  }

 private:
  const CurveLayout& layout_;
  double spacing_;
  std::vector<std::vector<Vec3>> positions_;
  std::vector<double> d_;
};

}  // namespace

std::vector<CurveBinding> bindVertices(std::span<const Vec3> rest, const VertexAdjacency& adjacency,
                                       const Segmentation& seg, const CurveLayout& layout, double spacing) {
  std::vector<std::vector<Station>> ext(seg.parts.size());
  for (std::uint32_t p = 0; p < seg.parts.size(); ++p) ext[p] = extendedSequence(p, seg, layout, spacing);
  const std::vector<std::int32_t> part_of = bindingParts(rest, adjacency, seg, ext);
  Binder binder(rest, layout, spacing);
  std::vector<CurveBinding> bindings(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    bindings[i] = part_of[i] < 0 ? binder.nearestCurve(rest[i])
                                 : binder.bind(ext[static_cast<std::size_t>(part_of[i])], rest[i]);
  }
  return bindings;
}

}  // namespace odeskin

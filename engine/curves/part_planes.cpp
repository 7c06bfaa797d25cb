// SPDX-License-Identifier: MIT
#include "part_planes.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>

#include <glm/geometric.hpp>
#include <tbb/enumerable_thread_specific.h>

#include "../core/parallel.hpp"

namespace odeskin {
namespace {

// Centroid following turns the plane at most this much per step, so consecutive planes do not
// cross inside a limb of radius up to ~3 spacings.
constexpr double kMaxTurn = 20.0 * std::numbers::pi / 180.0;
// A march ends once its direction is more than 90 degrees from where it started.
constexpr double kMaxFlowTurnCos = 0.0;
// Dichotomy stops once two cuts are closer than this many spacings (final gaps 0.625 .. 1.25).
constexpr double kDichotomyStop = 1.25;
// Seam band: vertices within this many edges of a seam, on either side, carry the seam's cut.
constexpr int kSeamBandRings = 2;
// A part's cuts may use the faces within this many edges around it.
constexpr int kPartMarginRings = 2;

struct Probe {
  Plane plane;
  Vec3 centre{0.0};
  std::int32_t curve = -1;  // -1: none
  std::int32_t seam = -1;   // the seam whose shared curve it is (curve == kSeamCurve)
};

Vec3 turnToward(const Vec3& dir, const Vec3& target, double max_angle) {
  const double len = glm::length(target);
  if (!(len > 0.0)) return dir;
  const Vec3 t = target / len;
  const double c = glm::dot(dir, t);
  if (c >= std::cos(max_angle)) return t;
  const Vec3 perp = t - c * dir;
  if (!(glm::length(perp) > 1e-12)) return dir;  // straight back: keep going
  return glm::normalize(std::cos(max_angle) * dir + std::sin(max_angle) * glm::normalize(perp));
}

// A part's cut curves in the order they were made, and its probes in flow order; a probe's curve
// indexes `drafts`, or is kSeamCurve for its seam's shared curve (`seam`).
constexpr std::int32_t kSeamCurve = -2;

struct PartPlan {
  std::vector<Probe> probes;
  std::vector<CurveDraft> drafts;
};

// A seam's shared cut: the probe (its normal the seam's, from parts[0] into parts[1]) and, when the
// cut is a curve, that curve (made for the part that asks for it first).
struct SeamCut {
  Probe probe;
  std::optional<CurveDraft> draft;
};

// Cuts parts and seams; one per thread (its scratch is the cutter's and the marks').
class PartPlanner {
 public:
  PartPlanner(std::span<const Vec3> rest, const CutMesh& mesh, const VertexAdjacency& adjacency,
              const Segmentation& seg, const PlaneCutOptions& options, const std::vector<SeamCut>& seam_cuts)
      : rest_(rest), mesh_(mesh), adjacency_(adjacency), seg_(seg), options_(options), seam_cuts_(seam_cuts),
        cutter_(mesh, rest, options.snap_threshold), mark_(rest.size(), -1) {}

  // The seam's cut, its curve (if any) belonging to `part`'s bone.
  SeamCut seamCut(std::uint32_t s, std::uint32_t part) {
    const Seam& seam = seg_.seams[s];
    const std::vector<std::uint32_t> band = grow(seam.vertices, kSeamBandRings, seam.parts[0], seam.parts[1]);
    const CutRegion band_region(mesh_, rest_, cutter_.trianglesTouching(band), options_.region_scans_before_tree);
    const Plane plane{seam.centroid, seam.normal};
    owned_ = {};
    plan_ = PartPlan{};
    std::optional<Probe> cut = probe(band_region, plane, part);
    SeamCut out;
    out.probe = cut ? *cut : Probe{plane, seam.centroid, -1};
    out.probe.curve = -1;
    if (!plan_.drafts.empty()) out.draft = std::move(plan_.drafts.front());
    // A cut that wandered off the seam (a very uneven seam) still marks its curve, but the
    // planes around it are placed from the seam itself.
    if (glm::length(out.probe.centre - seam.centroid) > options_.spacing) out.probe.centre = seam.centroid;
    return out;
  }

  PartPlan plan(std::uint32_t p) {
    plan_ = PartPlan{};
    plan_.probes = partProbes(p);
    return std::move(plan_);
  }

 private:
  std::optional<Probe> probe(const CutRegion& region, const Plane& plane, std::uint32_t part) {
    std::optional<PlaneCut> cut = cutter_.bestChain(region, plane, owned_);
    // A plane that meets only the margin around the part has left the part.
    if (!cut || cut->owned == 0) return std::nullopt;
    Probe out{plane, cut->centroid, -1};
    // A chain mostly on a neighbour's faces is the neighbour's curve, not this part's.
    if (cut->points.size() >= options_.min_points && 2 * cut->owned >= cut->points.size()) {
      CurveDraft draft;
      draft.points = std::move(cut->points);
      draft.closed = cut->closed;
      draft.bone = seg_.parts[part].bone;
      draft.centroid = cut->centroid;
      draft.radius = cut->radius;
      out.curve = static_cast<std::int32_t>(plan_.drafts.size());
      plan_.drafts.push_back(std::move(draft));
    }
    return out;
  }

  // `seeds` and the vertices within `rings` edges of them (only through vertices of parts `a` or
  // `b` when a >= 0).
  std::vector<std::uint32_t> grow(std::vector<std::uint32_t> seeds, int rings, std::int64_t a = -1,
                                  std::int64_t b = -1) {
    ++mark_epoch_;
    for (std::uint32_t v : seeds) mark_[v] = mark_epoch_;
    std::size_t begin = 0;
    for (int ring = 0; ring < rings; ++ring) {
      const std::size_t end = seeds.size();
      for (std::size_t k = begin; k < end; ++k) {
        for (std::uint32_t n : adjacency_.of(seeds[k])) {
          const std::uint32_t part = seg_.vertex_part[n];
          if (mark_[n] == mark_epoch_ || (a >= 0 && part != a && part != b)) continue;
          mark_[n] = mark_epoch_;
          seeds.push_back(n);
        }
      }
      begin = end;
    }
    return seeds;
  }

  // The seam's cut (made once, before the parts; shared by both); its normal points into `part`.
  Probe seamProbe(std::uint32_t s, std::uint32_t part) {
    const SeamCut& cut = seam_cuts_[s];
    Probe p = cut.probe;
    if (cut.draft) {
      p.curve = kSeamCurve;
      p.seam = static_cast<std::int32_t>(s);
    }
    p.plane.normal = seg_.seams[s].normalInto(part);
    return p;
  }

  std::size_t maxSteps(const Part& part) const {
    return static_cast<std::size_t>(std::ceil(2.0 * part.extent / options_.spacing)) + 2;
  }

  // Centroid following (thesis 6.3.1): each plane sits one spacing past the previous cut's
  // centroid, its normal turned toward the step between the last two centroids.
  void march(const Probe& from, Vec3 dir, const CutRegion& region, std::uint32_t part,
             std::vector<Probe>& out) {
    Vec3 prev = from.centre;
    const Vec3 start = dir;
    const std::size_t steps = maxSteps(seg_.parts[part]);
    for (std::size_t step = 0; step < steps; ++step) {
      std::optional<Probe> next = probe(region, {prev + options_.spacing * dir, dir}, part);
      if (!next) return;
      out.push_back(*next);
      dir = turnToward(dir, next->centre - prev, kMaxTurn);
      prev = next->centre;
      // A flow does not turn back: following the centroids of open arcs (a torso's cuts between
      // the legs) would otherwise circle the part until the step limit, which grows with the
      // mesh's resolution, laying crossing planes.
      if (glm::dot(dir, start) < kMaxFlowTurnCos) return;
    }
  }

  // Dichotomy refinement (thesis 6.3.1) between two planes whose normals point from a to b.
  void dichotomy(const Probe& a, const Probe& b, const CutRegion& region, std::uint32_t part,
                 std::vector<Probe>& out) {
    const Vec3 gap = b.centre - a.centre;
    const double len = glm::length(gap);
    if (len < kDichotomyStop * options_.spacing) return;
    Vec3 n = a.plane.normal + b.plane.normal;
    if (!(glm::length(n) > 1e-9) || glm::dot(n, gap) <= 0.0) n = gap;
    n = glm::normalize(n);
    const Vec3 m = 0.5 * (a.centre + b.centre);
    std::optional<Probe> cut = probe(region, {m, n}, part);
    Probe mid = cut ? *cut : Probe{{m, n}, m, -1};
    // Each half is then at most 3/4 of this gap, so the recursion ends.
    if (glm::length(mid.centre - m) > 0.25 * len) mid.centre = m;
    dichotomy(a, mid, region, part, out);
    out.push_back(mid);
    dichotomy(mid, b, region, part, out);
  }

  // Probes from `a` (normal along the flow) marching backwards, then a .. b by dichotomy, then
  // marching on past b.
  // (b == nullptr: march both ways from a alone.)
  void spanAndExtend(const Probe& a, const Probe* b, const CutRegion& region, std::uint32_t part,
                     std::vector<Probe>& out) {
    std::vector<Probe> before;
    march(a, -a.plane.normal, region, part, before);
    for (auto it = before.rbegin(); it != before.rend(); ++it) {
      Probe p = *it;
      p.plane.normal = -p.plane.normal;
      out.push_back(p);
    }
    out.push_back(a);
    if (b) {
      dichotomy(a, *b, region, part, out);
      out.push_back(*b);
    }
    const Probe& last = b ? *b : a;
    march(last, last.plane.normal, region, part, out);
  }

  Probe planeProbe(const CutRegion& region, const Plane& plane, std::uint32_t part) {
    std::optional<Probe> p = probe(region, plane, part);
    return p ? *p : Probe{plane, plane.origin, -1};
  }

  // More than two seams: split them in two groups along the axis (1-D two-means on the
  // projections of their centroids); false when the groups are less than a spacing apart.
  bool clusterSeams(const Part& part, Probe& a, Probe& b, const CutRegion& region, std::uint32_t p) {
    std::vector<std::pair<double, Vec3>> at;
    for (std::uint32_t s : part.seams) at.push_back({glm::dot(seg_.seams[s].centroid, part.axis), seg_.seams[s].centroid});
    std::sort(at.begin(), at.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::size_t best_split = 1;
    double best_cost = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < at.size(); ++k) {
      double cost = 0.0;
      for (int g = 0; g < 2; ++g) {
        const std::size_t lo = g == 0 ? 0 : k;
        const std::size_t hi = g == 0 ? k : at.size();
        double mean = 0.0;
        for (std::size_t i = lo; i < hi; ++i) mean += at[i].first;
        mean /= static_cast<double>(hi - lo);
        for (std::size_t i = lo; i < hi; ++i) cost += (at[i].first - mean) * (at[i].first - mean);
      }
      if (cost < best_cost) {
        best_cost = cost;
        best_split = k;
      }
    }
    Vec3 ca(0.0), cb(0.0);
    for (std::size_t i = 0; i < at.size(); ++i) (i < best_split ? ca : cb) += at[i].second;
    ca /= static_cast<double>(best_split);
    cb /= static_cast<double>(at.size() - best_split);
    if (glm::dot(cb - ca, part.axis) < options_.spacing) return false;
    a = planeProbe(region, {ca, part.axis}, p);
    b = planeProbe(region, {cb, part.axis}, p);
    return true;
  }

  std::vector<Probe> partProbes(std::uint32_t p) {
    const Part& part = seg_.parts[p];
    std::vector<Probe> out;
    if (part.vertices.empty()) return out;
    // Cuts may run a little past the part's own faces (a margin of kPartMarginRings edges), so a
    // ring closes where a neighbour's patch reaches thinly around the limb; among the chains the
    // one with the most points on the part's own edges wins.
    const CutRegion region(mesh_, rest_, cutter_.trianglesTouching(grow(part.vertices, kPartMarginRings)),
                           options_.region_scans_before_tree);
    if (region.triangles().empty()) return out;
    owned_ = [this, p](std::uint32_t v) { return seg_.vertex_part[v] == p; };
    if (part.seams.size() == 1) {
      const Probe a = seamProbe(part.seams[0], p);
      out.push_back(a);
      march(a, a.plane.normal, region, p, out);
      return out;
    }
    if (part.seams.size() == 2) {
      const Probe a = seamProbe(part.seams[0], p);
      Probe b = seamProbe(part.seams[1], p);
      b.plane.normal = -b.plane.normal;  // out of the part, along the flow a -> b
      const Vec3 gap = b.centre - a.centre;
      if (glm::length(gap) >= options_.spacing && glm::dot(a.plane.normal, gap) > 0.0 &&
          glm::dot(b.plane.normal, gap) > 0.0) {
        out.push_back(a);
        dichotomy(a, b, region, p, out);
        out.push_back(b);
        return out;
      }
    }
    Probe a, b;
    if (part.seams.size() >= 2 && clusterSeams(part, a, b, region, p)) {
      spanAndExtend(a, &b, region, p, out);
      return out;
    }
    // No seam, or seams all at one place: march both ways from the middle, across the bone; a
    // bone that points along no extent of its patch (a flat patch seen edge on) cuts nothing,
    // and the patch's longest principal axis is tried instead.
    const Probe middle = planeProbe(region, {part.centroid, part.axis}, p);
    spanAndExtend(middle, nullptr, region, p, out);
    if (std::none_of(out.begin(), out.end(), [](const Probe& probe) { return probe.curve >= 0; })) {
      std::vector<Vec3> points;
      for (std::uint32_t v : part.vertices) points.push_back(rest_[v]);
      const Vec3 axis = principalAxes(points).axes[2];
      out.clear();
      spanAndExtend(planeProbe(region, {part.centroid, axis}, p), nullptr, region, p, out);
    }
    return out;
  }

  std::span<const Vec3> rest_;
  const CutMesh& mesh_;
  const VertexAdjacency& adjacency_;
  const Segmentation& seg_;
  PlaneCutOptions options_;
  const std::vector<SeamCut>& seam_cuts_;
  PlaneCutter cutter_;
  PartPlan plan_;  // of the part (or seam) being cut
  std::function<bool(std::uint32_t)> owned_;
  std::vector<std::int64_t> mark_;
  std::int64_t mark_epoch_ = 0;
};

// The seams a part asks for, in order: partProbes takes seam cuts for one or two seams, once it
// has found faces to cut (a part whose vertices have none stops first).
std::vector<std::uint32_t> seamsAskedFor(const Segmentation& seg, const CutMesh& mesh, std::uint32_t p) {
  const Part& part = seg.parts[p];
  if (part.seams.size() != 1 && part.seams.size() != 2) return {};
  const bool faces = std::any_of(part.vertices.begin(), part.vertices.end(),
                                 [&](std::uint32_t v) { return mesh.vertex_offsets[v + 1] > mesh.vertex_offsets[v]; });
  return faces ? part.seams : std::vector<std::uint32_t>{};
}


}  // namespace

CurveLayout planeCutCurves(std::span<const Vec3> rest, const CutMesh& mesh, const VertexAdjacency& adjacency,
                           const Segmentation& seg, const PlaneCutOptions& options) {
  // Parts are cut independently, in parallel; seams, shared by two parts, first. Curves are then
  // numbered as cutting the parts one after another in seg.order numbers them: each part's seam
  // curves (those not numbered yet), then its own in the order they were cut.
  std::vector<SeamCut> seam_cuts(seg.seams.size());
  std::vector<std::int64_t> asker(seg.seams.size(), -1);  // the first part in order to ask
  for (std::uint32_t p : seg.order) {
    for (std::uint32_t s : seamsAskedFor(seg, mesh, p)) {
      if (asker[s] < 0) asker[s] = p;
    }
  }
  std::vector<std::uint32_t> asked;
  for (std::uint32_t s = 0; s < seg.seams.size(); ++s) {
    if (asker[s] >= 0) asked.push_back(s);
  }
  tbb::enumerable_thread_specific<PartPlanner> planners(
      [&] { return PartPlanner(rest, mesh, adjacency, seg, options, seam_cuts); });
  parallelFor(std::size_t{0}, asked.size(), [&](std::size_t k) {
    const std::uint32_t s = asked[k];
    seam_cuts[s] = planners.local().seamCut(s, static_cast<std::uint32_t>(asker[s]));
  });
  std::vector<PartPlan> plans(seg.parts.size());
  parallelFor(std::size_t{0}, seg.parts.size(), [&](std::size_t p) {
    plans[p] = planners.local().plan(static_cast<std::uint32_t>(p));
  });

  CurveLayout layout;
  layout.sequences.resize(seg.parts.size());
  std::vector<std::int32_t> seam_curve(seg.seams.size(), -1);
  for (std::uint32_t p : seg.order) {
    PartPlan& plan = plans[p];
    for (std::uint32_t s : seamsAskedFor(seg, mesh, p)) {
      if (seam_curve[s] >= 0 || !seam_cuts[s].draft) continue;
      seam_curve[s] = static_cast<std::int32_t>(layout.curves.size());
      layout.curves.push_back(std::move(*seam_cuts[s].draft));
    }
    const auto first = static_cast<std::int32_t>(layout.curves.size());
    for (CurveDraft& draft : plan.drafts) layout.curves.push_back(std::move(draft));
    for (const Probe& probe : plan.probes) {
      if (probe.curve == -1) continue;
      const std::int32_t curve = probe.curve == kSeamCurve ? seam_curve[static_cast<std::size_t>(probe.seam)]
                                                            : first + probe.curve;
      // Snapping moves points off the cutting plane; what the curve's fitted series describes
      // is where its points are on average, so bindings measure from the plane through the
      // curve's centroid.
      Plane plane = probe.plane;
      const Vec3 centroid = layout.curves[static_cast<std::size_t>(curve)].centroid;
      plane.origin += glm::dot(centroid - plane.origin, plane.normal) * plane.normal;
      layout.sequences[p].push_back({static_cast<std::uint32_t>(curve), plane});
    }
  }
  return layout;
}

void addBoundaryLoops(std::span<const Vec3> rest, const std::vector<std::vector<std::uint32_t>>& loops,
                      const Segmentation& seg, double spacing, std::size_t min_points, CurveLayout& layout) {
  for (const std::vector<std::uint32_t>& loop : loops) {
    if (loop.size() < min_points) continue;
    std::vector<std::size_t> votes(seg.parts.size(), 0);
    for (std::uint32_t v : loop) ++votes[seg.vertex_part[v]];
    const auto p = static_cast<std::uint32_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    CurveDraft draft;
    for (std::uint32_t v : loop) draft.points.push_back({v, v, 0.0});
    draft.closed = true;
    draft.bone = seg.parts[p].bone;
    measureCurve(draft, rest);
    std::vector<Vec3> points;
    points.reserve(loop.size());
    for (std::uint32_t v : loop) points.push_back(rest[v]);
    const PrincipalAxes pca = principalAxes(points);
    Vec3 normal = pca.values[0] <= 0.25 * pca.values[1] ? pca.axes[0] : seg.parts[p].axis;
    std::vector<Station>& seq = layout.sequences[p];
    if (seq.empty()) {
      seq.push_back({static_cast<std::uint32_t>(layout.curves.size()), {draft.centroid, normal}});
      layout.curves.push_back(std::move(draft));
      continue;
    }
    // Along the flow: beyond the last station, or before the first (within half a spacing).
    for (int end = 0; end < 2; ++end) {
      const Station& s = end == 0 ? seq.back() : seq.front();
      const Vec3 flow = s.plane.normal;
      const double ahead = glm::dot(flow, draft.centroid - s.plane.origin) * (end == 0 ? 1.0 : -1.0);
      if (ahead < -0.5 * spacing || std::abs(glm::dot(normal, flow)) < 0.7) continue;
      const Vec3 n = glm::dot(normal, flow) < 0.0 ? -normal : normal;
      const double sign = end == 0 ? 1.0 : -1.0;
      // Stations the rim overtakes (within half a spacing of it, or past it) go.
      auto overtaken = [&](const Station& st) { return sign * glm::dot(n, st.plane.origin - draft.centroid) > -0.5 * spacing; };
      if (end == 0) {
        while (!seq.empty() && overtaken(seq.back())) seq.pop_back();
        seq.push_back({static_cast<std::uint32_t>(layout.curves.size()), {draft.centroid, n}});
      } else {
        while (!seq.empty() && overtaken(seq.front())) seq.erase(seq.begin());
        seq.insert(seq.begin(), Station{static_cast<std::uint32_t>(layout.curves.size()), {draft.centroid, n}});
      }
      layout.curves.push_back(std::move(draft));
      break;
    }
  }
}

}  // namespace odeskin

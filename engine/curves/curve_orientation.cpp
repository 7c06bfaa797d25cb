// SPDX-License-Identifier: MIT
#include "curve_orientation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "../offline/fourier_fit.hpp"

namespace odeskin {
namespace {

// A carried reference that has become nearly normal to the next plane (its projection shorter
// than this) is replaced by a fixed world direction.
constexpr double kMinProjection = 0.3;
// Planes within 35 degrees are parallel; a neighbour's sense of turning is followed when the
// planes are less than ~73 degrees apart.
constexpr double kParallelCos = 0.82;
constexpr double kSenseCos = 0.3;

// The first of +y, +z, +x not nearly along n, projected onto the plane: the start of the first
// curve of a tree (y is up in the usual character data).
Vec3 worldReference(const Vec3& n) {
  for (const Vec3 r : {Vec3(0.0, 1.0, 0.0), Vec3(0.0, 0.0, 1.0), Vec3(1.0, 0.0, 0.0)}) {
    const Vec3 p = r - glm::dot(r, n) * n;
    if (glm::length(p) > 0.5) return glm::normalize(p);
  }
  return Vec3(0.0, 1.0, 0.0);
}

Vec3 carry(const Vec3& reference, const Vec3& n) {
  const Vec3 p = reference - glm::dot(reference, n) * n;
  return glm::length(p) > kMinProjection ? glm::normalize(p) : worldReference(n);
}

void orientCurve(std::span<const Vec3> rest, const Vec3& orientation, const Vec3& reference, CurveDraft& curve) {
  const std::size_t n = curve.points.size();
  std::vector<Vec3> pos(n);
  for (std::size_t j = 0; j < n; ++j) pos[j] = curvePointPosition(rest, curve.points[j]);
  double winding = 0.0;
  for (std::size_t j = 0; j + (curve.closed ? 0 : 1) < n; ++j) {
    winding += glm::dot(glm::cross(pos[j] - curve.centroid, pos[(j + 1) % n] - curve.centroid), orientation);
  }
  if (winding < 0.0) {
    std::reverse(curve.points.begin(), curve.points.end());
    std::reverse(pos.begin(), pos.end());
  }
  if (curve.closed) {
    std::size_t start = 0;
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3 d = pos[j] - curve.centroid;
      const double len = glm::length(d);
      if (!(len > 0.0)) continue;
      const double c = glm::dot(d, reference) / len;
      if (c > best) {
        best = c;
        start = j;
      }
    }
    std::rotate(curve.points.begin(), curve.points.begin() + static_cast<std::ptrdiff_t>(start), curve.points.end());
    std::rotate(pos.begin(), pos.begin() + static_cast<std::ptrdiff_t>(start), pos.end());
  }
  Result<std::vector<double>> v = arcLengthParameters(pos, curve.closed);
  curve.oriented = true;
  curve.orientation = orientation;
  curve.reference = reference;
  if (!v.ok()) {
    curve.dropped = true;
    return;
  }
  curve.v = std::move(*v);
}

}  // namespace

void orientCurves(std::span<const Vec3> rest, const Segmentation& seg, CurveLayout& layout) {
  for (std::uint32_t p : seg.order) {
    const std::vector<Station>& seq = layout.sequences[p];
    if (seq.empty()) continue;
    const Part& part = seg.parts[p];
    const Station& first = seq.front();
    double sign = 1.0;
    Vec3 reference = worldReference(first.plane.normal);
    if (!layout.curves[first.curve].oriented) {
      // Follow the neighbour done before whose curve nearest their seam is parallel to ours (two
      // arms of a T, a forearm after an upper arm); else the parent's curve nearest the entry
      // seam, whose sense is followed only if the two are not nearly perpendicular (a leg under
      // a torso shares no sense of turning with it).
      const CurveDraft* guide = nullptr;
      double guide_distance = std::numeric_limits<double>::infinity();
      bool aligned = false;
      for (std::uint32_t sm : part.seams) {
        const Seam& seam = seg.seams[sm];
        const std::uint32_t q = seam.other(p);
        for (const Station& t : layout.sequences[q]) {
          const CurveDraft& c = layout.curves[t.curve];
          if (!c.oriented) continue;
          const bool parallel = std::abs(glm::dot(t.plane.normal, first.plane.normal)) >= kParallelCos;
          if (!parallel && static_cast<std::int32_t>(q) != part.parent) continue;
          const double distance = glm::length(t.plane.origin - seam.centroid);
          if ((parallel && !aligned) || (parallel == aligned && distance < guide_distance)) {
            guide = &c;
            guide_distance = distance;
            aligned = parallel;
          }
        }
      }
      if (guide) {
        if (glm::dot(first.plane.normal, guide->orientation) < -kSenseCos) sign = -1.0;
        reference = guide->reference;
      }
    }
    for (const Station& s : seq) {
      CurveDraft& curve = layout.curves[s.curve];
      if (curve.oriented) {
        // Shared with a part done before (a seam curve): go on in its sense and from its start.
        sign = glm::dot(s.plane.normal, curve.orientation) < 0.0 ? -1.0 : 1.0;
        reference = curve.reference;
        continue;
      }
      reference = carry(reference, s.plane.normal);
      orientCurve(rest, sign * s.plane.normal, reference, curve);
    }
  }
}

}  // namespace odeskin

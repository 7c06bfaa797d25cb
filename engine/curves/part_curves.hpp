// SPDX-License-Identifier: MIT
// Working types of the iso-curve builder (thesis 6.3.1): curves as they are cut, and per body
// part the ordered planes ("stations") that bindings interpolate between. Internal to curves/.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/iso_curve.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct Plane {
  Vec3 origin{0.0};
  Vec3 normal{0.0};  // unit
};

struct CurveDraft {
  std::vector<CurvePoint> points;  // in order; a closed curve does not repeat its first point
  bool closed = true;
  std::uint32_t bone = 0;   // IsoCurve::part
  Vec3 centroid{0.0};       // length-weighted, bind pose
  double radius = 0.0;      // mean distance of the points from the centroid
  // Set by orientCurves.
  std::vector<double> v;
  Vec3 orientation{0.0};  // the curve runs counter-clockwise about this unit vector
  Vec3 reference{0.0};    // its first point is the one seen from the centroid nearest this direction
  bool oriented = false;
  bool dropped = false;   // no usable arc-length parameters; removed by compactCurves
};

// One plane of a part's sequence that carries a curve. `plane.normal` points along the part's
// flow (from its first station to its last), so consecutive stations enclose the vertices between
// them: d_k(x) = normal_k . (x - origin_k) >= 0 >= d_{k+1}(x).
struct Station {
  std::uint32_t curve = 0;
  Plane plane;
};

struct CurveLayout {
  std::vector<CurveDraft> curves;
  std::vector<std::vector<Station>> sequences;  // per part, in flow order (a shared seam curve may end one and start another)
};

// Sets centroid (length-weighted) and radius from the bind positions.
void measureCurve(CurveDraft& curve, std::span<const Vec3> rest);

// Removes dropped curves and curves no sequence uses, and renumbers the stations.
void compactCurves(CurveLayout& layout);

}  // namespace odeskin

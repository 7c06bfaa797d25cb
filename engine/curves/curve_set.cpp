// SPDX-License-Identifier: MIT
#include "curve_set.hpp"

#include <cmath>
#include <string>

#include "../core/number_text.hpp"

namespace odeskin {
namespace {

bool inUnit(double x) { return std::isfinite(x) && x >= 0.0 && x <= 1.0; }

}  // namespace

Status validateCurveSet(const CurveSet& set, std::size_t vertex_count) {
  const std::size_t curves = set.curves.size();
  if (set.bindings.size() != vertex_count) {
    return invalidArgument("curves: " + std::to_string(set.bindings.size()) + " bindings for " +
                           std::to_string(vertex_count) + " vertices");
  }
  if (!set.vertex_parts.empty() && set.vertex_parts.size() != vertex_count) {
    return invalidArgument("curves: " + std::to_string(set.vertex_parts.size()) + " vertex parts for " +
                           std::to_string(vertex_count) + " vertices");
  }
  for (std::size_t c = 0; c < curves; ++c) {
    const IsoCurve& curve = set.curves[c];
    const std::string name = "curves: curve " + std::to_string(c);
    if (curve.points.size() < 3) return invalidArgument(name + " has " + std::to_string(curve.points.size()) + " points");
    if (curve.v.size() != curve.points.size()) return invalidArgument(name + " has a v per point missing");
    for (std::size_t j = 0; j < curve.points.size(); ++j) {
      const CurvePoint& p = curve.points[j];
      if (p.a >= vertex_count || p.b >= vertex_count || !inUnit(p.t)) {
        return invalidArgument(name + " point " + std::to_string(j) + " is not on a mesh edge");
      }
      if (!inUnit(curve.v[j]) || (j > 0 && curve.v[j] < curve.v[j - 1])) {
        return invalidArgument(name + " point " + std::to_string(j) + " has v outside [0, 1] or out of order");
      }
    }
  }
  for (std::size_t i = 0; i < vertex_count; ++i) {
    const CurveBinding& b = set.bindings[i];
    if (b.curve_a >= curves || b.curve_b >= curves || !inUnit(b.w) || !inUnit(b.v)) {
      return invalidArgument("curves: vertex " + std::to_string(i) + " is unbound or bound outside the curves (" +
                             std::to_string(b.curve_a) + ", " + std::to_string(b.curve_b) + ", w " +
                             messageNumber(b.w) + ", v " + messageNumber(b.v) + ")");
    }
  }
  return okStatus();
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "network.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace odeskin {
namespace {

// Two ratios count as equal when they differ by rounding only: (1, 3, 1) and (0.1, 0.3, 0.1) give
// b = 3 and 2.9999999999999996. Cardinal functions this close differ by ~1e-13, and the network then
// uses one of them for both patches, so the shared edge is exact.
bool sameRatio(double a, double b) {
  return std::isfinite(a) && std::isfinite(b) && std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)});
}

bool sameFunctions(const Ode6Shape& x, const Ode6Shape& y) {
  return sameRatio(x.eta / x.rho, y.eta / y.rho) && sameRatio(x.lambda / x.rho, y.lambda / y.rho);
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
}

std::string patchName(std::uint32_t row, std::uint32_t column) {
  return "patch (row " + std::to_string(row) + ", column " + std::to_string(column) + ")";
}

std::string boundaryName(const NetworkDescription& d, std::size_t b) {
  const std::string& name = d.boundaries[b].name;
  return "boundary " + (name.empty() ? std::to_string(b) : "'" + name + "'");
}

std::uint32_t rowCount(const NetworkDescription& d) {
  const auto b = static_cast<std::uint32_t>(d.boundaries.size());
  return d.closed_u ? b : (b == 0 ? 0 : b - 1);
}

Status checkCurveIndex(const NetworkDescription& d, std::size_t b, std::uint32_t curve, const char* role) {
  if (curve >= d.curve_names.size()) {
    return invalidArgument(boundaryName(d, b) + ": " + role + " curve index " + std::to_string(curve) +
                           " is out of range (" + std::to_string(d.curve_names.size()) + " curves)");
  }
  return okStatus();
}

// S_u and S_uu of boundary b as curve combinations, after checking its fields.
Status boundaryTerms(const NetworkDescription& d, std::size_t b, std::vector<CurveTerm>& first,
                     std::vector<CurveTerm>& second) {
  const NetworkBoundary& x = d.boundaries[b];
  ODESKIN_TRY(checkCurveIndex(d, b, x.position, "position"));
  first.clear();
  second.clear();
  switch (x.source) {
    case DerivativeSource::kCoefficients:
      if (!std::isfinite(x.w_first) || !std::isfinite(x.w_second)) {
        return invalidArgument(boundaryName(d, b) + ": coefficients must be finite numbers");
      }
      first = {{x.w_first, x.position}};
      second = {{x.w_second, x.position}};
      return okStatus();
    case DerivativeSource::kCurves:
      ODESKIN_TRY(checkCurveIndex(d, b, x.first_curve, "first-derivative"));
      ODESKIN_TRY(checkCurveIndex(d, b, x.second_curve, "second-derivative"));
      first = {{1.0, x.first_curve}};
      second = {{1.0, x.second_curve}};
      return okStatus();
    case DerivativeSource::kControlCurves: {
      ODESKIN_TRY(checkCurveIndex(d, b, x.control_lower, "control"));
      ODESKIN_TRY(checkCurveIndex(d, b, x.control_upper, "control"));
      const std::uint32_t rows = rowCount(d);
      if (!d.closed_u && x.side == ControlSide::kBefore && b == 0) {
        return invalidArgument(boundaryName(d, b) + ": control curves 'before' the first boundary lie in no patch");
      }
      if (!d.closed_u && x.side == ControlSide::kAfter && b == rows) {
        return invalidArgument(boundaryName(d, b) + ": control curves 'after' the last boundary lie in no patch");
      }
      // After: near = the lower curve (u2), far = the upper (u3). Before: near = upper (u6), far = lower (u5).
      Result<ControlWeights> w = x.side == ControlSide::kAfter ? startControlWeights(x.u_lower, x.u_upper, x.slopes)
                                                               : endControlWeights(x.u_lower, x.u_upper, x.slopes);
      if (!w.ok()) return invalidArgument(boundaryName(d, b) + ": " + w.status().message());
      const std::uint32_t near = x.side == ControlSide::kAfter ? x.control_lower : x.control_upper;
      const std::uint32_t far = x.side == ControlSide::kAfter ? x.control_upper : x.control_lower;
      first = {{w->first.boundary, x.position}, {w->first.near, near}, {w->first.far, far}};
      second = {{w->second.boundary, x.position}, {w->second.near, near}, {w->second.far, far}};
      return okStatus();
    }
  }
  return internalError("network: unknown derivative source");
}

// Control curves of both ends of one row must not cross: u3 <= u5 (erratum F7).
Status checkRowControls(const NetworkDescription& d, std::uint32_t row) {
  const std::size_t lower = row;
  const std::size_t upper = (row + 1) % d.boundaries.size();
  const NetworkBoundary& a = d.boundaries[lower];
  const NetworkBoundary& b = d.boundaries[upper];
  if (a.source == DerivativeSource::kControlCurves && a.side == ControlSide::kAfter &&
      b.source == DerivativeSource::kControlCurves && b.side == ControlSide::kBefore && !(a.u_upper <= b.u_lower)) {
    return invalidArgument("row " + std::to_string(row) + ": control curves of " + boundaryName(d, lower) +
                           " reach u3 = " + number(a.u_upper) + " beyond those of " + boundaryName(d, upper) +
                           " at u5 = " + number(b.u_lower) + " (need u3 <= u5)");
  }
  return okStatus();
}

bool termsUse(const std::vector<CurveTerm>& terms, std::uint32_t curve) {
  return std::any_of(terms.begin(), terms.end(), [&](const CurveTerm& t) { return t.curve == curve; });
}

}  // namespace

Result<Network> Network::build(NetworkDescription d, std::vector<std::string>* warnings) {
  const std::size_t curve_count = d.curve_names.size();
  if (curve_count == 0) return invalidArgument("network: no curves");
  if (d.curve_points.size() != curve_count || d.curve_closed.size() != curve_count) {
    return invalidArgument("network: curve names, points and closure flags differ in count");
  }
  std::set<std::string> names;
  for (const std::string& name : d.curve_names) {
    if (name.empty()) return invalidArgument("network: a curve has an empty name");
    if (!names.insert(name).second) return invalidArgument("network: curve '" + name + "' is defined twice");
  }
  for (std::size_t i = 1; i < curve_count; ++i) {
    if (d.curve_closed[i] != d.curve_closed[0]) {
      return invalidArgument("network: curve '" + d.curve_names[i] + "' is " + (d.curve_closed[i] ? "closed" : "open") +
                             " but '" + d.curve_names[0] + "' is not: a network's curves are all closed (a tube " +
                             "closed in v) or all open");
    }
  }
  if (d.columns == 0) return invalidArgument("network: columns must be at least 1");
  if (d.boundaries.size() < (d.closed_u ? 1u : 2u)) {
    return invalidArgument(std::string("network: ") + (d.closed_u ? "a network closed in u needs at least 1 boundary"
                                                                   : "an open network needs at least 2 boundaries"));
  }
  Network n;
  n.rows_ = rowCount(d);
  n.closed_v_ = d.curve_closed[0];
  const std::size_t patches = static_cast<std::size_t>(n.rows_) * d.columns;
  if (d.shapes.size() != patches) {
    return invalidArgument("network: " + std::to_string(d.shapes.size()) + " shapes for " + std::to_string(n.rows_) +
                           " rows x " + std::to_string(d.columns) + " columns");
  }
  for (std::size_t i = 0; i < curve_count; ++i) {
    Result<NetworkCurve> curve = NetworkCurve::interpolate(d.curve_points[i], d.curve_closed[i], d.columns);
    if (!curve.ok()) return invalidArgument("curve '" + d.curve_names[i] + "': " + curve.status().message());
    n.curves_.push_back(std::move(curve).value());
  }
  n.first_terms_.resize(d.boundaries.size());
  n.second_terms_.resize(d.boundaries.size());
  for (std::size_t b = 0; b < d.boundaries.size(); ++b) {
    ODESKIN_TRY(boundaryTerms(d, b, n.first_terms_[b], n.second_terms_[b]));
  }
  for (std::uint32_t row = 0; row < n.rows_; ++row) ODESKIN_TRY(checkRowControls(d, row));
  n.description_ = std::move(d);
  ODESKIN_TRY(n.rebuildCardinals(warnings));
  return n;
}

Status Network::rebuildCardinals(std::vector<std::string>* warnings) {
  const std::uint32_t columns = description_.columns;
  std::vector<Ode6Cardinal> cardinals;
  std::vector<std::uint32_t> of_patch(static_cast<std::size_t>(rows_) * columns);
  for (std::uint32_t row = 0; row < rows_; ++row) {
    // Each patch's own functions first (so a bad shape is reported as such), shared within the row.
    const std::size_t row_start = cardinals.size();
    for (std::uint32_t column = 0; column < columns; ++column) {
      const Ode6Shape& shape = description_.shapes[row * columns + column];
      std::size_t found = cardinals.size();
      for (std::size_t k = row_start; k < cardinals.size() && found == cardinals.size(); ++k) {
        if (sameFunctions(cardinals[k].shape(), shape)) found = k;
      }
      if (found == cardinals.size()) {
        Result<Ode6Cardinal> g = Ode6Cardinal::create(shape);
        if (!g.ok()) return Status(g.status().code(), patchName(row, column) + ": " + g.status().message());
        cardinals.push_back(std::move(g).value());
      }
      of_patch[row * columns + column] = static_cast<std::uint32_t>(found);
    }
    // Then the v-neighbours: the next column, and across the seam of a tube.
    for (std::uint32_t column = 0; column < columns; ++column) {
      const std::uint32_t next = column + 1 < columns ? column + 1 : (closed_v_ && columns > 1 ? 0 : columns);
      if (next == columns || of_patch[row * columns + column] == of_patch[row * columns + next]) continue;
      const Ode6Shape& shape = description_.shapes[row * columns + column];
      const Ode6Shape& other = description_.shapes[row * columns + next];
      const std::string what = patchName(row, column) + " and " + patchName(row, next) +
                               " share a v-edge but have eta/rho = " + number(shape.eta / shape.rho) + " vs " +
                               number(other.eta / other.rho) + " and lambda/rho = " + number(shape.lambda / shape.rho) +
                               " vs " + number(other.lambda / other.rho) +
                               ": they cannot be C2 (not even C0) across it (MATH.md 3.8, erratum F9)";
      if (description_.continuity == ContinuityPolicy::kRefuse) {
        return invalidArgument(what + "; give them equal ratios or set \"continuity\": \"warn\"");
      }
      if (warnings) warnings->push_back(what + "; the mesh takes " + patchName(row, next) + "'s values on it");
    }
  }
  cardinals_ = std::move(cardinals);
  cardinal_of_patch_ = std::move(of_patch);
  return okStatus();
}

std::uint32_t Network::upperBoundary(std::uint32_t row) const {
  return (row + 1) % static_cast<std::uint32_t>(description_.boundaries.size());
}

const Ode6Cardinal& Network::cardinal(std::uint32_t row, std::uint32_t column) const {
  return cardinals_[cardinalIndex(row, column)];
}

std::uint32_t Network::cardinalIndex(std::uint32_t row, std::uint32_t column) const {
  return cardinal_of_patch_[row * description_.columns + column];
}

BoundarySample Network::boundarySample(std::uint32_t b, double v, int order, bool left_limit) const {
  BoundarySample s;
  s.position = curves_[description_.boundaries[b].position].evaluate(v, order, left_limit);
  for (const CurveTerm& t : first_terms_[b]) s.first += t.weight * curves_[t.curve].evaluate(v, order, left_limit);
  for (const CurveTerm& t : second_terms_[b]) s.second += t.weight * curves_[t.curve].evaluate(v, order, left_limit);
  return s;
}

PatchPoint Network::evaluate(std::uint32_t row, std::uint32_t column, double u, double v) const {
  std::array<Ode6Values, 3> g{};
  cardinal(row, column).evaluate(u, g);
  const double global_v = column + v;
  PatchPoint p;
  const std::uint32_t ends[2] = {lowerBoundary(row), upperBoundary(row)};
  for (int order = 0; order < 3; ++order) {
    for (std::size_t e = 0; e < 2; ++e) {
      const BoundarySample c = boundarySample(ends[e], global_v, order, v == 1.0);
      const Vec3 ck[3] = {c.position, c.first, c.second};
      for (std::size_t j = 0; j < 3; ++j) {
        const std::size_t k = 3 * e + j;
        if (order == 0) {
          p.s += g[0][k] * ck[j];
          p.s_u += g[1][k] * ck[j];
          p.s_uu += g[2][k] * ck[j];
        } else if (order == 1) {
          p.s_v += g[0][k] * ck[j];
          p.s_uv += g[1][k] * ck[j];
        } else {
          p.s_vv += g[0][k] * ck[j];
        }
      }
    }
  }
  return p;
}

Result<Patch> Network::patch(std::uint32_t row, std::uint32_t column) const {
  if (row >= rows_ || column >= description_.columns) {
    return outOfRange(patchName(row, column) + " is outside the " + std::to_string(rows_) + " x " +
                      std::to_string(description_.columns) + " network");
  }
  PatchCurves curves;
  const std::uint32_t ends[2] = {lowerBoundary(row), upperBoundary(row)};
  const double offset = column;
  for (std::size_t e = 0; e < 2; ++e) {
    const std::uint32_t b = ends[e];
    auto term_curve = [&](const std::vector<CurveTerm>& terms) -> PatchCurve {
      std::vector<std::pair<double, NetworkCurve>> copies;
      copies.reserve(terms.size());
      for (const CurveTerm& t : terms) copies.emplace_back(t.weight, curves_[t.curve]);
      return [copies = std::move(copies), offset](double v, int order) {
        Vec3 sum(0.0);
        for (const auto& [w, c] : copies) sum += w * c.evaluate(offset + v, order, v == 1.0);
        return sum;
      };
    };
    curves[3 * e] = term_curve({{1.0, description_.boundaries[b].position}});
    curves[3 * e + 1] = term_curve(first_terms_[b]);
    curves[3 * e + 2] = term_curve(second_terms_[b]);
  }
  return Patch::create(cardinal(row, column), std::move(curves));
}

std::vector<std::uint32_t> Network::rowsPatches(std::vector<std::uint32_t> rows) const {
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  std::vector<std::uint32_t> patches;
  for (std::uint32_t row : rows) {
    for (std::uint32_t column = 0; column < description_.columns; ++column) patches.push_back(row * description_.columns + column);
  }
  return patches;
}

Result<std::vector<std::uint32_t>> Network::setRowShape(std::uint32_t row, const Ode6Shape& shape) {
  if (row >= rows_) return outOfRange("network: row " + std::to_string(row) + " does not exist");
  const std::vector<Ode6Shape> old = description_.shapes;
  for (std::uint32_t column = 0; column < description_.columns; ++column) description_.shapes[row * description_.columns + column] = shape;
  if (Status s = rebuildCardinals(nullptr); !s.ok()) {
    description_.shapes = old;
    ODESKIN_TRY(rebuildCardinals(nullptr));
    return s;
  }
  return rowsPatches({row});
}

Result<std::vector<std::uint32_t>> Network::setPatchShape(std::uint32_t row, std::uint32_t column, const Ode6Shape& shape) {
  if (row >= rows_ || column >= description_.columns) return outOfRange("network: " + patchName(row, column) + " does not exist");
  const Ode6Shape old = description_.shapes[row * description_.columns + column];
  description_.shapes[row * description_.columns + column] = shape;
  if (Status s = rebuildCardinals(nullptr); !s.ok()) {
    description_.shapes[row * description_.columns + column] = old;
    ODESKIN_TRY(rebuildCardinals(nullptr));
    return s;
  }
  return std::vector<std::uint32_t>{row * description_.columns + column};
}

Result<std::vector<std::uint32_t>> Network::setBoundary(std::uint32_t b, const NetworkBoundary& boundary) {
  if (b >= description_.boundaries.size()) return outOfRange("network: boundary " + std::to_string(b) + " does not exist");
  NetworkDescription trial = description_;
  trial.boundaries[b] = boundary;
  std::vector<CurveTerm> first;
  std::vector<CurveTerm> second;
  ODESKIN_TRY(boundaryTerms(trial, b, first, second));
  std::vector<std::uint32_t> rows;
  for (std::uint32_t row = 0; row < rows_; ++row) {
    if (lowerBoundary(row) == b || upperBoundary(row) == b) {
      ODESKIN_TRY(checkRowControls(trial, row));
      rows.push_back(row);
    }
  }
  description_.boundaries[b] = boundary;
  first_terms_[b] = std::move(first);
  second_terms_[b] = std::move(second);
  return rowsPatches(std::move(rows));
}

Result<std::vector<std::uint32_t>> Network::setCurvePoints(std::uint32_t curve, std::span<const Vec3> points) {
  if (curve >= curves_.size()) return outOfRange("network: curve " + std::to_string(curve) + " does not exist");
  if (points.size() != description_.curve_points[curve].size()) {
    return invalidArgument("curve '" + description_.curve_names[curve] + "': " + std::to_string(points.size()) +
                           " points instead of " + std::to_string(description_.curve_points[curve].size()));
  }
  Result<NetworkCurve> rebuilt = NetworkCurve::interpolate(points, closed_v_, description_.columns);
  if (!rebuilt.ok()) return invalidArgument("curve '" + description_.curve_names[curve] + "': " + rebuilt.status().message());
  curves_[curve] = std::move(rebuilt).value();
  description_.curve_points[curve].assign(points.begin(), points.end());
  std::vector<std::uint32_t> rows;
  for (std::uint32_t row = 0; row < rows_; ++row) {
    for (std::uint32_t b : {lowerBoundary(row), upperBoundary(row)}) {
      if (description_.boundaries[b].position == curve || termsUse(first_terms_[b], curve) ||
          termsUse(second_terms_[b], curve)) {
        rows.push_back(row);
      }
    }
  }
  return rowsPatches(std::move(rows));
}

}  // namespace odeskin

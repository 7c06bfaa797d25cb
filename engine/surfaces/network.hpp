// SPDX-License-Identifier: MIT
// A network of C2 surface patches (thesis sec. 4.4; MATH.md 3.8): a grid of rows x columns patches.
// Boundary i is an iso-u curve with its first and second u-derivative curves; row i runs from
// boundary i (its u = 0) to boundary i + 1 (its u = 1, or boundary 0 again when closed in u). Every
// curve spans all columns (v in [0, columns]); patch (i, j) uses v in [j, j + 1].
//  - u-adjacent patches share a boundary, so S, S_u, S_uu agree along it for any shapes (3.8).
//  - v-adjacent patches read the same C2 curves on both sides of their edge; they are C2 across it
//    only if their cardinal functions are the same, i.e. equal eta/rho and lambda/rho (3.8, erratum
//    F9: the thesis's Fig 4.1(b) pairs (1, 3, 1) with (0.1, 3, 0.1) and is not even C0 there). The
//    builder refuses such a pairing (kInvalidArgument) unless the policy is kWarn; then it warns,
//    and each patch keeps its own cardinal functions.
// Patches with equal ratios in one row share one Ode6Cardinal (MATH.md 3.9).
//
// Meant to take curve networks from anywhere: hand-written JSON (network_json.hpp), generated
// grids, or curves extracted from a mesh with measured derivative curves (DerivativeSource::kCurves).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "network_curve.hpp"
#include "ode6_cardinal.hpp"
#include "patch.hpp"
#include "patch_boundary.hpp"

namespace odeskin {

// How a boundary's u-derivative curves are built (patch_boundary.hpp).
enum class DerivativeSource {
  kCoefficients,   // S_u = w_first * C, S_uu = w_second * C (thesis Eqs 4.24-4.25)
  kControlCurves,  // from two control curves on one side of the boundary (thesis Eqs 4.3-4.7, corrected)
  kCurves,         // S_u and S_uu given as curves (e.g. measured on a mesh)
};

// Which patch holds a boundary's control curves.
enum class ControlSide {
  kAfter,   // the row that starts at the boundary: curves at u2 < u3 of that row (c2, c3)
  kBefore,  // the row that ends at the boundary: curves at u5 < u6 of that row (c5, c6)
};

struct NetworkBoundary {
  std::string name;
  std::uint32_t position = 0;  // curve index: S on the boundary
  DerivativeSource source = DerivativeSource::kCoefficients;
  double w_first = 0.0;   // kCoefficients
  double w_second = 0.0;  // kCoefficients
  ControlSide side = ControlSide::kAfter;                      // kControlCurves
  std::uint32_t control_lower = 0;                             // kControlCurves: the curve at the smaller u
  std::uint32_t control_upper = 0;                             // kControlCurves: the curve at the larger u
  double u_lower = 0.0;                                        // kControlCurves: patch-local u of control_lower
  double u_upper = 0.0;                                        // kControlCurves: patch-local u of control_upper
  SlopeRule slopes = SlopeRule::kOneSided;                     // kControlCurves
  std::uint32_t first_curve = 0;                               // kCurves: S_u
  std::uint32_t second_curve = 0;                              // kCurves: S_uu
};

enum class ContinuityPolicy {
  kRefuse,  // v-adjacent patches with different eta/rho or lambda/rho: kInvalidArgument
  kWarn,    // build anyway, with a warning per pairing
};

// What a network file describes; buildNetwork checks it.
struct NetworkDescription {
  std::vector<std::string> curve_names;             // unique, one per curve
  std::vector<std::vector<Vec3>> curve_points;      // interpolated points of each curve
  std::vector<bool> curve_closed;                   // all closed (closed in v) or all open
  std::vector<NetworkBoundary> boundaries;          // in u order; >= 2 (open) or >= 1 (closed in u)
  bool closed_u = false;                            // the last row joins the last boundary to the first
  std::uint32_t columns = 1;                        // patches along v, >= 1
  std::vector<Ode6Shape> shapes;                    // rows x columns, row-major
  ContinuityPolicy continuity = ContinuityPolicy::kRefuse;
};

// A term w * curve(v) of a derivative curve.
struct CurveTerm {
  double weight = 0.0;
  std::uint32_t curve = 0;
};

// S, S_u and S_uu on a boundary at one v, with their v-derivatives of one order.
struct BoundarySample {
  Vec3 position{0.0};
  Vec3 first{0.0};
  Vec3 second{0.0};
};

class Network {
 public:
  // kInvalidArgument naming the element for: missing or duplicate curves, bad indices, control
  // curves outside (0, 1) or out of order (u3 <= u5 within a row), control curves on the missing
  // side of an open network's first or last boundary, mixed open and closed curves, wrong shape
  // count, and (policy kRefuse) v-adjacent patches that cannot be C2. Ode6Cardinal's errors for
  // each shape, prefixed with the patch. `warnings` (optional) receives one line per tolerated pairing.
  static Result<Network> build(NetworkDescription description, std::vector<std::string>* warnings = nullptr);

  std::uint32_t rows() const { return rows_; }
  std::uint32_t columns() const { return description_.columns; }
  std::uint32_t patchCount() const { return rows_ * description_.columns; }
  bool closedU() const { return description_.closed_u; }
  bool closedV() const { return closed_v_; }
  const NetworkDescription& description() const { return description_; }

  // Boundary indices of row i: (i, i + 1), the second wrapping to 0 when closed in u.
  std::uint32_t lowerBoundary(std::uint32_t row) const { return row; }
  std::uint32_t upperBoundary(std::uint32_t row) const;

  // The cardinal functions patch (row, column) uses, and an index shared by every patch using the
  // same functions (0 .. cardinalCount() - 1).
  const Ode6Cardinal& cardinal(std::uint32_t row, std::uint32_t column) const;
  std::uint32_t cardinalIndex(std::uint32_t row, std::uint32_t column) const;
  std::uint32_t cardinalCount() const { return static_cast<std::uint32_t>(cardinals_.size()); }
  const Ode6Cardinal& cardinalAt(std::uint32_t index) const { return cardinals_[index]; }

  const NetworkCurve& curve(std::uint32_t index) const { return curves_[index]; }
  // S_u and S_uu of boundary b as combinations of curves.
  const std::vector<CurveTerm>& firstTerms(std::uint32_t b) const { return first_terms_[b]; }
  const std::vector<CurveTerm>& secondTerms(std::uint32_t b) const { return second_terms_[b]; }
  // Boundary data at global v in [0, columns], v-derivative `order` (0..2); `left_limit` as in
  // NetworkCurve::evaluate (patches use it at their v = 1 edge).
  BoundarySample boundarySample(std::uint32_t b, double v, int order = 0, bool left_limit = false) const;

  // Patch (row, column) on its own parameters (u, v) in [0, 1]^2; at v = 1 the curves are read from
  // the spline pieces inside the patch (left limits), so comparing with the next patch at v = 0
  // measures the C2 join rather than repeating one evaluation.
  Result<Patch> patch(std::uint32_t row, std::uint32_t column) const;
  PatchPoint evaluate(std::uint32_t row, std::uint32_t column, double u, double v) const;

  // Edits for interactive modelling. Each re-checks what the edit can break and returns the patches
  // (row * columns + column) whose surface changed; nothing changes on error.
  // A new shape for every patch of a row (its v-chain stays C2).
  Result<std::vector<std::uint32_t>> setRowShape(std::uint32_t row, const Ode6Shape& shape);
  // A new shape for one patch; under kRefuse only when its v-neighbours keep matching ratios.
  Result<std::vector<std::uint32_t>> setPatchShape(std::uint32_t row, std::uint32_t column, const Ode6Shape& shape);
  // New derivative data for boundary b (its position curve stays): affects the rows on both sides.
  Result<std::vector<std::uint32_t>> setBoundary(std::uint32_t b, const NetworkBoundary& boundary);
  // New points for a curve (same count and closure): affects every row that reads it.
  Result<std::vector<std::uint32_t>> setCurvePoints(std::uint32_t curve, std::span<const Vec3> points);

 private:
  Network() = default;
  Status rebuildCardinals(std::vector<std::string>* warnings);
  std::vector<std::uint32_t> rowsPatches(std::vector<std::uint32_t> rows) const;

  NetworkDescription description_;
  std::uint32_t rows_ = 0;
  bool closed_v_ = false;
  std::vector<NetworkCurve> curves_;
  std::vector<std::vector<CurveTerm>> first_terms_;   // per boundary
  std::vector<std::vector<CurveTerm>> second_terms_;  // per boundary
  std::vector<Ode6Cardinal> cardinals_;
  std::vector<std::uint32_t> cardinal_of_patch_;      // rows x columns
};

}  // namespace odeskin

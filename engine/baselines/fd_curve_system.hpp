// SPDX-License-Identifier: MIT
// Finite-difference solution of the dynamic curve deformation of thesis 5.5 on one iso-curve: the
// lowered operator of MATH.md 5.1 acting on the curve's displacement u(v, t), v in [0, 1) periodic,
// t in [0, 1] (one segment):
//   rho u_tt + eta u_t + s xi u_vv + zeta u = t Ftilde(v)        (s = +1 thesis sign, -1 stiffening,
//                                                                  Material::bending, erratum G12)
//   u(v, 0) = 0,  u_t(v, 0) = rate(v),  u(v, 1) = Delta(v)      (the constraints of thesis 5.4)
// with the force amplitude Ftilde(v) unknown, exactly the problem the analytic time basis solves per
// Fourier mode (MATH.md 5.2), discretised instead of diagonalised:
//   grid   v_j = j / J (j = 0..J-1, periodic), t_n = n / T (n = 0..T);
//   space  u_vv ~ (u_{j+1} - 2 u_j + u_{j-1}) / dv^2 (central, periodic wrap);
//   rho != 0: the equation at (v_j, t_n), n = 1..T-1, with central differences
//          u_tt ~ (u^{n+1} - 2 u^n + u^{n-1}) / dt^2, u_t ~ (u^{n+1} - u^{n-1}) / (2 dt), and at n = 0
//          the same equation with the ghost value u^{-1} = u^1 - 2 dt rate (central initial
//          velocity), which reduces to (2 rho / dt^2) u^1 = (2 rho / dt - eta) rate;
//   rho = 0 (first order or static): the rate cannot be imposed (MATH.md 5.3, as in the analytic
//          basis) and the equation is taken at the midpoints t_{n+1/2}, n = 0..T-1 (central
//          difference of u^{n+1} - u^n, average of the spatial operator: Crank-Nicolson).
// Unknowns: u at n = 1..T-1 for every j, and Ftilde_j: J T of them, as many as equations; one
// sparse space-time system, second order in dv and dt. The matrix depends only on the material
// and the grid, so it is factorised once (Eigen SparseLU) and reused for every curve of that
// material and all three coordinates.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "../offline/material.hpp"

namespace odeskin {

class FdCurveSystem {
 public:
  // points J >= 1 (J = 1: a spatially constant field, no v coupling, e.g. an open curve's linear
  // trend, on which u_vv vanishes), steps T >= 2. Errors: kInvalidArgument for non-finite material
  // values, J = 0, T < 2 or J T > 4e6; kDegenerate for rho = eta = zeta = xi = 0; kIllPosed when
  // the factorisation fails (the discrete analogue of a resonant mode, MATH.md 5.4).
  static Result<FdCurveSystem> create(const Material& material, std::uint32_t points, std::uint32_t steps);

  std::uint32_t points() const { return points_; }
  std::uint32_t steps() const { return steps_; }
  std::size_t unknowns() const { return static_cast<std::size_t>(points_) * steps_; }
  bool rateIgnored() const { return rho_ == 0.0; }

  // target: J values Delta(v_j); rate: J values u_t(v_j, 0), or empty for zero (ignored when
  // rateIgnored()); out: (T + 1) x J values u(v_j, t_n), time-major (out[n J + j]); force: J
  // values Ftilde(v_j), or empty. Errors: kInvalidArgument for wrong sizes or non-finite input, and
  // for a non-zero rate when eta dt > 2 rho > 0 (the start would reverse it; see the .cpp).
  Status solve(std::span<const Vec3> target, std::span<const Vec3> rate, std::span<Vec3> out,
               std::span<Vec3> force = {}) const;

  // u_t(v_j, 1) of a solution (out of solve) by the second-order backward difference
  // (3 u^T - 4 u^{T-1} + u^{T-2}) / (2 dt), J values into `rates`: the rate the next segment starts with.
  void endRates(std::span<const Vec3> solution, std::span<Vec3> rates) const;

 private:
  using Solver = Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>;

  std::uint32_t points_ = 0;
  std::uint32_t steps_ = 0;
  double rho_ = 0.0, eta_ = 0.0;
  double target_coupling_ = 0.0;   // coefficient of u^T in the rows of the last unknown level
  double target_neighbour_ = 0.0;  // first order: coefficient of u^T at the neighbours j +- 1
  double scale_ = 1.0;             // rows were divided by it; the force unknown is Ftilde / scale
  std::unique_ptr<Solver> solver_;  // SparseLU is neither copyable nor movable
};

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "fd_curve_system.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"

namespace odeskin {
namespace {

constexpr std::size_t kMaxUnknowns = 4'000'000;

}  // namespace

Result<FdCurveSystem> FdCurveSystem::create(const Material& material, std::uint32_t points, std::uint32_t steps) {
  const double rho = material.rho, eta = material.eta, zeta = material.zeta, xi = material.xi;
  if (!std::isfinite(rho) || !std::isfinite(eta) || !std::isfinite(zeta) || !std::isfinite(xi)) {
    return invalidArgument("fd curve: material " + describe(material) + " is not finite");
  }
  if (rho == 0.0 && eta == 0.0 && zeta == 0.0 && xi == 0.0) {
    return degenerate("fd curve: material " + describe(material) + " has no terms (the equation reads 0 = t F)");
  }
  if (points == 0 || steps < 2) {
    return invalidArgument("fd curve: grid of " + std::to_string(points) + " points x " + std::to_string(steps) +
                           " steps (needs J >= 1, T >= 2)");
  }
  const std::size_t j_count = points;
  const std::size_t t_count = steps;
  if (j_count * t_count > kMaxUnknowns) {
    return invalidArgument("fd curve: grid of " + std::to_string(points) + " x " + std::to_string(steps) +
                           " is too large for one space-time system");
  }
  const double dt = 1.0 / static_cast<double>(t_count);
  const double dv = 1.0 / static_cast<double>(j_count);
  // s xi u_vv: the thesis lowers +xi d2/dv2 (MATH.md 5.1); stiffening flips the sign.
  const double sign = material.bending == BendingSign::kThesis ? 1.0 : -1.0;
  const double bend = j_count > 1 ? sign * xi / (dv * dv) : 0.0;
  // Rows are divided by the largest coefficient and Ftilde is solved as Ftilde / scale, so the
  // matrix entries are O(1) whatever the material's units.
  const double scale = std::max({std::abs(rho) / (dt * dt), std::abs(eta) / dt, std::abs(zeta), std::abs(bend), 1.0});

  FdCurveSystem sys;
  sys.points_ = points;
  sys.steps_ = steps;
  sys.rho_ = rho;
  sys.eta_ = eta;
  auto u_col = [&](std::size_t n, std::size_t j) { return static_cast<int>((n - 1) * j_count + j); };
  auto f_col = [&](std::size_t j) { return static_cast<int>((t_count - 1) * j_count + j); };
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(j_count * t_count * 8);
  // Adds coefficient c of u(n, j) to `row` unless level n is known (n = 0: zero; n = T: the target,
  // whose coefficients solve() moves to the right-hand side).
  auto add_u = [&](int row, std::size_t n, std::size_t j, double c) {
    if (n == 0 || n == t_count || c == 0.0) return;
    entries.emplace_back(row, u_col(n, j), c / scale);
  };
  auto add_level = [&](int row, std::size_t n, std::size_t j, double diagonal, double neighbour) {
    add_u(row, n, j, diagonal);
    if (neighbour != 0.0) {
      add_u(row, n, (j + 1) % j_count, neighbour);
      add_u(row, n, (j + j_count - 1) % j_count, neighbour);
    }
  };
  if (rho != 0.0) {
    const double c_minus = rho / (dt * dt) - eta / (2.0 * dt);
    const double c_plus = rho / (dt * dt) + eta / (2.0 * dt);
    const double c_centre = -2.0 * rho / (dt * dt) + zeta - 2.0 * bend;
    for (std::size_t j = 0; j < j_count; ++j) {
      add_u(static_cast<int>(j), 1, j, 2.0 * rho / (dt * dt));  // n = 0 with the ghost level
    }
    for (std::size_t n = 1; n < t_count; ++n) {
      for (std::size_t j = 0; j < j_count; ++j) {
        const int row = static_cast<int>(n * j_count + j);
        add_u(row, n - 1, j, c_minus);
        add_level(row, n, j, c_centre, bend);
        add_u(row, n + 1, j, c_plus);
        entries.emplace_back(row, f_col(j), -static_cast<double>(n) * dt);
      }
    }
    sys.target_coupling_ = c_plus / scale;
  } else {
    const double diagonal = 0.5 * (zeta - 2.0 * bend);
    const double neighbour = 0.5 * bend;
    for (std::size_t n = 0; n < t_count; ++n) {
      for (std::size_t j = 0; j < j_count; ++j) {
        const int row = static_cast<int>(n * j_count + j);
        add_level(row, n, j, -eta / dt + diagonal, neighbour);
        add_level(row, n + 1, j, eta / dt + diagonal, neighbour);
        entries.emplace_back(row, f_col(j), -(static_cast<double>(n) + 0.5) * dt);
      }
    }
    sys.target_coupling_ = (eta / dt + diagonal) / scale;
    sys.target_neighbour_ = neighbour / scale;
  }
  const auto size = static_cast<Eigen::Index>(j_count * t_count);
  Eigen::SparseMatrix<double> matrix(size, size);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  sys.solver_ = std::make_unique<Solver>();
  sys.solver_->compute(matrix);
  if (sys.solver_->info() != Eigen::Success) {
    return illPosed("fd curve: the space-time system for " + describe(material) + " on " + std::to_string(points) +
                    " x " + std::to_string(steps) + " is singular (" + sys.solver_->lastErrorMessage() + ")");
  }
  sys.scale_ = scale;
  return sys;
}

Status FdCurveSystem::solve(std::span<const Vec3> target, std::span<const Vec3> rate, std::span<Vec3> out,
                            std::span<Vec3> force) const {
  const std::size_t j_count = points_;
  const std::size_t t_count = steps_;
  if (target.size() != j_count || (!rate.empty() && rate.size() != j_count) || out.size() != (t_count + 1) * j_count ||
      (!force.empty() && force.size() != j_count)) {
    return invalidArgument("fd curve: solve needs " + std::to_string(j_count) + " targets and rates, " +
                           std::to_string((t_count + 1) * j_count) + " outputs (got " + std::to_string(target.size()) +
                           ", " + std::to_string(rate.size()) + ", " + std::to_string(out.size()) + ")");
  }
  for (std::size_t j = 0; j < j_count; ++j) {
    if (!isFinite(target[j]) || (!rate.empty() && !isFinite(rate[j]))) {
      return invalidArgument("fd curve: target or rate at grid point " + std::to_string(j) + " is not finite");
    }
  }
  const double dt = 1.0 / static_cast<double>(t_count);
  // The start (2 rho / dt^2) u^1 = (2 rho / dt - eta) rate moves against the rate once eta dt > 2 rho:
  // the damping layer (rho / eta) is thinner than a step, and the odd-even mode it starts barely
  // decays (0.15 off at t = 1/2 for rho 1e-3, eta 1e3, T = 1024). Refused rather than solved wrongly.
  const bool moving_start = !rate.empty() && std::any_of(rate.begin(), rate.end(), [](const Vec3& r) { return r != Vec3(0.0); });
  if (moving_start && rho_ > 0.0 && eta_ * dt > 2.0 * rho_) {
    return invalidArgument("fd curve: a start rate with eta dt / (2 rho) = " + messageNumber(eta_ * dt / (2.0 * rho_)) +
                           " > 1: the damping layer rho / eta = " + messageNumber(rho_ / eta_) +
                           " is thinner than a time step, and the central-difference start would reverse the rate; "
                           "use at least " + messageNumber(std::ceil(eta_ / (2.0 * rho_))) + " steps");
  }
  const auto size = static_cast<Eigen::Index>(j_count * t_count);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(size, 3);
  const std::size_t last = (t_count - 1) * j_count;  // rows that touch the known level T
  for (std::size_t j = 0; j < j_count; ++j) {
    for (int c = 0; c < 3; ++c) {
      double coupled = target_coupling_ * target[j][c];
      if (target_neighbour_ != 0.0) {
        coupled += target_neighbour_ * (target[(j + 1) % j_count][c] + target[(j + j_count - 1) % j_count][c]);
      }
      rhs(static_cast<Eigen::Index>(last + j), c) -= coupled;
      if (rho_ != 0.0 && !rate.empty()) {
        rhs(static_cast<Eigen::Index>(j), c) += (2.0 * rho_ / dt - eta_) * rate[j][c] / scale_;
      }
    }
  }
  const Eigen::MatrixXd x = solver_->solve(rhs);
  if (solver_->info() != Eigen::Success || !x.allFinite()) return illPosed("fd curve: the space-time solve failed");
  for (std::size_t j = 0; j < j_count; ++j) out[j] = Vec3(0.0);
  for (std::size_t n = 1; n < t_count; ++n) {
    for (std::size_t j = 0; j < j_count; ++j) {
      const auto r = static_cast<Eigen::Index>((n - 1) * j_count + j);
      out[n * j_count + j] = Vec3(x(r, 0), x(r, 1), x(r, 2));
    }
  }
  for (std::size_t j = 0; j < j_count; ++j) out[t_count * j_count + j] = target[j];
  for (std::size_t j = 0; j < force.size(); ++j) {
    const auto r = static_cast<Eigen::Index>(last + j);
    force[j] = scale_ * Vec3(x(r, 0), x(r, 1), x(r, 2));
  }
  return okStatus();
}

void FdCurveSystem::endRates(std::span<const Vec3> solution, std::span<Vec3> rates) const {
  const std::size_t j_count = points_;
  const std::size_t t_count = steps_;
  const double dt = 1.0 / static_cast<double>(t_count);
  for (std::size_t j = 0; j < j_count && j < rates.size(); ++j) {
    rates[j] = (3.0 * solution[t_count * j_count + j] - 4.0 * solution[(t_count - 1) * j_count + j] +
                solution[(t_count - 2) * j_count + j]) /
               (2.0 * dt);
  }
}

}  // namespace odeskin

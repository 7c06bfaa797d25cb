// SPDX-License-Identifier: MIT
// Per vertex i with candidate bones b_1..b_n and d_b = stacked over poses (T_bk x_i - p_ki):
//   min_w 1/2 |D w|^2 + 1/2 lambda |w - w_prior|^2   s.t. w >= 0, sum w = 1,
// where sum w = 1 lets the positions be replaced by the errors d_b, so the problem does not depend
// on where the origin is. lambda = prior_pull x the mean |d_b|^2 of the candidates: a bone that
// fits clearly better wins, and among bones that fit alike (a rigid region covered by bones that
// move together) the smooth prior decides. Solved by a primal active-set method on the simplex (n <= 8);
// when more than max_influences weights stay positive, the largest are kept and the problem is
// solved again on them (SSDR's sparsity step).
#include "vertex_weight_fit.hpp"
#include "../core/parallel.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace odeskin {
namespace {

constexpr std::size_t kMaxCandidates = 8;
// Bounded sizes keep a vertex's small matrices off the heap (the same dynamic-size algorithms).
constexpr int kMaxSize = static_cast<int>(kMaxCandidates);
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxSize, kMaxSize>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxSize, 1>;
using KktMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxSize + 1, kMaxSize + 1>;
using KktVector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxSize + 1, 1>;

// Minimises 1/2 w^T G w - g^T w on the simplex; G must be positive definite.
SmallVector solveOnSimplex(const SmallMatrix& big_g, const SmallVector& g) {
  const Eigen::Index n = g.size();
  Eigen::Index start = 0;
  for (Eigen::Index j = 1; j < n; ++j) {
    if (0.5 * big_g(j, j) - g(j) < 0.5 * big_g(start, start) - g(start)) start = j;
  }
  SmallVector w = SmallVector::Zero(n);
  w(start) = 1.0;
  std::vector<Eigen::Index> free{start};
  const double tolerance = 1e-13 * (big_g.diagonal().cwiseAbs().maxCoeff() + g.cwiseAbs().maxCoeff());
  for (int outer = 0; outer < 4 * static_cast<int>(n); ++outer) {
    // On the free set the gradient equals the multiplier of sum w = 1; a fixed weight whose
    // gradient is below it would lower the objective by growing.
    const SmallVector gradient = big_g * w - g;
    const double level = gradient(free[0]);
    Eigen::Index enter = -1;
    double most = -tolerance;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::find(free.begin(), free.end(), j) != free.end()) continue;
      if (gradient(j) - level < most) {
        most = gradient(j) - level;
        enter = j;
      }
    }
    if (enter < 0) break;
    free.push_back(enter);
    for (Eigen::Index inner = 0; inner <= n; ++inner) {
      const auto f = static_cast<Eigen::Index>(free.size());
      KktMatrix kkt = KktMatrix::Zero(f + 1, f + 1);
      KktVector rhs(f + 1);
      for (Eigen::Index a = 0; a < f; ++a) {
        for (Eigen::Index b = 0; b < f; ++b) kkt(a, b) = big_g(free[a], free[b]);
        kkt(a, f) = kkt(f, a) = 1.0;
        rhs(a) = g(free[a]);
      }
      rhs(f) = 1.0;
      const KktVector z = kkt.partialPivLu().solve(rhs);
      double step = 1.0;
      for (Eigen::Index a = 0; a < f; ++a) {
        const double wa = w(free[a]);
        if (z(a) <= 0.0 && wa - z(a) > 0.0) step = std::min(step, wa / (wa - z(a)));
      }
      for (Eigen::Index a = 0; a < f; ++a) w(free[a]) += step * (z(a) - w(free[a]));
      if (step == 1.0) break;
      // Blocked: the weights that reached zero leave the free set.
      std::erase_if(free, [&](Eigen::Index j) {
        if (w(j) > 1e-15) return false;
        w(j) = 0.0;
        return true;
      });
      if (free.empty()) break;
    }
    if (free.empty()) {
      w.setZero();
      w(start) = 1.0;
      break;
    }
  }
  return w;
}

}  // namespace

std::vector<WeightRow> fitVertexWeights(const MotionData& m, const std::vector<std::vector<RigidTransform>>& transforms,
                                        const std::vector<WeightRow>& prior, int max_influences, double prior_pull) {
  const std::size_t poses = m.poseCount();
  const auto rows = static_cast<Eigen::Index>(3 * poses);
  std::vector<WeightRow> out(m.vertexCount());
  const double floor = 1e-24 * m.box * m.box * static_cast<double>(poses);
  parallelFor(std::size_t{0}, m.vertexCount(), [&](std::size_t i) {
    WeightRow candidates = prior[i];
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const BoneWeight& a, const BoneWeight& b) { return a.weight > b.weight; });
    if (candidates.size() > kMaxCandidates) candidates.resize(kMaxCandidates);
    auto solve = [&](const WeightRow& set) {
      const auto n = static_cast<Eigen::Index>(set.size());
      Eigen::MatrixXd d(rows, n);
      for (Eigen::Index b = 0; b < n; ++b) {
        for (std::size_t k = 0; k < poses; ++k) {
          const Vec3 e = transforms[k][set[static_cast<std::size_t>(b)].bone].apply(m.rest[i]) - (*m.poses)[k][i];
          for (int c = 0; c < 3; ++c) d(static_cast<Eigen::Index>(3 * k) + c, b) = e[c];
        }
      }
      SmallMatrix g = d.transpose() * d;
      const double lambda = prior_pull * g.trace() / static_cast<double>(n) + floor;
      SmallVector target(n);
      double prior_sum = 0.0;
      for (const BoneWeight& e : set) prior_sum += e.weight;
      for (Eigen::Index b = 0; b < n; ++b) target(b) = lambda * set[static_cast<std::size_t>(b)].weight / prior_sum;
      g.diagonal().array() += lambda;
      const SmallVector w = solveOnSimplex(g, target);
      WeightRow row;
      for (Eigen::Index b = 0; b < n; ++b) {
        if (w(b) > 0.0) row.push_back({set[static_cast<std::size_t>(b)].bone, w(b)});
      }
      return row;
    };
    WeightRow row = solve(candidates);
    if (row.size() > static_cast<std::size_t>(max_influences)) {
      std::stable_sort(row.begin(), row.end(), [](const BoneWeight& a, const BoneWeight& b) { return a.weight > b.weight; });
      row.resize(static_cast<std::size_t>(max_influences));
      std::erase_if(candidates, [&](const BoneWeight& c) {
        return std::none_of(row.begin(), row.end(), [&](const BoneWeight& r) { return r.bone == c.bone; });
      });
      row = solve(candidates);
    }
    std::sort(row.begin(), row.end(), [](const BoneWeight& a, const BoneWeight& b) { return a.bone < b.bone; });
    out[i] = std::move(row);
  });
  return out;
}

}  // namespace odeskin

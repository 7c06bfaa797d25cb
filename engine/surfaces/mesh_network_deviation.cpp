// SPDX-License-Identifier: MIT
#include "mesh_network_deviation.hpp"
#include "../core/parallel.hpp"

#include <algorithm>
#include <cmath>


namespace odeskin {
namespace {

// S and its derivatives in the network's global (U, V).
struct GlobalPoint {
  Vec3 s{0.0};
  Vec3 s_u{0.0};
  Vec3 s_v{0.0};
};

GlobalPoint evaluateGlobal(const Network& network, Vec2 uv) {
  const NetworkParameter p = networkParameter(network, uv);
  const PatchPoint point = network.evaluate(p.row, p.column, p.u, p.v);
  return {point.s, point.s_u * static_cast<double>(network.rows()), point.s_v * static_cast<double>(network.columns())};
}

}  // namespace

NetworkParameter networkParameter(const Network& network, Vec2 uv) {
  uv = glm::clamp(uv, Vec2(0.0), Vec2(1.0));
  const double u = uv.x * network.rows(), v = uv.y * network.columns();
  NetworkParameter p;
  p.row = std::min(static_cast<std::uint32_t>(u), network.rows() - 1);
  p.column = std::min(static_cast<std::uint32_t>(v), network.columns() - 1);
  p.u = std::clamp(u - p.row, 0.0, 1.0);
  p.v = std::clamp(v - p.column, 0.0, 1.0);
  return p;
}

std::vector<Vec3> evaluateAtParameters(const Network& network, std::span<const Vec2> uv) {
  std::vector<Vec3> out(uv.size());
  parallelFor(std::size_t{0}, uv.size(), [&](std::size_t i) {
    const NetworkParameter p = networkParameter(network, uv[i]);
    out[i] = network.evaluate(p.row, p.column, p.u, p.v).s;
  });
  return out;
}

SurfacePoint nearestOnNetwork(const Network& network, const Vec3& x, Vec2 start) {
  Vec2 uv = glm::clamp(start, Vec2(0.0), Vec2(1.0));
  GlobalPoint g = evaluateGlobal(network, uv);
  double distance = glm::distance(x, g.s);
  for (int step = 0; step < 20 && distance > 0.0; ++step) {
    const Vec3 r = x - g.s;
    const double a = glm::dot(g.s_u, g.s_u), b = glm::dot(g.s_u, g.s_v), c = glm::dot(g.s_v, g.s_v);
    // Damping keeps the step finite where the parameterisation degenerates (the disk's corners).
    const double damping = 1e-10 * (a + c) + 1e-300;
    const double det = (a + damping) * (c + damping) - b * b;
    if (!(det > 0.0)) break;
    const double gu = glm::dot(g.s_u, r), gv = glm::dot(g.s_v, r);
    Vec2 delta(((c + damping) * gu - b * gv) / det, ((a + damping) * gv - b * gu) / det);
    bool improved = false;
    for (int halving = 0; halving < 8 && !improved; ++halving, delta *= 0.5) {
      const Vec2 next = glm::clamp(uv + delta, Vec2(0.0), Vec2(1.0));
      const GlobalPoint candidate = evaluateGlobal(network, next);
      const double d = glm::distance(x, candidate.s);
      if (d < distance) {
        improved = true;
        const double moved = glm::length(next - uv);
        uv = next;
        g = candidate;
        distance = d;
        if (moved < 1e-13) step = 20;
      }
    }
    if (!improved) break;
  }
  return {uv, g.s, distance};
}

MeshDeviation measureDeviation(const Network& network, std::span<const Vec2> uv, std::span<const Vec3> positions,
                               std::span<const std::uint8_t> excluded, std::vector<Vec3>* reconstruction) {
  const std::size_t n = positions.size();
  std::vector<Vec3> surface(n);
  std::vector<double> parametric(n), nearest(n);
  parallelFor(std::size_t{0}, n, [&](std::size_t i) {
    const NetworkParameter p = networkParameter(network, uv[i]);
    surface[i] = network.evaluate(p.row, p.column, p.u, p.v).s;
    parametric[i] = glm::distance(surface[i], positions[i]);
    const bool measured = excluded.empty() || excluded[i] == 0;
    nearest[i] = measured ? std::min(parametric[i], nearestOnNetwork(network, positions[i], uv[i]).distance) : 0.0;
  });
  MeshDeviation d;
  Vec3 lo(0.0), hi(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (!excluded.empty() && excluded[i] != 0) continue;
    lo = d.measured == 0 ? positions[i] : glm::min(lo, positions[i]);
    hi = d.measured == 0 ? positions[i] : glm::max(hi, positions[i]);
    ++d.measured;
  }
  d.excluded = n - d.measured;
  const Vec3 side = hi - lo;
  d.box = std::max({side.x, side.y, side.z});
  const double scale = d.box > 0.0 ? 1.0 / d.box : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!excluded.empty() && excluded[i] != 0) {
      d.excluded_max_parametric = std::max(d.excluded_max_parametric, parametric[i] * scale);
      continue;
    }
    d.mean_parametric += parametric[i];
    d.mean_surface += nearest[i];
    d.max_parametric = std::max(d.max_parametric, parametric[i] * scale);
    if (nearest[i] * scale >= d.max_surface) {
      d.max_surface = nearest[i] * scale;
      d.worst_vertex = static_cast<std::uint32_t>(i);
    }
  }
  if (d.measured > 0) {
    d.mean_parametric *= scale / static_cast<double>(d.measured);
    d.mean_surface *= scale / static_cast<double>(d.measured);
  }
  if (reconstruction) *reconstruction = std::move(surface);
  return d;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "mesh_network_locate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace odeskin {
namespace {

// Barycentric coordinates of p in triangle (a, b, c); all 1/3 for a degenerate triangle's corners.
std::array<double, 3> barycentric(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (area == 0.0) return {-1.0, -1.0, -1.0};
  const double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / area;
  const double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / area;
  return {wa, wb, 1.0 - wa - wb};
}

}  // namespace

DiskLocator::DiskLocator(const MeshDisk& disk) : disk_(&disk) {
  // About two triangles per cell.
  cells_ = std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::sqrt(0.5 * static_cast<double>(disk.triangles.size()))));
  const auto cell = [&](double t) {
    return std::min<std::uint32_t>(cells_ - 1, static_cast<std::uint32_t>(std::max(0.0, t) * cells_));
  };
  std::vector<std::uint32_t> counts(std::size_t{cells_} * cells_ + 1, 0);
  const auto visit = [&](const std::array<std::uint32_t, 3>& t, auto&& f) {
    Vec2 lo = disk.uv[t[0]], hi = disk.uv[t[0]];
    for (int k = 1; k < 3; ++k) {
      lo = glm::min(lo, disk.uv[t[k]]);
      hi = glm::max(hi, disk.uv[t[k]]);
    }
    for (std::uint32_t i = cell(lo.x); i <= cell(hi.x); ++i) {
      for (std::uint32_t j = cell(lo.y); j <= cell(hi.y); ++j) f(std::size_t{i} * cells_ + j);
    }
  };
  for (const auto& t : disk.triangles) visit(t, [&](std::size_t c) { ++counts[c + 1]; });
  for (std::size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
  cell_offsets_ = counts;
  cell_triangles_.resize(counts.back());
  for (std::uint32_t f = 0; f < disk.triangles.size(); ++f) {
    visit(disk.triangles[f], [&](std::size_t c) { cell_triangles_[counts[c]++] = f; });
  }
}

MeshPoint DiskLocator::locate(Vec2 uv) const {
  uv = glm::clamp(uv, Vec2(0.0), Vec2(1.0));
  const auto cell = [&](double t) { return std::min<std::uint32_t>(cells_ - 1, static_cast<std::uint32_t>(t * cells_)); };
  const std::uint32_t ci = cell(uv.x), cj = cell(uv.y);
  double best = -std::numeric_limits<double>::infinity();
  MeshPoint point;
  // The point's own cell holds its triangle; rounding at a cell edge may need a neighbour's.
  for (std::uint32_t ring = 0; ring <= cells_ && best < -1e-12; ++ring) {
    // cppcheck-suppress constStatement ; false positive: cppcheck misparses std::int64_t{ci} in a for header
    for (std::int64_t i = std::int64_t{ci} - ring; i <= std::int64_t{ci} + ring; ++i) {
      // cppcheck-suppress constStatement ; as above
      for (std::int64_t j = std::int64_t{cj} - ring; j <= std::int64_t{cj} + ring; ++j) {
        if (i < 0 || j < 0 || i >= cells_ || j >= cells_) continue;
        if (std::max(std::abs(i - ci), std::abs(j - cj)) != ring) continue;
        const std::size_t c = static_cast<std::size_t>(i) * cells_ + static_cast<std::size_t>(j);
        for (std::uint32_t k = cell_offsets_[c]; k < cell_offsets_[c + 1]; ++k) {
          const auto& t = disk_->triangles[cell_triangles_[k]];
          const std::array<double, 3> w = barycentric(uv, disk_->uv[t[0]], disk_->uv[t[1]], disk_->uv[t[2]]);
          const double worst = std::min({w[0], w[1], w[2]});
          if (worst > best) {
            best = worst;
            point.vertex = t;
            point.weight = w;
          }
        }
      }
    }
  }
  double sum = 0.0;
  for (double& w : point.weight) sum += (w = std::max(0.0, w));
  if (sum > 0.0) {
    for (double& w : point.weight) w /= sum;
  } else {
    point.weight = {1.0, 0.0, 0.0};
  }
  return point;
}

}  // namespace odeskin

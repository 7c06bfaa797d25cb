// SPDX-License-Identifier: MIT
#include "part_curves.hpp"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

namespace odeskin {

void measureCurve(CurveDraft& curve, std::span<const Vec3> rest) {
  const std::size_t n = curve.points.size();
  if (n == 0) return;
  std::vector<Vec3> pos(n);
  for (std::size_t j = 0; j < n; ++j) pos[j] = curvePointPosition(rest, curve.points[j]);
  double length = 0.0;
  Vec3 weighted(0.0);
  Vec3 mean(0.0);
  for (std::size_t j = 0; j < n; ++j) {
    mean += pos[j];
    if (j + 1 == n && !curve.closed) break;
    const Vec3& next = pos[(j + 1) % n];
    const double len = glm::length(next - pos[j]);
    length += len;
    weighted += len * 0.5 * (pos[j] + next);
  }
  curve.centroid = length > 0.0 ? weighted / length : mean / static_cast<double>(n);
  curve.radius = 0.0;
  for (const Vec3& p : pos) curve.radius += glm::length(p - curve.centroid);
  curve.radius /= static_cast<double>(n);
}

void compactCurves(CurveLayout& layout) {
  constexpr std::uint32_t kGone = std::numeric_limits<std::uint32_t>::max();
  std::vector<char> used(layout.curves.size(), 0);
  for (const auto& seq : layout.sequences) {
    for (const Station& s : seq) used[s.curve] = !layout.curves[s.curve].dropped;
  }
  std::vector<std::uint32_t> remap(layout.curves.size(), kGone);
  std::vector<CurveDraft> kept;
  for (std::size_t c = 0; c < layout.curves.size(); ++c) {
    if (!used[c]) continue;
    remap[c] = static_cast<std::uint32_t>(kept.size());
    kept.push_back(std::move(layout.curves[c]));
  }
  layout.curves = std::move(kept);
  for (auto& seq : layout.sequences) {
    std::erase_if(seq, [&](const Station& s) { return remap[s.curve] == kGone; });
    for (Station& s : seq) s.curve = remap[s.curve];
  }
}

}  // namespace odeskin

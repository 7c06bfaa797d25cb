// SPDX-License-Identifier: MIT
#include "skeleton_template.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// Tips within this fraction of the height range above the lowest node count as feet.
constexpr double kLowTips = 0.3;
// A turn-test joint this close to a template position (fraction of the path length) takes its name.
constexpr double kBendTolerance = 0.12;
// A limb shorter than this many radii of its seam ring is a stub: seam and tip joints only.
constexpr double kStubRadii = 3.0;
// Automatic choice: a quadruped's spine (pelvis -> chest) lies within 45 degrees of horizontal, a
// humanoid's (pelvis -> head) within 45 degrees of up.
constexpr double kSpineCos = 0.7071;
// Arms must leave the spine below this fraction of pelvis -> head (the ears of a big head do not).
constexpr double kArmsBelow = 0.8;

// Humanoid ratios along each path (header: Winter's anthropometric table).
constexpr double kKnee = 0.39, kAnkle = 0.78, kElbow = 0.42, kWrist = 0.75, kSpine = 0.5, kHead = 0.3;
// Quadruped ratios (header: legs in thirds).
constexpr double kQuadKnee = 0.35, kQuadHock = 0.7, kQuadNeck = 0.5;

using Path = std::vector<std::uint32_t>;

struct Walker {
  const SkeletonTreeView& tree;
  std::span<const std::uint32_t> bends;
  std::vector<char> claimed;  // bend nodes already named

  double height(std::uint32_t n, const Vec3& up) const { return glm::dot(tree.positions[n], up); }

  // The nodes from a to b (inclusive) along the tree.
  Path path(std::uint32_t a, std::uint32_t b) const {
    std::vector<std::int64_t> from(tree.positions.size(), -2);
    std::vector<std::uint32_t> queue{a};
    from[a] = -1;
    for (std::size_t head = 0; head < queue.size() && from[b] == -2; ++head) {
      for (const std::uint32_t m : tree.adjacent[queue[head]]) {
        if (from[m] != -2) continue;
        from[m] = queue[head];
        queue.push_back(m);
      }
    }
    Path out;
    if (from[b] == -2) return out;
    for (std::int64_t n = b; n >= 0; n = from[static_cast<std::size_t>(n)]) out.push_back(static_cast<std::uint32_t>(n));
    std::reverse(out.begin(), out.end());
    return out;
  }

  double length(const Path& p) const {
    double l = 0.0;
    for (std::size_t i = 1; i < p.size(); ++i) l += glm::length(tree.positions[p[i]] - tree.positions[p[i - 1]]);
    return l;
  }

  // From a tip up to the first node where another branch leaves (or the whole tree's far end).
  Path branch(std::uint32_t tip) const {
    Path p{tip};
    std::int64_t previous = -1;
    std::uint32_t at = tip;
    while (true) {
      std::int64_t next = -1;
      for (const std::uint32_t m : tree.adjacent[at]) {
        if (static_cast<std::int64_t>(m) != previous) next = m;
      }
      if (next < 0) break;
      previous = at;
      at = static_cast<std::uint32_t>(next);
      p.push_back(at);
      if (tree.adjacent[at].size() >= 3) break;
    }
    std::reverse(p.begin(), p.end());  // attach node first, tip last
    return p;
  }

  // The joint at `ratio` of the path's arc length: a turn-test joint nearby, else the nearest node.
  TemplateJoint atRatio(const Path& p, double ratio, const std::string& name) {
    std::vector<double> s(p.size(), 0.0);
    for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + glm::length(tree.positions[p[i]] - tree.positions[p[i - 1]]);
    const double target = ratio * s.back();
    std::int64_t best_bend = -1;
    double best_gap = kBendTolerance * s.back();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (std::abs(s[i] - target) < std::abs(s[nearest] - target)) nearest = i;
      const auto it = std::find(bends.begin(), bends.end(), p[i]);
      if (it == bends.end() || claimed[static_cast<std::size_t>(it - bends.begin())]) continue;
      if (std::abs(s[i] - target) <= best_gap) {
        best_gap = std::abs(s[i] - target);
        best_bend = static_cast<std::int64_t>(it - bends.begin());
      }
    }
    TemplateJoint j;
    j.name = name;
    if (best_bend >= 0) {
      claimed[static_cast<std::size_t>(best_bend)] = 1;
      j.node = bends[static_cast<std::size_t>(best_bend)];
      j.is_bend = true;
    } else {
      j.node = p[nearest];
    }
    return j;
  }
};

std::vector<std::uint32_t> leavesOf(const SkeletonTreeView& tree) {
  std::vector<std::uint32_t> leaves;
  for (std::uint32_t n = 0; n < tree.adjacent.size(); ++n) {
    if (tree.adjacent[n].size() <= 1) leaves.push_back(n);
  }
  return leaves;
}

// Unit `v` without its component along `up` (zero if parallel).
Vec3 flatten(const Vec3& v, const Vec3& up) {
  const Vec3 f = v - glm::dot(v, up) * up;
  return glm::length(f) > 1e-12 ? glm::normalize(f) : Vec3(0.0);
}

std::string side(const Vec3& offset, const Vec3& left) { return glm::dot(offset, left) >= 0.0 ? "l_" : "r_"; }

// A limb: its branch (attach node .. tip) and its seam (the first ring after the attach node).
struct Limb {
  std::uint32_t tip = 0;
  Path branch;
  std::uint32_t attach() const { return branch.front(); }
  std::uint32_t seam() const { return branch.size() > 2 ? branch[1] : branch.back(); }
  Path fromSeam() const { return branch.size() > 2 ? Path(branch.begin() + 1, branch.end()) : branch; }
};

void addLimb(Walker& w, const Limb& limb, const std::string& prefix, const std::array<const char*, 4>& names,
             const std::array<double, 2>& ratios, TemplateMatch& m) {
  m.joints.push_back({limb.seam(), prefix + names[0], false, false, Vec3(0.0)});
  const Path p = limb.fromSeam();
  // A stub (shorter than kStubRadii of its seam ring's radii) has no room for inner joints.
  if (w.length(p) >= kStubRadii * w.tree.radii[limb.seam()]) {
    m.joints.push_back(w.atRatio(p, ratios[0], prefix + names[1]));
    m.joints.push_back(w.atRatio(p, ratios[1], prefix + names[2]));
  }
  m.joints.push_back({limb.tip, prefix + names[3], false, false, Vec3(0.0)});
}

TemplateMatch humanoid(Walker& w, const std::vector<std::uint32_t>& by_height, const Vec3& up) {
  TemplateMatch m;
  m.kind = SkeletonTemplateKind::kHumanoid;
  const SkeletonTreeView& t = w.tree;
  std::array<Limb, 2> legs{Limb{by_height[0], w.branch(by_height[0])}, Limb{by_height[1], w.branch(by_height[1])}};
  std::int64_t head = -1;
  for (auto it = by_height.rbegin(); it != by_height.rend(); ++it) {
    if (*it != legs[0].tip && *it != legs[1].tip) {
      head = *it;
      break;
    }
  }
  if (head < 0) return {SkeletonTemplateKind::kNone, "humanoid: no tip besides the two legs for a head", 0, {}, Vec3(0.0)};
  const auto head_tip = static_cast<std::uint32_t>(head);
  // The pelvis: of the legs' attach nodes, the one nearer the head.
  const std::uint32_t pelvis = w.length(w.path(legs[0].attach(), head_tip)) <= w.length(w.path(legs[1].attach(), head_tip))
                                   ? legs[0].attach()
                                   : legs[1].attach();
  const Path spine = w.path(pelvis, head_tip);
  const double spine_length = w.length(spine);
  // Arms: the other tips whose branches leave the spine lowest.
  std::vector<std::pair<double, Limb>> arms;
  for (const std::uint32_t tip : by_height) {
    if (tip == legs[0].tip || tip == legs[1].tip || tip == head_tip) continue;
    const Path to_head = w.path(tip, head_tip);
    std::size_t k = 0;
    while (k < to_head.size() && std::find(spine.begin(), spine.end(), to_head[k]) == spine.end()) ++k;
    if (k == to_head.size()) continue;
    const Path on_spine = w.path(pelvis, to_head[k]);
    const double s = w.length(on_spine);
    if (s > kArmsBelow * spine_length) continue;
    Limb arm{tip, w.path(to_head[k], tip)};
    arms.push_back({s, arm});
  }
  std::sort(arms.begin(), arms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

  Vec3 forward(0.0);
  const Vec3 feet = flatten(t.positions[legs[0].tip] - t.positions[legs[0].branch[legs[0].branch.size() / 2]], up) +
                    flatten(t.positions[legs[1].tip] - t.positions[legs[1].branch[legs[1].branch.size() / 2]], up);
  forward = glm::length(feet) > 1e-9 ? glm::normalize(feet) : flatten(Vec3(0.0, 0.0, 1.0), up);
  const Vec3 left = glm::cross(up, forward);

  m.root = pelvis;
  const Vec3 hips_mid = 0.5 * (t.positions[legs[0].seam()] + t.positions[legs[1].seam()]);
  m.joints.push_back({pelvis, "pelvis", false, true, hips_mid});
  for (const Limb& leg : legs) {
    addLimb(w, leg, side(t.positions[leg.seam()] - hips_mid, left), {"hip", "knee", "ankle", "toe"}, {kKnee, kAnkle}, m);
  }
  std::uint32_t neck = spine[spine.size() / 2];
  if (arms.size() >= 2) {
    const Limb& a = arms[0].second;
    const Limb& b = arms[1].second;
    neck = arms[0].first >= arms[1].first ? a.attach() : b.attach();
    const Vec3 shoulders_mid = 0.5 * (t.positions[a.seam()] + t.positions[b.seam()]);
    m.joints.push_back({neck, "neck", false, true, shoulders_mid});
    for (const Limb* arm : {&a, &b}) {
      addLimb(w, *arm, side(t.positions[arm->seam()] - shoulders_mid, left), {"shoulder", "elbow", "wrist", "hand"},
              {kElbow, kWrist}, m);
    }
    m.note = "humanoid: legs, head and arms found";
  } else {
    m.joints.push_back({neck, "neck", false, false, Vec3(0.0)});
    m.note = "humanoid: legs and head found, no pair of arms (the neck at half the spine)";
  }
  m.joints.push_back(w.atRatio(w.path(pelvis, neck), kSpine, "spine"));
  m.joints.push_back(w.atRatio(w.path(neck, head_tip), kHead, "head"));
  m.joints.push_back({head_tip, "head_top", false, false, Vec3(0.0)});
  m.spine = t.positions[head_tip] - hips_mid;
  return m;
}

TemplateMatch quadruped(Walker& w, const std::vector<std::uint32_t>& by_height, const Vec3& up) {
  TemplateMatch m;
  m.kind = SkeletonTemplateKind::kQuadruped;
  const SkeletonTreeView& t = w.tree;
  std::array<Limb, 4> legs;
  for (std::size_t i = 0; i < 4; ++i) legs[i] = Limb{by_height[i], w.branch(by_height[i])};
  // Girdles: the pairing of the legs whose attach nodes are closest along the skeleton.
  const std::array<std::array<int, 4>, 3> pairings{{{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}}};
  double best = std::numeric_limits<double>::infinity();
  std::array<int, 4> pairing = pairings[0];
  for (const auto& p : pairings) {
    const double d = w.length(w.path(legs[static_cast<std::size_t>(p[0])].attach(), legs[static_cast<std::size_t>(p[1])].attach())) +
                     w.length(w.path(legs[static_cast<std::size_t>(p[2])].attach(), legs[static_cast<std::size_t>(p[3])].attach()));
    if (d < best) {
      best = d;
      pairing = p;
    }
  }
  std::array<std::array<const Limb*, 2>, 2> girdles{{{&legs[static_cast<std::size_t>(pairing[0])], &legs[static_cast<std::size_t>(pairing[1])]},
                                                     {&legs[static_cast<std::size_t>(pairing[2])], &legs[static_cast<std::size_t>(pairing[3])]}}};
  // Each girdle's node: of its two attach nodes, the one nearer the other girdle.
  std::array<std::uint32_t, 2> node{};
  for (int g = 0; g < 2; ++g) {
    const std::uint32_t other = girdles[static_cast<std::size_t>(1 - g)][0]->attach();
    const std::uint32_t a = girdles[static_cast<std::size_t>(g)][0]->attach();
    const std::uint32_t b = girdles[static_cast<std::size_t>(g)][1]->attach();
    node[static_cast<std::size_t>(g)] = w.length(w.path(a, other)) <= w.length(w.path(b, other)) ? a : b;
  }
  // Head: the thickest other branch; its girdle holds the front legs.
  std::int64_t head = -1;
  int head_girdle = 0;
  double head_radius = -1.0;
  std::vector<std::pair<std::uint32_t, int>> others;
  for (const std::uint32_t tip : by_height) {
    bool is_leg = false;
    for (const Limb& l : legs) is_leg = is_leg || l.tip == tip;
    if (is_leg) continue;
    const double d0 = w.length(w.path(tip, node[0]));
    const double d1 = w.length(w.path(tip, node[1]));
    const int g = d0 <= d1 ? 0 : 1;
    others.push_back({tip, g});
    double radius = 0.0;
    for (const std::uint32_t n : w.path(node[static_cast<std::size_t>(g)], tip)) radius = std::max(radius, t.radii[n]);
    if (radius > head_radius) {
      head_radius = radius;
      head = tip;
      head_girdle = g;
    }
  }
  if (head < 0) return {SkeletonTemplateKind::kNone, "quadruped: no tip besides the four legs for a head", 0, {}, Vec3(0.0)};
  const auto head_tip = static_cast<std::uint32_t>(head);
  const std::size_t fore = static_cast<std::size_t>(head_girdle);
  const std::size_t hind = 1 - fore;
  std::int64_t tail = -1;
  double tail_length = 0.0;
  for (const auto& [tip, g] : others) {
    if (static_cast<std::size_t>(g) != hind) continue;
    const double l = w.length(w.path(node[hind], tip));
    if (l > tail_length) {
      tail_length = l;
      tail = tip;
    }
  }
  const Vec3 hips_mid = 0.5 * (t.positions[girdles[hind][0]->seam()] + t.positions[girdles[hind][1]->seam()]);
  const Vec3 chest_mid = 0.5 * (t.positions[girdles[fore][0]->seam()] + t.positions[girdles[fore][1]->seam()]);
  const Vec3 forward = flatten(chest_mid - hips_mid, up);
  const Vec3 left = glm::cross(up, forward);
  m.root = node[hind];
  m.spine = chest_mid - hips_mid;
  m.joints.push_back({node[hind], "pelvis", false, true, hips_mid});
  m.joints.push_back({node[fore], "chest", false, true, chest_mid});
  for (const Limb* leg : girdles[hind]) {
    addLimb(w, *leg, side(t.positions[leg->seam()] - hips_mid, left) + "hind_", {"hip", "knee", "hock", "paw"},
            {kQuadKnee, kQuadHock}, m);
  }
  for (const Limb* leg : girdles[fore]) {
    addLimb(w, *leg, side(t.positions[leg->seam()] - chest_mid, left) + "fore_", {"shoulder", "elbow", "wrist", "paw"},
            {kQuadKnee, kQuadHock}, m);
  }
  m.joints.push_back(w.atRatio(w.path(node[hind], node[fore]), kSpine, "spine"));
  m.joints.push_back(w.atRatio(w.path(node[fore], head_tip), kQuadNeck, "neck"));
  m.joints.push_back({head_tip, "head_tip", false, false, Vec3(0.0)});
  m.note = "quadruped: four legs and a head found";
  if (tail >= 0) {
    const Limb tail_limb{static_cast<std::uint32_t>(tail), w.branch(static_cast<std::uint32_t>(tail))};
    const Path p = tail_limb.fromSeam();
    m.joints.push_back({tail_limb.seam(), "tail_base", false, false, Vec3(0.0)});
    m.joints.push_back(w.atRatio(p, 1.0 / 3.0, "tail_1"));
    m.joints.push_back(w.atRatio(p, 2.0 / 3.0, "tail_2"));
    m.joints.push_back({tail_limb.tip, "tail_tip", false, false, Vec3(0.0)});
    m.note += " and a tail";
  }
  return m;
}

}  // namespace

std::string_view templateKindName(SkeletonTemplateKind kind) {
  switch (kind) {
    case SkeletonTemplateKind::kNone: return "none";
    case SkeletonTemplateKind::kAuto: return "auto";
    case SkeletonTemplateKind::kHumanoid: return "humanoid";
    case SkeletonTemplateKind::kQuadruped: return "quadruped";
  }
  return "none";
}

std::optional<SkeletonTemplateKind> parseTemplateKind(std::string_view text) {
  for (const SkeletonTemplateKind k : {SkeletonTemplateKind::kNone, SkeletonTemplateKind::kAuto,
                                       SkeletonTemplateKind::kHumanoid, SkeletonTemplateKind::kQuadruped}) {
    if (text == templateKindName(k)) return k;
  }
  return std::nullopt;
}

TemplateMatch matchTemplate(const SkeletonTreeView& tree, std::span<const std::uint32_t> bend_nodes,
                            SkeletonTemplateKind requested, const Vec3& up_axis) {
  if (requested == SkeletonTemplateKind::kNone || tree.positions.empty()) return {};
  const Vec3 up = glm::normalize(up_axis);
  Walker w{tree, bend_nodes, std::vector<char>(bend_nodes.size(), 0)};
  std::vector<std::uint32_t> by_height = leavesOf(tree);
  std::sort(by_height.begin(), by_height.end(), [&](std::uint32_t a, std::uint32_t b) {
    return w.height(a, up) < w.height(b, up);
  });
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::uint32_t n = 0; n < tree.positions.size(); ++n) {
    lo = std::min(lo, w.height(n, up));
    hi = std::max(hi, w.height(n, up));
  }
  std::size_t low = 0;
  for (const std::uint32_t n : by_height) low += w.height(n, up) <= lo + kLowTips * (hi - lo) ? 1 : 0;
  auto spineCos = [&](const TemplateMatch& m) {
    return glm::length(m.spine) > 0.0 ? std::abs(glm::dot(glm::normalize(m.spine), up)) : 0.0;
  };
  if (requested == SkeletonTemplateKind::kHumanoid) {
    if (by_height.size() < 3) return {SkeletonTemplateKind::kNone, "humanoid: fewer than 3 tips", 0, {}, Vec3(0.0)};
    return humanoid(w, by_height, up);
  }
  if (requested == SkeletonTemplateKind::kQuadruped) {
    if (by_height.size() < 5) return {SkeletonTemplateKind::kNone, "quadruped: fewer than 5 tips", 0, {}, Vec3(0.0)};
    return quadruped(w, by_height, up);
  }
  // Automatic: the template whose feet count and spine direction both fit.
  std::string tried = std::to_string(low) + " tip(s) in the lowest 30% of the height";
  // Where both fit (a standing humanoid's hands hang low enough to pass for front feet, with a
  // "spine" from its feet to a hand), the one whose spine lies nearer its own direction: the
  // quadruped's sine against the humanoid's cosine of the angle to up.
  std::optional<TemplateMatch> quad;
  if (low >= 4 && by_height.size() >= 5) {
    TemplateMatch q = quadruped(w, by_height, up);
    if (q.kind == SkeletonTemplateKind::kQuadruped && spineCos(q) < kSpineCos) {
      quad = std::move(q);
    } else {
      tried += "; the quadruped's spine is not horizontal";
    }
    w.claimed.assign(bend_nodes.size(), 0);
  }
  if (low >= 2 && by_height.size() >= 3) {
    TemplateMatch h = humanoid(w, by_height, up);
    if (h.kind == SkeletonTemplateKind::kHumanoid && spineCos(h) >= kSpineCos) {
      if (!quad || spineCos(h) > std::sqrt(1.0 - spineCos(*quad) * spineCos(*quad))) return h;
    } else if (!quad) {
      tried += "; the humanoid's spine is not upright";
    }
  }
  if (quad) return std::move(*quad);
  return {SkeletonTemplateKind::kNone, tried + ": no template", 0, {}, Vec3(0.0)};
}

}  // namespace odeskin

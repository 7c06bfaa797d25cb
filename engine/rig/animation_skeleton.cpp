// SPDX-License-Identifier: MIT
#include "animation_skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace odeskin {
namespace {

// A branch leaving a junction is the body going on (no seam joint) when its first ring is the
// thickest of the junction's branches and at least this fraction of the arriving ring.
constexpr double kContinuation = 0.6;
// ... and at the root, when it is at least this many times as thick as the next branch.
constexpr double kRootContinuation = 1.5;

struct Chain {
  std::vector<std::uint32_t> nodes;  // key node, interior nodes..., key node
};

std::vector<std::vector<std::uint32_t>> adjacencyOf(const CurveSkeleton& s) {
  std::vector<std::vector<std::uint32_t>> adjacent(s.nodeCount());
  for (std::uint32_t n = 0; n < s.nodeCount(); ++n) {
    if (s.parents[n] < 0) continue;
    const auto p = static_cast<std::uint32_t>(s.parents[n]);
    adjacent[n].push_back(p);
    adjacent[p].push_back(n);
  }
  return adjacent;
}

// Paths between nodes whose degree is not 2 (tips, junctions), through nodes of degree 2.
std::vector<Chain> chainsOf(const std::vector<std::vector<std::uint32_t>>& adjacent) {
  std::vector<Chain> chains;
  std::vector<char> used(adjacent.size(), 0);  // interior nodes already on a chain
  for (std::uint32_t k = 0; k < adjacent.size(); ++k) {
    if (adjacent[k].size() == 2) continue;
    for (const std::uint32_t first : adjacent[k]) {
      Chain c;
      c.nodes = {k};
      std::uint32_t previous = k;
      std::uint32_t at = first;
      while (adjacent[at].size() == 2 && !used[at]) {
        used[at] = 1;
        c.nodes.push_back(at);
        const std::uint32_t next = adjacent[at][0] == previous ? adjacent[at][1] : adjacent[at][0];
        previous = at;
        at = next;
      }
      if (adjacent[at].size() == 2) continue;  // walked from the other end already
      c.nodes.push_back(at);
      // A chain with interior nodes is found once (its nodes are used); two key nodes side by
      // side are found from both, and kept from the smaller.
      if (c.nodes.size() == 2 && at < k) continue;
      chains.push_back(std::move(c));
    }
  }
  return chains;
}

double angleDeg(const Vec3& a, const Vec3& b) {
  const double la = glm::length(a);
  const double lb = glm::length(b);
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

// Position at bind arc length `target` along the chain, on `pose`.
Vec3 atArcLength(const std::vector<std::uint32_t>& nodes, const std::vector<double>& s, const std::vector<Vec3>& pose,
                 double target) {
  if (target <= 0.0) return pose[nodes.front()];
  if (target >= s.back()) return pose[nodes.back()];
  const auto it = std::upper_bound(s.begin(), s.end(), target);
  const auto j = static_cast<std::size_t>(it - s.begin());
  const double span = s[j] - s[j - 1];
  const double t = span > 0.0 ? (target - s[j - 1]) / span : 0.0;
  return (1.0 - t) * pose[nodes[j - 1]] + t * pose[nodes[j]];
}

struct Bend {
  std::uint32_t node;
  double deg;
};

// The turn-test joints of one chain (header): largest turn first, one window apart.
void chainBends(const Chain& chain, const CurveSkeleton& cs, const std::vector<std::vector<Vec3>>& poses,
                const AnimationSkeletonOptions& o, std::vector<Bend>& out, std::vector<double>& node_bend) {
  const std::vector<std::uint32_t>& nodes = chain.nodes;
  if (nodes.size() < 3) return;
  std::vector<double> s(nodes.size(), 0.0);
  for (std::size_t i = 1; i < nodes.size(); ++i) s[i] = s[i - 1] + glm::length(cs.positions[nodes[i]] - cs.positions[nodes[i - 1]]);
  std::vector<double> radii;
  for (std::size_t i = 1; i + 1 < nodes.size(); ++i) radii.push_back(cs.radii[nodes[i]]);
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
  const double mean_step = s.back() / static_cast<double>(nodes.size() - 1);
  const double window = std::max(o.window_radii * radii[radii.size() / 2], 3.0 * mean_step);
  std::vector<Bend> candidates;
  for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
    if (s[i] < 0.5 * window || s[i] > s.back() - 0.5 * window) continue;  // a junction or tip is a joint already
    double turn = 0.0;
    for (const std::vector<Vec3>& pose : poses) {
      const Vec3 here = pose[nodes[i]];
      const Vec3 back = atArcLength(nodes, s, pose, s[i] - window);
      const Vec3 ahead = atArcLength(nodes, s, pose, s[i] + window);
      turn = std::max(turn, angleDeg(here - back, ahead - here));
    }
    node_bend[nodes[i]] = turn;
    if (turn > o.angle_threshold_deg) candidates.push_back({nodes[i], turn});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Bend& a, const Bend& b) { return a.deg > b.deg; });
  std::vector<double> taken;
  for (const Bend& b : candidates) {
    const double at = s[static_cast<std::size_t>(std::find(nodes.begin(), nodes.end(), b.node) - nodes.begin())];
    bool near = false;
    for (const double t : taken) near = near || std::abs(t - at) < window;
    if (near) continue;
    taken.push_back(at);
    out.push_back(b);
  }
}

// The root joint without a template: the junction with the most branches, nearest the curve
// skeleton's centre ring (node 0); a tube without junctions hangs from its centre ring, or from a
// bend within one ring radius of it (the centre is only where the distance grew from; a bend
// there is where the tube really turns).
std::uint32_t defaultRoot(const CurveSkeleton& cs, const std::vector<std::vector<std::uint32_t>>& adjacent,
                          const std::vector<Bend>& bends) {
  std::vector<std::int64_t> hops(adjacent.size(), -1);
  std::vector<std::uint32_t> queue{0};
  hops[0] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    for (const std::uint32_t m : adjacent[queue[head]]) {
      if (hops[m] >= 0) continue;
      hops[m] = hops[queue[head]] + 1;
      queue.push_back(m);
    }
  }
  std::uint32_t best = 0;
  for (const std::uint32_t n : queue) {  // in order of hops from node 0
    if (adjacent[n].size() > std::max<std::size_t>(2, adjacent[best].size())) best = n;
  }
  if (best != 0 || adjacent[0].size() > 2) return best;
  double nearest = cs.radii[0];
  for (const Bend& b : bends) {
    const double d = glm::length(cs.positions[b.node] - cs.positions[0]);
    if (d <= nearest) {
      nearest = d;
      best = b.node;
    }
  }
  return best;
}

Status checkInput(const CurveSkeleton& cs, const std::vector<std::vector<Vec3>>& poses, const AnimationSkeletonOptions& o) {
  if (cs.nodeCount() == 0) return invalidArgument("animation skeleton: the curve skeleton has no nodes");
  if (cs.parents.size() != cs.nodeCount() || cs.radii.size() != cs.nodeCount()) {
    return invalidArgument("animation skeleton: the curve skeleton's parents or radii are not one per node");
  }
  for (std::size_t n = 0; n < cs.nodeCount(); ++n) {
    if (cs.parents[n] >= static_cast<std::int32_t>(n) || (n > 0 && cs.parents[n] < 0)) {
      return invalidArgument("animation skeleton: node " + std::to_string(n) + " has parent " + std::to_string(cs.parents[n]) +
                             " (node 0 must be the only root and parents must precede their children)");
    }
  }
  if (poses.empty()) return invalidArgument("animation skeleton: no pose (give at least the bind pose's node positions)");
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (poses[k].size() != cs.nodeCount()) {
      return invalidArgument("animation skeleton: pose " + std::to_string(k) + " has " + std::to_string(poses[k].size()) +
                             " node positions, the curve skeleton " + std::to_string(cs.nodeCount()) + " nodes");
    }
  }
  if (!(o.angle_threshold_deg > 0.0 && o.angle_threshold_deg < 180.0)) {
    return invalidArgument("animation skeleton: the angle threshold must lie in (0, 180) degrees");
  }
  if (!(o.window_radii > 0.0) || !std::isfinite(o.window_radii)) {
    return invalidArgument("animation skeleton: window_radii must be a positive number");
  }
  if (!(glm::length(o.up) > 0.0) || !std::isfinite(glm::length(o.up))) {
    return invalidArgument("animation skeleton: the up axis must be a non-zero vector");
  }
  return okStatus();
}

}  // namespace

const char* reasonName(JointReason r) {
  switch (r) {
    case JointReason::kRoot: return "root";
    case JointReason::kJunction: return "junction";
    case JointReason::kSeam: return "seam";
    case JointReason::kBend: return "bend";
    case JointReason::kTemplate: return "template";
    case JointReason::kTip: return "tip";
  }
  return "joint";
}

Result<AnimationSkeleton> buildAnimationSkeleton(const CurveSkeleton& cs, const std::vector<std::vector<Vec3>>& poses,
                                                 const AnimationSkeletonOptions& o) {
  ODESKIN_TRY(checkInput(cs, poses, o));
  const std::size_t n_count = cs.nodeCount();
  const std::vector<std::vector<std::uint32_t>> adjacent = adjacencyOf(cs);
  std::vector<Bend> bends;
  std::vector<double> node_bend(n_count, 0.0);
  for (const Chain& chain : chainsOf(adjacent)) chainBends(chain, cs, poses, o, bends, node_bend);
  std::vector<std::uint32_t> bend_nodes;
  bend_nodes.reserve(bends.size());
  for (const Bend& b : bends) bend_nodes.push_back(b.node);

  const SkeletonTreeView view{cs.positions, cs.radii, adjacent};
  const TemplateMatch match = matchTemplate(view, bend_nodes, o.template_kind, o.up);
  const std::uint32_t root = match.kind != SkeletonTemplateKind::kNone ? match.root : defaultRoot(cs, adjacent, bends);

  // Which nodes are joints, why, and under what name.
  std::vector<std::int8_t> reason(n_count, -1);
  std::vector<std::string> name(n_count);
  std::vector<std::int8_t> moved(n_count, 0);
  std::vector<Vec3> position(cs.positions.begin(), cs.positions.end());
  auto mark = [&](std::uint32_t n, JointReason r) {
    if (reason[n] < 0 || static_cast<int>(r) < reason[n]) reason[n] = static_cast<std::int8_t>(r);
  };
  for (std::uint32_t n = 0; n < n_count; ++n) {
    if (adjacent[n].size() == 1 || (adjacent[n].empty() && n_count == 1)) mark(n, JointReason::kTip);
    if (adjacent[n].size() >= 3) mark(n, JointReason::kJunction);
  }
  for (const Bend& b : bends) mark(b.node, JointReason::kBend);
  // Seams: where a branch leaves a junction, unless it is the body going on.
  std::vector<std::int64_t> from(n_count, -2);
  std::vector<std::uint32_t> order{root};
  from[root] = -1;
  for (std::size_t head = 0; head < order.size(); ++head) {
    for (const std::uint32_t m : adjacent[order[head]]) {
      if (from[m] != -2) continue;
      from[m] = order[head];
      order.push_back(m);
    }
  }
  for (const std::uint32_t j : order) {
    if (adjacent[j].size() < 3) continue;
    std::vector<std::uint32_t> kids;
    for (const std::uint32_t m : adjacent[j]) {
      if (static_cast<std::int64_t>(m) != from[j]) kids.push_back(m);
    }
    std::sort(kids.begin(), kids.end(), [&](std::uint32_t a, std::uint32_t b) { return cs.radii[a] > cs.radii[b]; });
    // At the root nothing arrives: the body goes on where one branch is much the thickest (a
    // pelvis's spine between two legs).
    const double arriving = from[j] >= 0 ? cs.radii[static_cast<std::size_t>(from[j])]
                                         : (kids.size() > 1 ? kRootContinuation * cs.radii[kids[1]] / kContinuation : 0.0);
    for (const std::uint32_t c : kids) {
      const bool continues = c == kids.front() && arriving > 0.0 && cs.radii[c] >= kContinuation * arriving;
      if (!continues) mark(c, JointReason::kSeam);
    }
  }
  for (const TemplateJoint& t : match.joints) {
    mark(t.node, t.is_bend ? JointReason::kBend : JointReason::kTemplate);
    name[t.node] = t.name;
    if (t.moved) {
      moved[t.node] = 1;
      position[t.node] = t.position;
    }
  }
  reason[root] = static_cast<std::int8_t>(JointReason::kRoot);

  AnimationSkeleton out;
  out.used = match.kind;
  out.template_note = match.note;
  std::vector<std::int32_t> joint_of(n_count, -1);
  std::vector<std::int32_t> above(n_count, -1);  // nearest joint on the way to the root
  for (const std::uint32_t n : order) {
    const std::int32_t parent_joint = from[n] < 0 ? -1 : above[static_cast<std::size_t>(from[n])];
    above[n] = parent_joint;
    if (reason[n] < 0) continue;
    const auto r = static_cast<JointReason>(reason[n]);
    joint_of[n] = static_cast<std::int32_t>(out.joints.size());
    above[n] = joint_of[n];
    out.joints.push_back(position[n]);
    out.parents.push_back(parent_joint);
    out.reasons.push_back(r);
    out.nodes.push_back(moved[n] ? -1 : static_cast<std::int32_t>(n));
    out.bend_deg.push_back(node_bend[n]);
    out.names.push_back(!name[n].empty() ? name[n] : std::string(reasonName(r)) + "_" + std::to_string(out.joints.size() - 1));
  }
  return out;
}

Skeleton toSkeleton(const AnimationSkeleton& a) {
  Skeleton s;
  // Joint j > 0 ends bone j - 1; joints come parents first, so a bone's parent bone precedes it.
  for (std::size_t j = 1; j < a.jointCount(); ++j) {
    const std::int32_t head = a.parents[j];
    s.names.push_back(a.names[j]);
    s.heads.push_back(a.joints[static_cast<std::size_t>(head)]);
    s.tails.push_back(a.joints[j]);
    s.parents.push_back(head > 0 ? head - 1 : -1);
  }
  return s;
}

}  // namespace odeskin

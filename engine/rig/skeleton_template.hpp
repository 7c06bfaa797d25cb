// SPDX-License-Identifier: MIT
// Humanoid and quadruped templates for the animation skeleton (thesis 5.4, Fig. 5.4 and Eq. 5.1):
// the joints a limb needs even when it is straight in every example pose (an elbow, a knee), and
// which branch is which. The shared spec (MATH.md, PIPELINE.md) gives neither the figure's joint
// list nor its ratios, so the numbers below are ours, from the figure's description in issue 8
// and from anthropometry (segment lengths as fractions of the body height H, Drillis & Contini
// 1966 as tabulated by Winter, "Biomechanics and Motor Control of Human Movement", 4th ed., Fig.
// 4.1), for the humanoid:
//  - legs: the two branches whose tips reach lowest; hips at their seam rings, and (Eq. 5.1) the
//    pelvis, the root, at the mid-point of the two hips. Along hip -> toe tip (thigh 0.245 H,
//    shank 0.246 H, ankle height 0.039 H, about 0.1 H of foot beyond the ankle: 0.63 H) the knee
//    at 0.39 and the ankle at 0.78 of the arc length.
//  - head: the highest other tip; the spine is the path from the pelvis to it.
//  - arms: the two remaining tips whose branches leave the spine closest to the pelvis;
//    shoulders at their seam rings, the neck at the mid-point of the shoulders (Eq. 5.1). Along
//    shoulder -> hand tip (upper arm 0.186 H, forearm 0.146 H, hand 0.108 H) the elbow at 0.42
//    and the wrist at 0.75.
//  - the spine joint at 0.5 of pelvis -> neck; the head joint (skull base) at 0.3 of neck -> crown
//    (neck 0.052 H below a 0.130 H head).
// and for the quadruped (four-legged mammals: the cat and horse of the data):
//  - legs: the four branches whose tips reach lowest, paired into girdles by their distance along
//    the skeleton; the head is the thickest other branch beyond one girdle (the shoulders), the
//    tail the other branch beyond the other (the hips). Pelvis and chest at the mid-points of
//    their girdles' seam rings (Eq. 5.1); the pelvis is the root.
//  - each leg (seam -> paw tip) in thirds of upper leg, lower leg and foot: elbow or knee at 0.35,
//    wrist or hock at 0.7; the spine joint at 0.5 of pelvis -> chest; the neck joint at 0.5 of
//    chest -> nose tip; the tail in three at 1/3 and 2/3.
// A turn-test joint within 12% of a limb's length of a template position takes the template's
// name instead of adding a joint: where the mesh bends is better evidence than a ratio.
// Automatic choice: with four or more tips in the lowest 30% of the height (along `up`) a
// quadruped whose spine (pelvis -> chest) lies within 45 degrees of horizontal; else, with two or
// more, a humanoid whose spine (pelvis -> head) lies within 45 degrees of up; else no template (a
// tube, a hand, a character lying down).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "../core/types.hpp"

namespace odeskin {

enum class SkeletonTemplateKind : std::uint8_t { kNone, kAuto, kHumanoid, kQuadruped };

std::string_view templateKindName(SkeletonTemplateKind kind);  // "none", "auto", "humanoid", "quadruped"
std::optional<SkeletonTemplateKind> parseTemplateKind(std::string_view text);

// The curve skeleton as the templates read it: an undirected tree of nodes on the bind mesh.
struct SkeletonTreeView {
  std::span<const Vec3> positions;
  std::span<const double> radii;
  std::vector<std::vector<std::uint32_t>> adjacent;
};

struct TemplateJoint {
  std::uint32_t node = 0;      // the curve-skeleton node it sits on
  std::string name;            // "pelvis", "l_knee", ...
  bool is_bend = false;        // a turn-test joint renamed, not an added one
  bool moved = false;          // Eq. 5.1: placed at `position` (a mid-point), not at the node
  Vec3 position{0.0};
};

struct TemplateMatch {
  SkeletonTemplateKind kind = SkeletonTemplateKind::kNone;
  std::string note;              // what was matched, or why nothing was
  std::uint32_t root = 0;        // the node of the root joint (the pelvis)
  std::vector<TemplateJoint> joints;
  Vec3 spine{0.0};               // pelvis -> chest (quadruped) or head tip (humanoid)
};

// requested: kAuto, kHumanoid or kQuadruped (kNone returns an empty match); bend_nodes: the
// turn-test joints. A requested template the tree cannot hold (too few tips) gives kNone with the
// reason in `note`.
TemplateMatch matchTemplate(const SkeletonTreeView& tree, std::span<const std::uint32_t> bend_nodes,
                            SkeletonTemplateKind requested, const Vec3& up);

}  // namespace odeskin

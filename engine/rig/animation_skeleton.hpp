// SPDX-License-Identifier: MIT
// The animation skeleton read off a curve skeleton (thesis 5.4): joints where the limbs leave the
// body (the centre of each limb's seam ring), at the junctions and the free ends, and where the
// curve skeleton turns by more than a threshold angle (20 degrees by default); a humanoid or
// quadruped template adds the joints a straight limb does not show (skeleton_template.hpp).
//
// The turn at a node is the angle between the chords to the points one window of arc length
// before and after it (the window is a few times the local ring radius), not between the short
// segments of neighbouring rings, whose direction is noise at the scale of one ring spacing. With
// several example poses the node's turn is its largest over the poses, and the greediest choice
// keeps the larger turn where two poses put a joint at nearby nodes (Sec. 5.4): joints are taken
// in decreasing order of turn and none closer than one window to a joint already taken.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "../core/result.hpp"
#include "curve_skeleton.hpp"
#include "rig.hpp"
#include "skeleton_template.hpp"

namespace odeskin {

enum class JointReason : std::uint8_t {
  kRoot,      // the root joint (a template's pelvis, or the central junction)
  kJunction,  // where branches of the curve skeleton meet
  kSeam,      // the centre of the ring where a limb leaves the body
  kBend,      // the curve skeleton turns by more than the threshold here (in some pose)
  kTemplate,  // a template joint the turn test did not find (at its arc-length ratio)
  kTip,       // the free end of a branch
};

// The reason's lower-case name ("bend", "tip", ...): joint names and the rig command's summary.
const char* reasonName(JointReason reason);

struct AnimationSkeleton {
  std::vector<Vec3> joints;             // J, on the bind mesh
  std::vector<std::int32_t> parents;    // J: the parent joint (-1 for the root, joint 0)
  std::vector<std::string> names;       // J: template names ("l_knee") or "<reason>_<index>"
  std::vector<JointReason> reasons;     // J
  std::vector<std::int32_t> nodes;      // J: the curve-skeleton node it sits on (-1: a template mid-point)
  std::vector<double> bend_deg;         // J: the largest turn over the poses at the joint (0 if not measured)
  SkeletonTemplateKind used = SkeletonTemplateKind::kNone;
  std::string template_note;            // why a template was chosen or not

  std::size_t jointCount() const { return joints.size(); }
  std::size_t boneCount() const { return joints.empty() ? 0 : joints.size() - 1; }
};

struct AnimationSkeletonOptions {
  double angle_threshold_deg = 20.0;  // the thesis's default
  double window_radii = 1.0;          // the turn's chords span this many ring radii (at least 3 rings)
  SkeletonTemplateKind template_kind = SkeletonTemplateKind::kAuto;
  Vec3 up{0.0, 1.0, 0.0};             // the mesh's up axis: legs are the limbs that reach lowest
};

// poses: the curve skeleton's node positions on each example pose (curveSkeletonPositions), the
// bind mesh's first; one pose is the bind mesh alone. kInvalidArgument for no nodes, poses of the
// wrong size, an angle outside (0, 180), window_radii <= 0 or a zero up axis.
Result<AnimationSkeleton> buildAnimationSkeleton(const CurveSkeleton& cs, const std::vector<std::vector<Vec3>>& poses,
                                                 const AnimationSkeletonOptions& o = {});

// One bone per non-root joint, from its parent joint (the head, its pivot) to it (the tail); the
// bone's parent is the bone ending at its head (-1 when the head is the root joint), as libigl's
// directed_edge_parents reads a .tgf. Bone names are the joints' names.
Skeleton toSkeleton(const AnimationSkeleton& a);

}  // namespace odeskin

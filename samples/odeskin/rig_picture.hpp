// SPDX-License-Identifier: MIT
// `odeskin rig --png`: the rig drawn over its mesh in two panels, one camera: the surface with the
// iso-parametric curves coloured by body part, and an x-ray of the same curves (thin, one colour)
// with the curve skeleton (the centroid chains) and the animation skeleton's bones and joints,
// which the surface would hide (and a ground-truth skeleton when given, for comparison).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "engine/core/iso_curve.hpp"
#include "engine/core/result.hpp"
#include "engine/rig/animation_skeleton.hpp"
#include "engine/rig/curve_skeleton.hpp"
#include "engine/rig/rig.hpp"

namespace odeskin {

struct RigPictureOptions {
  std::string size = "1440x540";  // whole picture
  double azimuth_deg = 30.0;
  double elevation_deg = 15.0;
  Vec3 up{0.0, 1.0, 0.0};
  std::string device = "auto";
  std::string title;  // the first label line (the mesh's file name)
  const Skeleton* truth = nullptr;  // optional: a ground-truth skeleton drawn in purple
};

// Errors: a malformed size, no Vulkan device (kUnavailable with a hint), the renderer's, kIoError
// naming the path.
Status drawRigPicture(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                      std::span<const IsoCurve> curves, const CurveSkeleton& cs, const AnimationSkeleton& skeleton,
                      const RigPictureOptions& o);

}  // namespace odeskin

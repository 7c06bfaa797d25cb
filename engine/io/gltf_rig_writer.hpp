// SPDX-License-Identifier: MIT
// A rigged mesh at its bind pose as one glTF 2.0 binary (`odeskin rig --gltf`): the mesh with its
// skin (JOINTS_0 / WEIGHTS_0, at most 4 influences per vertex, the largest kept and renormalised
// in float32), one joint node per bone at the bone's head (its pivot), children of their parent
// bone's node, and one extra leaf node per end bone at its tail ("<name>_end", not a skin joint)
// so viewers can draw the last bones. No animation: the rig, ready for an engine to pose.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "../rig/rig.hpp"

namespace odeskin {

// positions and faces: the bind mesh (polygons fanned into triangles); rig: skeleton and
// influences over it. Written through a temporary and rename. kInvalidArgument for sizes, invalid
// influences or skeleton, non-finite values, positions beyond glTF's float32 range
// (gltf::checkFloat32Positions), more than 65536 bones; kIoError naming the path.
Status writeRigGlb(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces, const Rig& rig,
                   const std::string& generator = "odeskin rig");

}  // namespace odeskin

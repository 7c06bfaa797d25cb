// SPDX-License-Identifier: MIT
// A rigged mesh at its bind pose as one glTF 2.0 binary (`odeskin rig --gltf`): the mesh with its
// skin (JOINTS_0 / WEIGHTS_0, at most 4 influences per vertex, the largest kept and renormalised
// in float32), one joint node per bone at the bone's head (its pivot), children of their parent
// bone's node, and one extra leaf node per end bone at its tail ("<name>_end", not a skin joint)
// so viewers can draw the last bones. Several root bones hang under one "skeleton" node (the
// skin's common root). No animation: the rig, ready for an engine to pose.
//
// A mesh read from a glTF keeps its look: its render vertices (split at UV and normal seams) with
// their NORMAL and TEXCOORD_0, its primitives, and the materials, textures and images they used.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "../rig/rig.hpp"
#include "gltf_materials.hpp"

namespace odeskin {

// How the written mesh looks. Without a layout: one glTF vertex per position, one primitive, no
// normals, texture coordinates or material.
struct RigGlbLook {
  const RenderLayout* render = nullptr;              // the input's render vertices over the positions
  const gltf::MaterialLibrary* materials = nullptr;  // the materials the layout's primitives name
};

// positions and faces: the bind mesh (polygons fanned into triangles); rig: skeleton and
// influences over it. A render vertex takes its topology vertex's position and weights. Written
// through a temporary and rename. kInvalidArgument naming the path for sizes, invalid influences,
// skeleton or render layout (checkRenderLayout), non-finite values, positions beyond glTF's
// float32 range (gltf::checkFloat32Positions), more than 65536 bones, a primitive's material the
// library lacks; kIoError naming the path.
Status writeRigGlb(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces, const Rig& rig,
                   const RigGlbLook& look = {}, const std::string& generator = "odeskin rig");

}  // namespace odeskin

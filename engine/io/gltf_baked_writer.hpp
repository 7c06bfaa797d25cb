// SPDX-License-Identifier: MIT
// A played animation baked into one GLB any glTF viewer plays: the first frame is the mesh, every
// later frame is a morph target (its displacement from the first), and a "weights" animation
// switches one target on per frame at its time: STEP shows the frames as they are, LINEAR
// cross-fades consecutive frames (key f weights target f-1 by 1, so between keys the mesh moves
// linearly from frame to frame). Meant for looking at results; the compact export with skin and
// per-mode targets is `odeskin export`'s job.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "../core/status.hpp"
#include "../core/types.hpp"
#include "gltf_materials.hpp"
#include "gltf_quantized.hpp"

namespace tinygltf {
class Model;
}

namespace odeskin {

struct BakedGlbOptions {
  bool linear = false;                   // LINEAR cross-fades instead of STEP
  std::string generator = "odeskin play";  // asset.generator
  std::string animation = "odeskin play";  // the animation's name
  // The materials to dress the primitives with (gltf_materials.hpp), or none.
  const gltf::MaterialLibrary* materials = nullptr;
  // KHR_mesh_quantization (gltf_quantized.hpp) on a grid over the first frame, which the mesh node's
  // translation and scale undo.
  bool quantize = false;
};

// What a baked file may carry besides the positions.
struct BakedVertexData {
  // Empty, or one unit normal per vertex of every frame, written as the mesh's NORMAL and each
  // target's NORMAL delta (without them a viewer shades the mesh flat, as glTF requires).
  std::span<const std::vector<Vec3>> normals;
  std::span<const Vec2> uvs;                    // empty, or TEXCOORD_0 per vertex
  // Empty (one primitive), or the input's primitives as runs of the faces, each written as its own
  // glTF primitive over the shared vertices (those without faces are left out).
  std::span<const RenderPrimitive> primitives;
};

// frames: F >= 1 vertex arrays of one mesh; seconds: F increasing times (seconds[0] >= 0).
// Polygons are triangulated as fans. Written through a temporary file and rename. Errors:
// kInvalidArgument naming the path (sizes, indices, non-finite values, positions beyond glTF's
// float32 range: gltf::checkFloat32Positions, times not increasing), kIoError naming the path.
// `quantization`, when given, receives what options.quantize cost, measured at every frame (where
// its one target has weight 1; the LINEAR cross-fades stay within the frames' errors).
Status writeBakedGlb(const std::filesystem::path& path, const FaceList& faces,
                     const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds,
                     const BakedGlbOptions& options = {}, const BakedVertexData& data = {},
                     QuantizationCost* quantization = nullptr);

// kInvalidArgument "baking F frames of V vertices needs 2 GiB or more" when a baked GLB of `frames`
// x `vertices` (a float32 position and normal each) would reach 2 GiB: tinygltf reads no larger
// buffer, and the frames are held in memory (in double) before the file is written. Callers check
// before playing any frame and add how to lower the count.
Status checkBakedSize(std::size_t frames, std::size_t vertices);
// The same for a frame count computed in double (which may exceed std::size_t, or be infinite), so
// a caller can check before it stores a single frame time; "baking more than 1.79769e+308 frames" when
// the count is infinite.
Status checkBakedSize(double frames, std::size_t vertices);

// Writes `model` as one binary glTF through "<path>.partial" and a rename, so a failure never leaves
// a half-written file at `path` (the partial file is removed). kIoError naming the path.
Status writeGlbAtomically(const std::filesystem::path& path, const tinygltf::Model& model);

}  // namespace odeskin

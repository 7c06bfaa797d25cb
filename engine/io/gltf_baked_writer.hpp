// SPDX-License-Identifier: MIT
// A played animation baked into one GLB any glTF viewer plays: the first frame is the mesh, every
// later frame is a morph target (its displacement from the first), and a STEP "weights" animation
// switches one target on per frame at its time. Meant for looking at results; the compact export
// with skin and per-mode targets is `odeskin export`'s job.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

// frames: F >= 1 vertex arrays of one mesh; seconds: F increasing times (seconds[0] >= 0).
// Polygons are triangulated as fans. Written through a temporary file and rename. Errors:
// kInvalidArgument (sizes, indices, non-finite values, times not increasing), kIoError naming the path.
Status writeBakedGlb(const std::filesystem::path& path, const FaceList& faces,
                     const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds);

}  // namespace odeskin

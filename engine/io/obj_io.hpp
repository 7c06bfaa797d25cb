// SPDX-License-Identifier: MIT
// Wavefront OBJ writing (reading comes with the pipeline issue). Writes go to a temporary file in
// the destination folder that is renamed into place, so a failure never leaves a half-written file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "../core/status.hpp"
#include "../core/types.hpp"

namespace odeskin {

// `uvs`: empty, or one texture coordinate per vertex, written as `vt` lines with faces `f i/i ...`
// (a glTF input's TEXCOORD_0, whose v runs down the image: OBJ's runs up, so v is written 1 - v).
// `position_of_uv` (RenderLayout::topology_of_render of an OBJ input's layout): empty, or the
// position of each texture coordinate; `faces` then index `uvs` and corner r is written
// `f p/r` with p = position_of_uv[r], so the `v` lines keep the positions' order.
// kInvalidArgument for an index out of range, a non-finite coordinate or a uvs count that is not
// the vertex count (or position_of_uv's); kIoError naming the path when the file cannot be written.
Status writeObj(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces,
                const std::string& comment = {}, std::span<const Vec2> uvs = {},
                std::span<const std::uint32_t> position_of_uv = {});

// Writes `content` to `path` through a temporary file and rename (kIoError naming the path). A
// symbolic link is followed: the link stays and its target is replaced, keeping its permission
// bits (a new file gets the umask's). An existing target that
// is not a regular file (/dev/null, a FIFO, /dev/stdout) is written in place, and a directory is
// refused. The data are synced to disk before the rename and the directory after it, so a power
// cut leaves the old file or the new one, not an empty one.
Status writeFileAtomically(const std::filesystem::path& path, const std::string& content);

}  // namespace odeskin

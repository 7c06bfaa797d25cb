// SPDX-License-Identifier: MIT
// A tessellated network as one glTF 2.0 binary any viewer opens: one mesh node with float POSITION
// (with min/max), unit NORMAL and uint32 triangle indices, two triangles per quad; no material (the
// viewer's default). Written through a temporary file and a rename, so a failure leaves nothing.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "../core/status.hpp"
#include "tessellation.hpp"

namespace odeskin {

// normals: one per vertex (vertexNormals). up: the network's up axis, a unit +-x, +-y or +-z; glTF
// is +y up, so any other gets the node a rotation taking it there (the accessors keep the network's
// coordinates). kInvalidArgument for a size mismatch, a coordinate that is not finite, or positions
// beyond glTF's float32 range (gltf::checkFloat32Positions); kIoError naming `path` when it cannot be
// written.
Status writeSurfaceGlb(const std::filesystem::path& path, const SurfaceMesh& mesh, std::span<const Vec3> normals,
                       const Vec3& up = Vec3(0.0, 1.0, 0.0), const std::string& generator = "odeskin surface");

}  // namespace odeskin

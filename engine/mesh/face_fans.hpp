// SPDX-License-Identifier: MIT
// Topology checks and boundary loops straight from polygon faces, without building OpenMesh's
// half-edge mesh (which costs more than everything else the iso-curve builder does with a mesh
// that is plainly manifold).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "../core/types.hpp"

namespace odeskin {

// True when every face has >= 3 corners, no repeated vertex and indices < vertex_count, no directed
// edge belongs to two faces, and the faces around every vertex form one fan (a disk inside the
// mesh, a half-disk on its boundary). buildPolyMesh accepts every such mesh, face after face: a
// corner's vertex never has a closed fan yet (complex vertex), a face edge is never already taken
// (complex edge), and where a face joins two partial fans another gap exists to move a third to
// (re-linking). false says nothing more: buildPolyMesh then gives the verdict and its message.
bool isSimpleManifold(const FaceList& faces, std::size_t vertex_count);

// The boundary loops boundaryLoops(buildPolyMesh(..)) returns, for faces isSimpleManifold accepts:
// in the order OpenMesh numbers their half-edges (a loop's first edge, by the position of its one
// face corner in `faces`), each from that half-edge's start, running against the faces' order.
// Empty for faces isSimpleManifold rejects.
std::vector<std::vector<std::uint32_t>> boundaryLoopsOfFaces(const FaceList& faces, std::size_t vertex_count);

// Both at once: nullopt where isSimpleManifold is false, else the boundary loops.
std::optional<std::vector<std::vector<std::uint32_t>>> simpleManifoldBoundaryLoops(const FaceList& faces,
                                                                                    std::size_t vertex_count);

}  // namespace odeskin

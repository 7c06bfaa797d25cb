// SPDX-License-Identifier: MIT
// Half-edge topology (OpenMesh) of a polygon mesh, for boundary loops, edge walks and plane cuts.
// OpenMesh silently drops faces it cannot add (non-manifold "complex edge/vertex"); buildPolyMesh
// counts them and fails instead, naming the first such face.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin {

struct PolyMeshTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<PolyMeshTraits>;

// Vertex i of the result is positions[i]; face f is faces' face f. `source` names the input in
// errors ("cat-00.obj"). Errors: kInvalidArgument for an index out of range, a face with fewer
// than 3 vertices or a repeated vertex, and a face OpenMesh cannot add (non-manifold).
Result<PolyMesh> buildPolyMesh(std::span<const Vec3> positions, const FaceList& faces, const std::string& source);

// Boundary loops as vertex indices in half-edge order (empty for a closed mesh).
std::vector<std::vector<std::uint32_t>> boundaryLoops(const PolyMesh& mesh);

}  // namespace odeskin

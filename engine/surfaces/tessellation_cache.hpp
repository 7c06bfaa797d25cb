// SPDX-License-Identifier: MIT
// Interactive editing of a patch network (issue 7, point 4): a Network with its tessellation kept
// in pieces - one cardinal table g_k(u_i) per set of cardinal functions, the samples of every
// boundary's S, S_u, S_uu along the grid's v, and the welded mesh. An edit marks only the patches
// whose surface it changes (a shape: that patch or that row; a boundary tangent: the two rows that
// share the boundary; a curve: the rows reading it) and update() recomputes just those pieces and
// the mesh vertices those patches own. The result is bitwise the mesh tessellateNetwork() builds
// from scratch for the edited network.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../core/result.hpp"
#include "network.hpp"
#include "tessellation.hpp"

namespace odeskin {

class NetworkTessellation {
 public:
  // Tessellates everything once. Errors of tessellationGrid.
  static Result<NetworkTessellation> create(Network network, TessellationResolution resolution);

  const Network& network() const { return network_; }
  const SurfaceMesh& mesh() const& { return mesh_; }
  SurfaceMesh mesh() && { return std::move(mesh_); }

  // Edits, as Network's (nothing changes on error); they mark patches dirty without recomputing.
  Status setRowShape(std::uint32_t row, const Ode6Shape& shape);
  Status setPatchShape(std::uint32_t row, std::uint32_t column, const Ode6Shape& shape);
  Status setBoundary(std::uint32_t boundary, const NetworkBoundary& data);
  Status setCurvePoints(std::uint32_t curve, std::span<const Vec3> points);

  std::uint32_t dirtyPatchCount() const;
  // Re-evaluates the dirty patches (in parallel) and returns how many there were.
  std::uint32_t update();

 private:
  NetworkTessellation(Network network, TessellationGrid grid);
  // Marks `patches`, and any patch whose cardinal functions were recomputed from another shape.
  void markDirty(const std::vector<std::uint32_t>& patches, const std::vector<Ode6Shape>& old_representatives);
  std::vector<Ode6Shape> representatives() const;
  void markBoundaryRows(const std::vector<std::uint32_t>& patches);
  void tessellatePatch(std::uint32_t patch);

  Network network_;
  TessellationGrid grid_;
  SurfaceMesh mesh_;
  std::vector<std::vector<double>> tables_;                 // per cardinal: u_samples x 6, g_k(u_i)
  std::vector<std::vector<BoundarySample>> samples_;        // per boundary: grid columns
  std::vector<std::uint8_t> dirty_patches_;                 // rows x columns
  std::vector<std::uint8_t> dirty_boundaries_;              // per boundary
  std::vector<std::uint32_t> table_of_patch_;               // cardinal index when tables_ were built
};

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// A patch network as ONE welded mesh (thesis sec. 4.4-4.6): every patch is sampled on a regular
// u_samples x v_samples grid of its own (u, v) in [0, 1]^2, and neighbouring patches share the
// samples on their common edge, so the whole network is a single vertex grid of
//   grid_rows    = rows    (u_samples - 1) + (closed in u ? 0 : 1)
//   grid_columns = columns (v_samples - 1) + (closed in v ? 0 : 1)
// vertices, quads between neighbours (wrapping where closed). The mesh is watertight where patches
// meet: one vertex per seam sample, each interior edge shared by exactly two quads.
//
// A seam vertex is computed by one patch, its owner: grid row gi belongs to patch row
// min(gi / (u_samples - 1), rows - 1) at local u = (gi - row (u_samples - 1)) / (u_samples - 1), and
// columns likewise; so a seam belongs to the patch that starts there (the last boundary of an open
// network to the last patch). Both patches give the same values there up to rounding (C0), except
// for v-pairings the network builder tolerated under ContinuityPolicy::kWarn.
//
// This double-precision tessellation is the CPU reference that shaders/ode6_tessellate.comp mirrors.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../core/result.hpp"
#include "../core/types.hpp"
#include "network.hpp"

namespace odeskin {

struct TessellationResolution {
  std::uint32_t u_samples = 33;  // per patch along u, both edges included, >= 2
  std::uint32_t v_samples = 33;  // per patch along v, >= 2
};

// Largest welded grid accepted (67M vertices, 1.5 GiB of double positions).
inline constexpr std::uint64_t kMaxTessellationVertices = std::uint64_t{1} << 26;

// Index arithmetic of the welded grid.
struct TessellationGrid {
  std::uint32_t rows = 0;
  std::uint32_t columns = 0;
  std::uint32_t u_samples = 2;
  std::uint32_t v_samples = 2;
  bool closed_u = false;
  bool closed_v = false;

  std::uint32_t gridRows() const { return rows * (u_samples - 1) + (closed_u ? 0 : 1); }
  std::uint32_t gridColumns() const { return columns * (v_samples - 1) + (closed_v ? 0 : 1); }
  std::uint64_t vertexCount() const { return std::uint64_t{gridRows()} * gridColumns(); }
  // (owning patch row, local u sample) of grid row gi, and likewise for columns.
  std::pair<std::uint32_t, std::uint32_t> rowOwner(std::uint32_t gi) const;
  std::pair<std::uint32_t, std::uint32_t> columnOwner(std::uint32_t gj) const;
  // Grid rows [first, end) owned by patch row i; likewise columns.
  std::pair<std::uint32_t, std::uint32_t> ownedRows(std::uint32_t row) const;
  std::pair<std::uint32_t, std::uint32_t> ownedColumns(std::uint32_t column) const;
  // The global v of grid column gj (patch column + local v).
  double globalV(std::uint32_t gj) const;
  double localU(std::uint32_t sample) const { return static_cast<double>(sample) / (u_samples - 1); }
};

// kInvalidArgument for fewer than 2 samples; kOutOfRange beyond kMaxTessellationVertices.
Result<TessellationGrid> tessellationGrid(const Network& network, TessellationResolution resolution);

struct SurfaceMesh {
  TessellationGrid grid;
  std::vector<Vec3> positions;  // grid_rows x grid_columns, row-major: vertex gi * grid_columns + gj
  FaceList faces;               // quads (gi, gj), (gi + 1, gj), (gi + 1, gj + 1), (gi, gj + 1): S_u x S_v outward
};

// S, S_u, S_uu of boundary b at every grid column (the last column of an open network reads the
// curves' pieces inside the last patch: NetworkCurve's left limits).
std::vector<BoundarySample> sampleBoundary(const Network& network, std::uint32_t b, const TessellationGrid& grid);

// The quads of a grid (wrapping where closed).
FaceList gridFaces(const TessellationGrid& grid);

// Every patch of `network` at `resolution` into one welded mesh (tessellation_cache.hpp keeps the
// pieces for edits). Errors of tessellationGrid.
Result<SurfaceMesh> tessellateNetwork(const Network& network, TessellationResolution resolution);

// Unit vertex normals: area-weighted quad normals (smooth across seams since they are welded).
std::vector<Vec3> vertexNormals(const SurfaceMesh& mesh);

// Edges used by only one face, as (smaller index, larger index) pairs: empty for a network closed
// in u and v; otherwise exactly the grid's outer rim. Edges used by more than two faces count too.
std::vector<std::pair<std::uint32_t, std::uint32_t>> unsharedEdges(const FaceList& faces);

}  // namespace odeskin

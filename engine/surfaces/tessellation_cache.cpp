// SPDX-License-Identifier: MIT
#include "tessellation_cache.hpp"
#include "../core/parallel.hpp"

#include <algorithm>


namespace odeskin {
namespace {

std::vector<double> cardinalTable(const Ode6Cardinal& g, const TessellationGrid& grid) {
  std::vector<double> table(std::size_t{grid.u_samples} * 6);
  for (std::uint32_t i = 0; i < grid.u_samples; ++i) {
    const Ode6Values v = g.evaluate(grid.localU(i));
    std::copy(v.begin(), v.end(), table.begin() + std::ptrdiff_t{6} * i);
  }
  return table;
}

bool sameShape(const Ode6Shape& a, const Ode6Shape& b) {
  return a.rho == b.rho && a.eta == b.eta && a.lambda == b.lambda;
}

}  // namespace

NetworkTessellation::NetworkTessellation(Network network, TessellationGrid grid)
    : network_(std::move(network)), grid_(grid) {}

Result<NetworkTessellation> NetworkTessellation::create(Network network, TessellationResolution resolution) {
  ODESKIN_ASSIGN_OR_RETURN(const TessellationGrid grid, tessellationGrid(network, resolution));
  NetworkTessellation t(std::move(network), grid);
  t.mesh_.grid = grid;
  t.mesh_.positions.assign(grid.vertexCount(), Vec3(0.0));
  t.mesh_.faces = gridFaces(grid);
  const std::size_t boundaries = t.network_.description().boundaries.size();
  t.samples_.resize(boundaries);
  t.dirty_boundaries_.assign(boundaries, 1);
  t.dirty_patches_.assign(t.network_.patchCount(), 1);
  t.table_of_patch_.assign(t.network_.patchCount(), 0);
  t.update();
  return t;
}

std::vector<Ode6Shape> NetworkTessellation::representatives() const {
  std::vector<Ode6Shape> shapes(network_.patchCount());
  for (std::uint32_t p = 0; p < shapes.size(); ++p) {
    shapes[p] = network_.cardinal(p / network_.columns(), p % network_.columns()).shape();
  }
  return shapes;
}

void NetworkTessellation::markDirty(const std::vector<std::uint32_t>& patches,
                                    const std::vector<Ode6Shape>& old_representatives) {
  for (std::uint32_t p : patches) dirty_patches_[p] = 1;
  // A row's shared cardinal functions come from one of its patches; if that one changed, every
  // patch using them is re-evaluated, so the mesh stays bitwise equal to a rebuild.
  const std::vector<Ode6Shape> now = representatives();
  for (std::size_t p = 0; p < now.size(); ++p) {
    if (!sameShape(now[p], old_representatives[p])) dirty_patches_[p] = 1;
  }
}

Status NetworkTessellation::setRowShape(std::uint32_t row, const Ode6Shape& shape) {
  const std::vector<Ode6Shape> old = representatives();
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> patches, network_.setRowShape(row, shape));
  markDirty(patches, old);
  return okStatus();
}

Status NetworkTessellation::setPatchShape(std::uint32_t row, std::uint32_t column, const Ode6Shape& shape) {
  const std::vector<Ode6Shape> old = representatives();
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> patches, network_.setPatchShape(row, column, shape));
  markDirty(patches, old);
  return okStatus();
}

Status NetworkTessellation::setBoundary(std::uint32_t boundary, const NetworkBoundary& data) {
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> patches, network_.setBoundary(boundary, data));
  for (std::uint32_t p : patches) dirty_patches_[p] = 1;
  dirty_boundaries_[boundary] = 1;
  return okStatus();
}

Status NetworkTessellation::setCurvePoints(std::uint32_t curve, std::span<const Vec3> points) {
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> patches, network_.setCurvePoints(curve, points));
  for (std::uint32_t p : patches) dirty_patches_[p] = 1;
  const NetworkDescription& d = network_.description();
  for (std::uint32_t b = 0; b < d.boundaries.size(); ++b) {
    bool uses = d.boundaries[b].position == curve;
    for (const CurveTerm& t : network_.firstTerms(b)) uses = uses || t.curve == curve;
    for (const CurveTerm& t : network_.secondTerms(b)) uses = uses || t.curve == curve;
    if (uses) dirty_boundaries_[b] = 1;
  }
  return okStatus();
}

std::uint32_t NetworkTessellation::dirtyPatchCount() const {
  return static_cast<std::uint32_t>(std::count(dirty_patches_.begin(), dirty_patches_.end(), 1));
}

std::uint32_t NetworkTessellation::update() {
  std::vector<std::uint32_t> dirty;
  for (std::uint32_t p = 0; p < dirty_patches_.size(); ++p) {
    if (dirty_patches_[p]) dirty.push_back(p);
  }
  if (dirty.empty()) return 0;
  for (std::uint32_t b = 0; b < dirty_boundaries_.size(); ++b) {
    if (dirty_boundaries_[b]) samples_[b] = sampleBoundary(network_, b, grid_);
  }
  // Tables: clean patches keep theirs (same cardinal functions, bitwise); the others are computed.
  std::vector<std::vector<double>> tables(network_.cardinalCount());
  std::vector<std::uint32_t> now(network_.patchCount());
  for (std::uint32_t p = 0; p < now.size(); ++p) {
    now[p] = network_.cardinalIndex(p / network_.columns(), p % network_.columns());
    if (!dirty_patches_[p] && tables[now[p]].empty()) tables[now[p]] = tables_[table_of_patch_[p]];
  }
  for (std::uint32_t k = 0; k < tables.size(); ++k) {
    if (tables[k].empty()) tables[k] = cardinalTable(network_.cardinalAt(k), grid_);
  }
  tables_ = std::move(tables);
  table_of_patch_ = std::move(now);
  parallelFor(std::size_t{0}, dirty.size(), [&](std::size_t i) { tessellatePatch(dirty[i]); });
  std::fill(dirty_patches_.begin(), dirty_patches_.end(), 0);
  std::fill(dirty_boundaries_.begin(), dirty_boundaries_.end(), 0);
  return static_cast<std::uint32_t>(dirty.size());
}

void NetworkTessellation::tessellatePatch(std::uint32_t patch) {
  const std::uint32_t row = patch / network_.columns();
  const std::uint32_t column = patch % network_.columns();
  const std::vector<double>& g = tables_[table_of_patch_[patch]];
  const std::vector<BoundarySample>& lower = samples_[network_.lowerBoundary(row)];
  const std::vector<BoundarySample>& upper = samples_[network_.upperBoundary(row)];
  const auto [row_begin, row_end] = grid_.ownedRows(row);
  const auto [column_begin, column_end] = grid_.ownedColumns(column);
  const std::uint32_t width = grid_.gridColumns();
  for (std::uint32_t gi = row_begin; gi < row_end; ++gi) {
    const double* w = &g[std::size_t{6} * (gi - row_begin)];
    for (std::uint32_t gj = column_begin; gj < column_end; ++gj) {
      const BoundarySample& a = lower[gj];
      const BoundarySample& b = upper[gj];
      // S = g1 c1 + g2 c2 + g3 c3 + g4 c4 + g5 c5 + g6 c6, in this order (the shader's too).
      mesh_.positions[std::size_t{gi} * width + gj] =
          w[0] * a.position + w[1] * a.first + w[2] * a.second + w[3] * b.position + w[4] * b.first + w[5] * b.second;
    }
  }
}

}  // namespace odeskin

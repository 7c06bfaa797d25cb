// SPDX-License-Identifier: MIT
#include "tessellation.hpp"

#include <algorithm>
#include <unordered_map>

#include "tessellation_cache.hpp"

namespace odeskin {

std::pair<std::uint32_t, std::uint32_t> TessellationGrid::rowOwner(std::uint32_t gi) const {
  const std::uint32_t row = std::min(gi / (u_samples - 1), rows - 1);
  return {row, gi - row * (u_samples - 1)};
}

std::pair<std::uint32_t, std::uint32_t> TessellationGrid::columnOwner(std::uint32_t gj) const {
  const std::uint32_t column = std::min(gj / (v_samples - 1), columns - 1);
  return {column, gj - column * (v_samples - 1)};
}

std::pair<std::uint32_t, std::uint32_t> TessellationGrid::ownedRows(std::uint32_t row) const {
  const std::uint32_t first = row * (u_samples - 1);
  return {first, first + (u_samples - 1) + (row + 1 == rows && !closed_u ? 1 : 0)};
}

std::pair<std::uint32_t, std::uint32_t> TessellationGrid::ownedColumns(std::uint32_t column) const {
  const std::uint32_t first = column * (v_samples - 1);
  return {first, first + (v_samples - 1) + (column + 1 == columns && !closed_v ? 1 : 0)};
}

double TessellationGrid::globalV(std::uint32_t gj) const {
  const auto [column, sample] = columnOwner(gj);
  return column + static_cast<double>(sample) / (v_samples - 1);
}

Result<TessellationGrid> tessellationGrid(const Network& network, TessellationResolution resolution) {
  if (resolution.u_samples < 2 || resolution.v_samples < 2) {
    return invalidArgument("tessellation: at least 2 samples per patch along u and v, got " +
                           std::to_string(resolution.u_samples) + " x " + std::to_string(resolution.v_samples));
  }
  TessellationGrid grid;
  grid.rows = network.rows();
  grid.columns = network.columns();
  grid.u_samples = resolution.u_samples;
  grid.v_samples = resolution.v_samples;
  grid.closed_u = network.closedU();
  grid.closed_v = network.closedV();
  // 64-bit arithmetic: the counts themselves may overflow 32 bits before the check.
  const std::uint64_t rows = std::uint64_t{grid.rows} * (grid.u_samples - 1) + (grid.closed_u ? 0 : 1);
  const std::uint64_t columns = std::uint64_t{grid.columns} * (grid.v_samples - 1) + (grid.closed_v ? 0 : 1);
  if (rows * columns > kMaxTessellationVertices || rows > UINT32_MAX || columns > UINT32_MAX) {
    return outOfRange("tessellation: " + std::to_string(rows) + " x " + std::to_string(columns) +
                      " vertices exceed the limit of " + std::to_string(kMaxTessellationVertices));
  }
  return grid;
}

std::vector<BoundarySample> sampleBoundary(const Network& network, std::uint32_t b, const TessellationGrid& grid) {
  std::vector<BoundarySample> samples(grid.gridColumns());
  for (std::uint32_t j = 0; j < samples.size(); ++j) {
    samples[j] = network.boundarySample(b, grid.globalV(j), 0, grid.columnOwner(j).second + 1 == grid.v_samples);
  }
  return samples;
}

FaceList gridFaces(const TessellationGrid& grid) {
  const std::uint32_t rows = grid.gridRows();
  const std::uint32_t columns = grid.gridColumns();
  const std::uint32_t quad_rows = grid.closed_u ? rows : rows - 1;
  const std::uint32_t quad_columns = grid.closed_v ? columns : columns - 1;
  FaceList faces;
  faces.face_offsets.reserve(std::size_t{quad_rows} * quad_columns + 1);
  faces.indices.reserve(std::size_t{quad_rows} * quad_columns * 4);
  for (std::uint32_t i = 0; i < quad_rows; ++i) {
    const std::uint32_t i1 = (i + 1) % rows;
    for (std::uint32_t j = 0; j < quad_columns; ++j) {
      const std::uint32_t j1 = (j + 1) % columns;
      faces.indices.insert(faces.indices.end(), {i * columns + j, i1 * columns + j, i1 * columns + j1, i * columns + j1});
      faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
    }
  }
  return faces;
}

Result<SurfaceMesh> tessellateNetwork(const Network& network, TessellationResolution resolution) {
  ODESKIN_ASSIGN_OR_RETURN(NetworkTessellation t, NetworkTessellation::create(network, resolution));
  return std::move(t).mesh();
}

std::vector<Vec3> vertexNormals(const SurfaceMesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3(0.0));
  const FaceList& f = mesh.faces;
  for (std::size_t face = 0; face < f.faceCount(); ++face) {
    const std::uint32_t* q = &f.indices[f.face_offsets[face]];
    const std::size_t count = f.face_offsets[face + 1] - f.face_offsets[face];
    Vec3 n(0.0);
    // Twice the (vector) area of the polygon, Newell's method: right for quads that are not planar.
    for (std::size_t k = 0; k < count; ++k) n += glm::cross(mesh.positions[q[k]], mesh.positions[q[(k + 1) % count]]);
    for (std::size_t k = 0; k < count; ++k) normals[q[k]] += n;
  }
  for (Vec3& n : normals) {
    const double length = glm::length(n);
    n = length > 0.0 ? n / length : Vec3(0.0, 0.0, 1.0);
  }
  return normals;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> unsharedEdges(const FaceList& faces) {
  std::unordered_map<std::uint64_t, std::uint32_t> uses;
  for (std::size_t face = 0; face < faces.faceCount(); ++face) {
    const std::uint32_t begin = faces.face_offsets[face];
    const std::uint32_t count = faces.face_offsets[face + 1] - begin;
    for (std::uint32_t k = 0; k < count; ++k) {
      std::uint32_t a = faces.indices[begin + k];
      std::uint32_t b = faces.indices[begin + (k + 1) % count];
      if (a > b) std::swap(a, b);
      ++uses[(std::uint64_t{a} << 32) | b];
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const auto& [key, count] : uses) {
    if (count != 2) edges.emplace_back(static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace odeskin

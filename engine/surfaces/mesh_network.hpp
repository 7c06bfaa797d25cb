// SPDX-License-Identifier: MIT
// A curve network extracted from a mesh, and the C2 patch network it gives (thesis sec. 4.7: a
// face reconstructed from a few curves, and the same curves moved with each expression).
//  1. The mesh is laid over the unit square (mesh_network_disk.hpp): every vertex gets (U, V).
//  2. rows + 1 boundaries lie at U_b = b / rows. Each boundary is sampled from the mesh at
//     columns * points_per_column + 1 values V_j = j / (that - 1) (barycentric points of the
//     triangles holding (U_b, V_j)): the boundary curve C_b, a C2 spline through the samples.
//  3. Its u-derivatives are measured the same way: at each V_j the mesh is sampled at
//     U_b + t_k / rows, t_k = +-k window / derivative_points (k = 1 .. derivative_points, one side
//     only at the first and last boundary), and S_u, S_uu are the first and second derivatives at
//     t = 0 of the least-squares polynomial of degree derivative_degree through them that passes
//     through C_b(V_j) (t in row heights, i.e. the patches' own u). Those values become the curves
//     S_u and S_uu of the boundary (DerivativeSource::kCurves).
//  4. Every patch takes `shape`; u-adjacent patches share boundary data and v-adjacent ones share
//     their cardinal functions, so the surface is C2 everywhere (network.hpp).
// Every sample is a fixed combination of mesh vertices, so the network of another pose of the same
// mesh (same vertex order) is the same map applied to that pose's positions (`describe`). The mesh's
// vertex i lies at vertexParameter(i) of the network, so `reconstruct` gives the surface with the
// mesh's own vertex order and faces.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../core/result.hpp"
#include "mesh_network_disk.hpp"
#include "mesh_network_locate.hpp"
#include "network.hpp"

namespace odeskin {

struct MeshNetworkOptions {
  std::uint32_t rows = 12;                // patches along u (rows + 1 boundaries), 1 .. kMaxMeshNetworkPatches
  std::uint32_t columns = 12;             // patches along v, 1 .. kMaxMeshNetworkPatches
  std::uint32_t points_per_column = 4;    // curve points per patch along v, >= 1 (a curve has columns * this + 1)
  std::uint32_t derivative_points = 6;    // mesh samples on each side of a boundary for S_u, S_uu, >= derivative_degree
  std::uint32_t derivative_degree = 4;    // 2 .. 8
  double derivative_window = 1.0;         // how far the samples reach, in row heights, (0, 1]
  Ode6Shape shape{1.0, 0.0, 0.0};         // every patch (default: the quintic Hermite blend, regime F)
};

inline constexpr std::uint32_t kMaxMeshNetworkPatches = 1000;      // per direction
inline constexpr std::uint32_t kMaxMeshNetworkCurvePoints = 100000;
inline constexpr std::uint64_t kMaxMeshNetworkSamples = 10'000'000;  // barycentric points (36 bytes each)

// The mesh points an extraction reads per pose: every curve point and its derivative samples.
std::uint64_t meshNetworkSampleCount(const MeshNetworkOptions& options);

// Least-squares weights of step 3: S_u ~ sum first[k] (S(t_k) - S(0)), S_uu ~ sum second[k] (...).
struct DerivativeStencil {
  std::vector<double> offsets;  // t_k, in row heights
  std::vector<double> first;
  std::vector<double> second;
};

// kInvalidArgument unless offsets.size() >= degree >= 1 and the offsets are distinct and nonzero.
Result<DerivativeStencil> derivativeStencil(std::vector<double> offsets, std::uint32_t degree);

class MeshNetwork {
 public:
  // kInvalidArgument naming the option for options outside their ranges; kOutOfRange beyond
  // kMaxMeshNetworkSamples; parameteriseDisk's errors.
  static Result<MeshNetwork> extract(std::span<const Vec3> positions, const FaceList& faces,
                                     const MeshNetworkOptions& options);

  const MeshNetworkOptions& options() const { return options_; }
  const MeshDisk& disk() const { return disk_; }
  std::size_t vertexCount() const { return disk_.vertex_count; }
  std::uint32_t curvePoints() const { return options_.columns * options_.points_per_column + 1; }
  // What the network keeps: (rows + 1) boundaries x 3 curves (C, S_u, S_uu) x curvePoints() points.
  std::size_t storedPoints() const { return std::size_t{options_.rows + 1} * 3 * curvePoints(); }
  // Mesh points read per pose: curve points and derivative samples.
  std::size_t meshSamples() const { return points_.size(); }
  // Vertex i's (U, V) in [0, 1]^2 over the whole network.
  Vec2 vertexParameter(std::uint32_t vertex) const { return disk_.uv[vertex]; }
  const std::vector<Vec2>& vertexParameters() const { return vertex_uv_; }

  // The network of a pose of the mesh: the samples read on `positions` (vertexCount() of them, the
  // extraction mesh's order). kInvalidArgument for a wrong count or positions not finite or too
  // large or small for double-precision lengths ("the pose: ...", checkedPositionBox).
  Result<NetworkDescription> describe(std::span<const Vec3> positions) const;
  // describe, then Network::build.
  Result<Network> build(std::span<const Vec3> positions) const;
  // S at every mesh vertex's parameters: the reconstruction in the mesh's vertex order.
  // Precondition: `network` was built by this object.
  std::vector<Vec3> reconstruct(const Network& network) const;

 private:
  MeshNetwork() = default;

  MeshNetworkOptions options_;
  MeshDisk disk_;
  std::vector<Vec2> vertex_uv_;                 // the mesh vertices' parameters (disk_.uv without hole centres)
  std::vector<DerivativeStencil> stencils_;     // 0: first boundary, 1: inner ones, 2: last boundary
  std::vector<MeshPoint> points_;               // per boundary, per curve point: C_b(V_j), then the stencil's samples
  std::vector<std::size_t> boundary_offsets_;   // rows + 2: where each boundary's points start
};

}  // namespace odeskin

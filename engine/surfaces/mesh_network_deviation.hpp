// SPDX-License-Identifier: MIT
// How far a patch network is from the mesh it was extracted from (thesis sec. 4.7). Two distances
// per mesh vertex x_i with network parameters (U_i, V_i) in [0, 1]^2:
//  - parametric: |S(U_i, V_i) - x_i|, vertex against vertex (what `odeskin render --heat` colours
//    when the reconstruction keeps the mesh's vertex order);
//  - surface: the distance from x_i to the nearest point of the network surface, found by
//    Gauss-Newton steps on S from (U_i, V_i) (a local foot point: the surface is one sheet near
//    x_i). Never more than the parametric distance.
// Both are divided by the longest side of the measured vertices' bounding box.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh_network_disk.hpp"
#include "network.hpp"

namespace odeskin {

// Where (U, V) in [0, 1]^2 (clamped) lies in the network: the patch and its own (u, v).
struct NetworkParameter {
  std::uint32_t row = 0;
  std::uint32_t column = 0;
  double u = 0.0;
  double v = 0.0;
};
NetworkParameter networkParameter(const Network& network, Vec2 uv);

// S at each (U, V).
std::vector<Vec3> evaluateAtParameters(const Network& network, std::span<const Vec2> uv);

struct SurfacePoint {
  Vec2 uv{0.0};       // (U, V) of the foot point
  Vec3 position{0.0};
  double distance = 0.0;
};

// The point of the network nearest to x near `start` (damped Gauss-Newton in (U, V), at most 20
// steps, each accepted only if it brings the surface closer).
SurfacePoint nearestOnNetwork(const Network& network, const Vec3& x, Vec2 start);

struct MeshDeviation {
  std::size_t measured = 0;         // vertices in the figures
  std::size_t excluded = 0;         // vertices left out (flagged by the caller)
  double box = 0.0;                 // longest side of the measured vertices' box
  double mean_parametric = 0.0;     // fractions of `box`
  double max_parametric = 0.0;
  double mean_surface = 0.0;
  double max_surface = 0.0;
  std::uint32_t worst_vertex = 0;   // largest surface distance
  double excluded_max_parametric = 0.0;  // the largest parametric distance among the excluded ones, of `box`
};

// The figures over every vertex whose `excluded` entry is 0 (empty span: none excluded).
// `reconstruction` (optional) receives S(U_i, V_i) for every vertex. Preconditions: uv and
// positions have one entry per vertex, excluded is empty or as long, and at least one vertex is measured.
MeshDeviation measureDeviation(const Network& network, std::span<const Vec2> uv, std::span<const Vec3> positions,
                               std::span<const std::uint8_t> excluded = {},
                               std::vector<Vec3>* reconstruction = nullptr);

}  // namespace odeskin

// SPDX-License-Identifier: MIT
// `odeskin reconstruct MESH.obj [--rows R --cols C] [--poses P.obj...] [-o OUT.obj] [--json REPORT.json]`:
// a curve network extracted from a mesh with one rim (a face), the C2 patch network over it, and how
// far that surface is from the mesh (thesis sec. 4.7; engine/surfaces/mesh_network.hpp). With
// --poses the same network (the same barycentric samples) is read on each pose of the mesh, an
// expression of the face, and rebuilt there (the thesis's action-unit experiments).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "console.hpp"

namespace odeskin {

inline constexpr const char* kDefaultDerivativeFit = "6,3,0.5";

struct ReconstructCommandOptions {
  std::filesystem::path mesh;                 // .obj: one open surface, a disk once its holes are filled
  std::vector<std::filesystem::path> poses;   // .obj: same vertex count and face list as `mesh`
  std::uint32_t rows = 16;                    // patches along u (the mesh's second principal direction)
  std::uint32_t columns = 16;                 // patches along v
  std::uint32_t points = 2;                   // curve points per patch along v
  std::string shape = "1,3,1";                // RHO,ETA,LAMBDA for every patch
  std::string derivative_fit = kDefaultDerivativeFit;  // POINTS,DEGREE,WINDOW of the S_u, S_uu fit (mesh_network.hpp)
  double tear_ratio = 4.0;                    // pose edges stretched more than this flag their vertices
  std::filesystem::path output;               // optional .obj: MESH's reconstruction; poses beside it
  std::filesystem::path network;              // optional .json: MESH's network, for `odeskin surface`
  std::filesystem::path json;                 // optional .json report
};

struct ReconstructPoseReport {
  std::filesystem::path file;
  std::size_t flagged_vertices = 0;
  std::size_t stretched_edges = 0;
  double max_stretch = 0.0;
  std::size_t measured_vertices = 0;
  double box = 0.0;                 // longest side of the measured vertices' box
  double mean = 0.0;                // parametric distance, fraction of `box`
  double max = 0.0;
  double mean_surface = 0.0;        // distance to the surface, fraction of `box`
  double max_surface = 0.0;
  std::uint32_t worst_vertex = 0;   // 0-based
  double flagged_max = 0.0;         // largest parametric distance of a flagged vertex (to its file position)
  double reconstruct_seconds = 0.0; // network from the pose, and S at every vertex
  double measure_seconds = 0.0;     // the deviation figures (foot points)
  std::filesystem::path written;    // the reconstruction, when -o is given
  std::filesystem::path reference;  // the pose with its flagged vertices filled, when there are any
};

struct ReconstructReport {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t rim_vertices = 0;
  double rim_length = 0.0;
  std::vector<std::size_t> holes;   // vertices of each filled hole
  std::uint32_t curve_points = 0;
  std::size_t stored_points = 0;    // boundaries x 3 curves x curve_points
  double size_reduction = 0.0;      // vertices / stored_points (both x 3 floats)
  double extract_seconds = 0.0;
  std::vector<ReconstructPoseReport> poses;  // MESH first, then --poses
};

// Exit status as console.hpp: usage (2) for option errors (an output that is not .obj, a network or
// report that is not .json, counts out of range, a malformed --shape or --derivative-fit, a tear
// ratio <= 1, two poses that would write the same file); failure (1) with one line naming the file
// for an unreadable mesh or pose, a mesh that is not one open surface with a rim, a pose that is not
// the same mesh, a shape without a surface (resonance), or a write error. Files are written
// atomically, and on failure none is left behind.
int runReconstructCommand(const ReconstructCommandOptions& options, Console& console, ReconstructReport* report = nullptr);

}  // namespace odeskin

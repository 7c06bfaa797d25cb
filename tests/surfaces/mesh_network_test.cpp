// SPDX-License-Identifier: MIT
// Curve networks extracted from meshes (thesis sec. 4.7): on a triangulated height field whose
// vertices lie on a known analytic surface, the patch network is within a few millionths of the box
// of it, and the deviation falls as the network is refined until the mesh's own piecewise-linear
// error; a plane comes back exactly; the network moved to another pose rebuilds that pose; the
// parameterisation is one to one and fills holes; the derivative stencils are exact for
// polynomials; bad meshes are refused with a message naming the problem; the face-poses data give
// the documented figures and the flagged vertices of a renumbered expression lie in its renumbered block.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/surfaces/mesh_network.hpp"
#include "engine/surfaces/mesh_network_deviation.hpp"
#include "engine/surfaces/mesh_network_pose.hpp"

namespace odeskin {
namespace {

using HeightField = std::function<double(double, double)>;

double wavy(double x, double y) { return 0.15 * std::sin(1.3 * x + 0.4) * std::cos(1.1 * y) + 0.1 * x * x; }
double other(double x, double y) { return 0.2 * std::cos(0.9 * x - 0.3) * std::sin(1.4 * y + 0.2) - 0.05 * y * y; }

struct GridMesh {
  std::vector<Vec3> positions;
  FaceList faces;
};

// z = f(x, y) on an nx x ny grid over [-1, 1] x [-0.8, 0.8] (x the wider side), two triangles per
// cell; cells with `hole` true are left out.
GridMesh heightField(const HeightField& f, std::uint32_t nx, std::uint32_t ny,
                     const std::function<bool(std::uint32_t, std::uint32_t)>& hole = {}) {
  GridMesh m;
  for (std::uint32_t j = 0; j < ny; ++j) {
    for (std::uint32_t i = 0; i < nx; ++i) {
      const double x = -1.0 + 2.0 * i / (nx - 1), y = -0.8 + 1.6 * j / (ny - 1);
      m.positions.emplace_back(x, y, f(x, y));
    }
  }
  for (std::uint32_t j = 0; j + 1 < ny; ++j) {
    for (std::uint32_t i = 0; i + 1 < nx; ++i) {
      if (hole && hole(i, j)) continue;
      const std::uint32_t a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      for (const std::array<std::uint32_t, 3>& t : {std::array{a, b, d}, std::array{a, d, c}}) {
        m.faces.indices.insert(m.faces.indices.end(), t.begin(), t.end());
        m.faces.face_offsets.push_back(static_cast<std::uint32_t>(m.faces.indices.size()));
      }
    }
  }
  return m;
}

MeshNetworkOptions grid(std::uint32_t n) {
  MeshNetworkOptions o;
  o.rows = n;
  o.columns = n;
  o.points_per_column = 2;
  o.derivative_points = 6;
  o.derivative_degree = 3;
  o.derivative_window = 0.5;
  o.shape = {1.0, 3.0, 1.0};
  return o;
}

MeshDeviation deviation(const MeshNetwork& m, std::span<const Vec3> pose) {
  Result<Network> network = m.build(pose);
  EXPECT_TRUE(network.ok()) << network.status().toString();
  return measureDeviation(*network, m.vertexParameters(), pose);
}

// Signed uv area of every triangle has one sign: the map is one to one.
void expectOneToOne(const MeshDisk& disk) {
  std::size_t positive = 0, negative = 0;
  for (const auto& t : disk.triangles) {
    const Vec2 a = disk.uv[t[0]], b = disk.uv[t[1]], c = disk.uv[t[2]];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    (area > 0.0 ? positive : negative) += 1;
  }
  EXPECT_TRUE(positive == 0 || negative == 0) << positive << " triangles one way, " << negative << " the other";
  for (const Vec2& p : disk.uv) {
    EXPECT_GE(std::min(p.x, p.y), 0.0);
    EXPECT_LE(std::max(p.x, p.y), 1.0);
  }
}

TEST(MeshNetwork, DeviationFromAnAnalyticSurfaceFallsWithFinerNetworks) {
  const GridMesh mesh = heightField(wavy, 121, 97);
  double last_mean = INFINITY, last_max = INFINITY;
  for (std::uint32_t n : {1u, 2u, 4u, 8u}) {
    Result<MeshNetwork> m = MeshNetwork::extract(mesh.positions, mesh.faces, grid(n));
    ASSERT_TRUE(m.ok()) << m.status().toString();
    const MeshDeviation d = deviation(*m, mesh.positions);
    std::printf("%u x %u patches, %zu points: surface mean %.3e max %.3e, parametric mean %.3e max %.3e\n", n, n,
                m->storedPoints(), d.mean_surface, d.max_surface, d.mean_parametric, d.max_parametric);
    EXPECT_EQ(d.measured, mesh.positions.size());
    EXPECT_LT(d.mean_surface, 0.5 * last_mean) << n;
    EXPECT_LT(d.max_surface, 0.5 * last_max) << n;
    EXPECT_LE(d.mean_surface, d.mean_parametric);
    last_mean = d.mean_surface;
    last_max = d.max_surface;
  }
  // 8 x 8 patches reach the mesh's own error (its triangles are chords of the surface: ~2e-6).
  EXPECT_LT(last_mean, 5e-6);
  EXPECT_LT(last_max, 2e-5);
}

TEST(MeshNetwork, MovedToAnotherPoseRebuildsThatPose) {
  const GridMesh neutral = heightField(wavy, 121, 97);
  const GridMesh pose = heightField(other, 121, 97);
  Result<MeshNetwork> m = MeshNetwork::extract(neutral.positions, neutral.faces, grid(8));
  ASSERT_TRUE(m.ok()) << m.status().toString();
  const MeshDeviation d = deviation(*m, pose.positions);
  EXPECT_LT(d.mean_surface, 5e-6);
  EXPECT_LT(d.max_parametric, 5e-5);
  // A pose with other vertex counts is refused.
  const std::vector<Vec3> shorter(pose.positions.begin(), pose.positions.end() - 1);
  EXPECT_EQ(m->build(shorter).status().code(), StatusCode::kInvalidArgument);
}

TEST(MeshNetwork, APlaneComesBackExactly) {
  // Mean-value coordinates reproduce a planar mesh's own affine map; every later step (samples,
  // polynomial fits, splines, the ODE) reproduces linear functions.
  const GridMesh mesh = heightField([](double x, double y) { return 0.3 * x - 0.2 * y + 0.5; }, 31, 25);
  for (std::uint32_t n : {1u, 3u, 7u}) {
    Result<MeshNetwork> m = MeshNetwork::extract(mesh.positions, mesh.faces, grid(n));
    ASSERT_TRUE(m.ok()) << m.status().toString();
    const MeshDeviation d = deviation(*m, mesh.positions);
    EXPECT_LT(d.max_parametric, 1e-12) << n;
    EXPECT_LT(d.max_surface, 1e-12) << n;
    expectOneToOne(m->disk());
  }
}

TEST(MeshNetwork, FootPointsFindTheSurfaceFromAnywhereNearIt) {
  const GridMesh mesh = heightField([](double, double) { return 0.0; }, 21, 17);
  Result<MeshNetwork> m = MeshNetwork::extract(mesh.positions, mesh.faces, grid(2));
  ASSERT_TRUE(m.ok());
  Result<Network> network = m->build(mesh.positions);
  ASSERT_TRUE(network.ok());
  // (x, y, 0.05) lies 0.05 above the plane z = 0, whatever (U, V) the search starts from.
  const SurfacePoint p = nearestOnNetwork(*network, {0.3, -0.2, 0.05}, {0.2, 0.9});
  EXPECT_NEAR(p.distance, 0.05, 1e-12);
  EXPECT_NEAR(p.position.x, 0.3, 1e-9);
  EXPECT_NEAR(p.position.y, -0.2, 1e-9);
}

TEST(MeshNetwork, HolesAreFilledAndTheMapIsOneToOne) {
  // A slit of 6 x 1 cells in the middle (a mouth), and the curves cross it.
  const GridMesh mesh = heightField(wavy, 61, 49, [](std::uint32_t i, std::uint32_t j) { return i >= 27 && i < 33 && j == 24; });
  Result<MeshNetwork> m = MeshNetwork::extract(mesh.positions, mesh.faces, grid(4));
  ASSERT_TRUE(m.ok()) << m.status().toString();
  ASSERT_EQ(m->disk().holes.size(), 1u);
  EXPECT_EQ(m->disk().holes[0].size(), 14u);
  EXPECT_EQ(m->disk().rim.size(), 2u * (61 - 1) + 2u * (49 - 1));
  expectOneToOne(m->disk());
  // The corners are the grid's corners: u runs up (+y), and v along -x so that S_u x S_v = +z, the
  // faces' normal.
  const std::array<std::uint32_t, 4> corners = {60, 0, 48 * 61, 49 * 61 - 1};
  EXPECT_EQ(m->disk().corners, corners);
  const MeshDeviation d = deviation(*m, mesh.positions);
  EXPECT_LT(d.mean_surface, 1e-4);
  EXPECT_LT(d.max_surface, 2e-3);
}

TEST(MeshNetwork, DerivativeStencilsAreExactForPolynomials) {
  for (const std::vector<double>& offsets : {std::vector<double>{0.1, 0.2, 0.3, 0.4},
                                             std::vector<double>{-0.5, -0.25, 0.25, 0.5, 0.75},
                                             std::vector<double>{-0.3, -0.2, -0.1}}) {
    Result<DerivativeStencil> s = derivativeStencil(offsets, 3);
    ASSERT_TRUE(s.ok()) << s.status().toString();
    // f(t) = 2 - 3t + 5t^2 + 7t^3: f'(0) = -3, f''(0) = 10.
    double first = 0.0, second = 0.0;
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const double t = offsets[k], difference = -3.0 * t + 5.0 * t * t + 7.0 * t * t * t;
      first += s->first[k] * difference;
      second += s->second[k] * difference;
    }
    EXPECT_NEAR(first, -3.0, 1e-10);
    EXPECT_NEAR(second, 10.0, 1e-9);
  }
  EXPECT_EQ(derivativeStencil({0.1, 0.2}, 3).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(derivativeStencil({0.1, 0.0, 0.3}, 2).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(derivativeStencil({0.1, 0.1, 0.3}, 2).status().code(), StatusCode::kInvalidArgument);
}

TEST(MeshNetwork, BadMeshesAndOptionsAreRefused) {
  const auto refused = [](const std::vector<Vec3>& p, const std::vector<std::uint32_t>& indices, const std::string& words,
                          MeshNetworkOptions o = grid(2)) {
    FaceList f;
    f.indices = indices;
    for (std::size_t k = 3; k <= indices.size(); k += 3) f.face_offsets.push_back(static_cast<std::uint32_t>(k));
    Result<MeshNetwork> m = MeshNetwork::extract(p, f, o);
    ASSERT_FALSE(m.ok()) << words;
    EXPECT_EQ(m.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(m.status().message().find(words), std::string::npos) << m.status().message();
  };
  const std::vector<Vec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  refused(tetra, {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2}, "closed");
  refused(tetra, {0, 1, 2}, "in no face");
  refused({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2}, "at least 4");
  refused(tetra, {0, 1, 2, 0, 1, 3}, "not manifold");
  refused(tetra, {0, 1, 7}, "uses vertex 8");
  const std::vector<Vec3> two = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}};
  refused(two, {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}, "several pieces");
  const GridMesh mesh = heightField(wavy, 9, 7);
  std::vector<std::uint32_t> indices = mesh.faces.indices;
  MeshNetworkOptions bad = grid(2);
  bad.rows = 0;
  refused(mesh.positions, indices, "rows", bad);
  bad = grid(2);
  bad.derivative_window = 1.5;
  refused(mesh.positions, indices, "window", bad);
  bad = grid(2);
  bad.derivative_points = 2;
  refused(mesh.positions, indices, "derivative points", bad);
  bad = grid(1000);
  bad.points_per_column = 50;
  FaceList f = mesh.faces;
  EXPECT_EQ(MeshNetwork::extract(mesh.positions, f, bad).status().code(), StatusCode::kOutOfRange);
  std::vector<Vec3> nan = mesh.positions;
  nan[5].y = NAN;
  refused(nan, indices, "vertex 6 is not finite");
  // Finite, but its squared lengths overflow: refused as such, not as a rim that is not convex.
  std::vector<Vec3> huge = mesh.positions;
  for (Vec3& p : huge) p *= 1e200;
  refused(huge, indices, "the mesh is too large for double-precision distances");
}

TEST(MeshNetworkPose, StretchedEdgesFlagRenumberedVerticesAndFillingRestoresThem) {
  const GridMesh reference = heightField(wavy, 21, 17);
  // Every vertex moves by a linear map, which the uniform graph Laplacian of this grid keeps harmonic.
  std::vector<Vec3> pose = reference.positions;
  for (Vec3& p : pose) p += Vec3(0.1 * p.x - 0.05 * p.y, 0.2 * p.y, 0.03 + 0.1 * p.x);
  const std::vector<Vec3> truth = pose;
  // Two vertices far apart swap places, as a renumbered file would have them.
  std::swap(pose[4 * 21 + 5], pose[12 * 21 + 15]);
  Result<PoseFlags> flags = flagVertices(reference.positions, pose, reference.faces, 4.0);
  ASSERT_TRUE(flags.ok());
  EXPECT_EQ(flags->flagged_vertices, 2u * 7u);  // each swapped vertex and its six neighbours
  EXPECT_EQ(flags->flagged[4 * 21 + 5], 1);
  EXPECT_EQ(flags->flagged[12 * 21 + 15], 1);
  Result<std::vector<Vec3>> filled = fillFlagged(reference.positions, pose, reference.faces, flags->flagged);
  ASSERT_TRUE(filled.ok()) << filled.status().toString();
  for (std::size_t i = 0; i < truth.size(); ++i) EXPECT_LT(glm::distance((*filled)[i], truth[i]), 1e-12) << i;

  // The true pose alone flags nothing; everything flagged leaves nothing to fill from.
  EXPECT_EQ(flagVertices(reference.positions, truth, reference.faces, 4.0)->flagged_vertices, 0u);
  const std::vector<std::uint8_t> all(pose.size(), 1);
  EXPECT_EQ(fillFlagged(reference.positions, pose, reference.faces, all).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(flagVertices(reference.positions, pose, reference.faces, 1.0).status().code(), StatusCode::kInvalidArgument);
  // A pose too large for its edge lengths is refused, not every edge flagged as stretched.
  std::vector<Vec3> huge = truth;
  for (Vec3& p : huge) p *= 1e200;
  const Status too_large = flagVertices(reference.positions, huge, reference.faces, 4.0).status();
  EXPECT_EQ(too_large.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(too_large.message().find("the pose: the mesh is too large"), std::string::npos) << too_large.message();
  std::vector<Vec3> nan = truth;
  nan[7].x = NAN;
  EXPECT_EQ(flagVertices(reference.positions, nan, reference.faces, 4.0).status().message(), "the pose: vertex 8 is not finite");
}

// The face-poses data (docs/surfaces.md, "Reconstructing a real face"): the default network's figures.
TEST(MeshNetworkFace, TheNeutralFaceAndARenumberedExpression) {
  const std::filesystem::path dir = std::filesystem::path(ODESKIN_DATA_DIR) / "face-poses";
  if (!std::filesystem::exists(dir / "face-00.obj")) GTEST_SKIP() << "no face-poses data in " << dir;
  Result<ObjMesh> neutral = readObj(dir / "face-00.obj");
  Result<ObjMesh> smile = readObj(dir / "face-01.obj");
  ASSERT_TRUE(neutral.ok() && smile.ok());
  Result<MeshNetwork> m = MeshNetwork::extract(neutral->positions, neutral->faces, grid(16));
  ASSERT_TRUE(m.ok()) << m.status().toString();
  EXPECT_EQ(m->disk().rim.size(), 688u);
  ASSERT_EQ(m->disk().holes.size(), 1u);  // the mouth
  EXPECT_EQ(m->disk().holes[0].size(), 74u);
  expectOneToOne(m->disk());
  EXPECT_EQ(m->storedPoints(), 17u * 3u * 33u);
  const MeshDeviation d = deviation(*m, neutral->positions);
  EXPECT_LT(d.mean_surface, 0.0005);
  EXPECT_LT(d.max_surface, 0.015);

  // face-01 numbers vertices 22826..23560 (0-based) differently from face-00; every flagged vertex is there.
  Result<PoseFlags> flags = flagVertices(neutral->positions, smile->positions, neutral->faces, 4.0);
  ASSERT_TRUE(flags.ok());
  EXPECT_GT(flags->flagged_vertices, 400u);
  for (std::size_t i = 0; i < flags->flagged.size(); ++i) {
    if (flags->flagged[i] != 0) {
      EXPECT_GE(i, 22826u);
      EXPECT_LE(i, 23560u);
    }
  }
  EXPECT_EQ(flagVertices(neutral->positions, readObj(dir / "face-02.obj")->positions, neutral->faces, 4.0)->flagged_vertices, 0u);
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// isSimpleManifold and boundaryLoopsOfFaces against OpenMesh (buildPolyMesh, boundaryLoops): every
// mesh the quick check accepts OpenMesh builds, with the same boundary loops, in the same order,
// from the same start vertices; the meshes it rejects include every one OpenMesh rejects.
#include "engine/mesh/face_fans.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/mesh/poly_mesh.hpp"

namespace odeskin {
namespace {

const std::string kData = ODESKIN_DATA_DIR;

FaceList facesOf(std::initializer_list<std::initializer_list<std::uint32_t>> list) {
  FaceList faces;
  for (const auto& face : list) {
    faces.indices.insert(faces.indices.end(), face);
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  }
  return faces;
}

// A grid of (nx+1) x (ny+1) vertices in quads, or triangles; `skip` removes faces (holes).
FaceList grid(std::uint32_t nx, std::uint32_t ny, bool quads, const std::vector<std::uint32_t>& skip = {}) {
  FaceList faces;
  std::uint32_t index = 0;
  for (std::uint32_t y = 0; y < ny; ++y) {
    for (std::uint32_t x = 0; x < nx; ++x, ++index) {
      if (std::find(skip.begin(), skip.end(), index) != skip.end()) continue;
      const std::uint32_t a = y * (nx + 1) + x, b = a + 1, c = b + nx + 1, d = a + nx + 1;
      if (quads) {
        faces.indices.insert(faces.indices.end(), {a, b, c, d});
        faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
      } else {
        faces.indices.insert(faces.indices.end(), {a, b, c});
        faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
        faces.indices.insert(faces.indices.end(), {a, c, d});
        faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
      }
    }
  }
  return faces;
}

std::vector<Vec3> points(std::size_t count) {
  std::vector<Vec3> p(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t row = i / 17;  // rows of 17 points
    p[i] = Vec3(static_cast<double>(i % 17), static_cast<double>(row), 0.0);
  }
  return p;
}

// The quick check's verdict agrees with OpenMesh where it says yes, with the same loops.
void expectAsOpenMesh(const std::vector<Vec3>& positions, const FaceList& faces, const std::string& what) {
  const auto loops = simpleManifoldBoundaryLoops(faces, positions.size());
  Result<PolyMesh> mesh = buildPolyMesh(positions, faces, what);
  if (!loops) return;  // no verdict: OpenMesh's stands
  ASSERT_TRUE(mesh.ok()) << what << ": the quick check accepted what OpenMesh rejects: " << mesh.status().toString();
  EXPECT_EQ(*loops, boundaryLoops(*mesh)) << what;
  EXPECT_TRUE(isSimpleManifold(faces, positions.size()));
  EXPECT_EQ(boundaryLoopsOfFaces(faces, positions.size()), *loops);
}

TEST(FaceFans, DataMeshesAreSimpleWithOpenMeshLoops) {
  for (const std::string file : {"/cat-poses/cat-00.obj", "/horse-gallop/horse-01.obj", "/cylinder/cylinder.obj",
                                 "/cheburashka/cheburashka.obj", "/face-poses/face-00.obj"}) {
    Result<ObjMesh> obj = readObj(kData + file);
    ASSERT_TRUE(obj.ok()) << obj.status().toString();
    EXPECT_TRUE(isSimpleManifold(obj->faces, obj->positions.size())) << file;
    expectAsOpenMesh(obj->positions, obj->faces, file);
  }
  Result<ObjMesh> horse = readObj(kData + "/horse-gallop/horse-01.obj");
  ASSERT_TRUE(horse.ok());
  const auto loops = boundaryLoopsOfFaces(horse->faces, horse->positions.size());
  ASSERT_EQ(loops.size(), 2u);  // README: a 16-edge hole under a hoof, a 3-edge hole on the head
  EXPECT_EQ(loops[0].size() + loops[1].size(), 19u);
}

TEST(FaceFans, GridsWithHolesAndMixedPolygons) {
  expectAsOpenMesh(points(std::size_t{5} * 4), grid(4, 3, true), "quad grid");
  expectAsOpenMesh(points(std::size_t{7} * 6), grid(6, 5, false, {7, 8, 20, 33}), "triangle grid with holes");
  expectAsOpenMesh(points(std::size_t{7} * 6), grid(6, 5, true, {7, 9, 21}), "quad grid with holes");
  // A pentagon and a hexagon among triangles.
  expectAsOpenMesh(points(12), facesOf({{0, 1, 2, 3, 4}, {0, 4, 5}, {4, 3, 6, 7, 8, 9}, {0, 5, 10, 11}}), "polygons");
  const auto loops = boundaryLoopsOfFaces(grid(6, 5, false, {7, 8, 20, 33}), std::size_t{7} * 6);
  EXPECT_EQ(loops.size(), 3u);  // the rim, the hole of faces 7 and 8 (one quad), faces 20 and 33 apart
}

TEST(FaceFans, RejectsWhatIsNotOneFanPerVertex) {
  const std::vector<Vec3> p = points(8);
  // Two triangles touching at vertex 0 only (a bow tie): two fans.
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 2}, {0, 3, 4}}), 5));
  expectAsOpenMesh(p, facesOf({{0, 1, 2}, {0, 3, 4}}), "bow tie");
  // A flipped neighbour uses the directed edge 0 -> 1 twice.
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 2}, {0, 1, 3}}), 4));
  expectAsOpenMesh(p, facesOf({{0, 1, 2}, {0, 1, 3}}), "flipped");
  // Three faces on one edge.
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 2}, {1, 0, 3}, {1, 0, 4}}), 5));
  expectAsOpenMesh(p, facesOf({{0, 1, 2}, {1, 0, 3}, {1, 0, 4}}), "three faces on an edge");
  // Bad faces: out of range, too short, a repeated corner.
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 9}}), 8));
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1}}), 8));
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 1}}), 8));
  EXPECT_FALSE(isSimpleManifold(facesOf({{0, 1, 2, 3, 1}}), 8));
  EXPECT_TRUE(boundaryLoopsOfFaces(facesOf({{0, 1, 9}}), 8).empty());
  // A vertex without faces is fine.
  EXPECT_TRUE(isSimpleManifold(facesOf({{0, 1, 2}}), 8));
  expectAsOpenMesh(p, facesOf({{0, 1, 2}}), "one triangle");
}

}  // namespace
}  // namespace odeskin

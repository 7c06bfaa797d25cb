// SPDX-License-Identifier: MIT
#include "engine/rig/rigid_clusters.hpp"

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "engine/offline/residual_fit.hpp"
#include "data_mesh.hpp"

namespace odeskin {
namespace {

// Cat-poses 00 and 01 as the automatic rig sees them: Lloyd rounds at 3, 4, 15 and 18 clusters
// cycle (2 rounds long) until the cap.
struct CatMotion {
  ObjMesh rest = testing::dataMesh("cat-poses/cat-00.obj");
  std::vector<std::vector<Vec3>> poses{rest.positions, testing::dataMesh("cat-poses/cat-01.obj").positions};
  VertexAdjacency adjacency = vertexAdjacency(rest.faces, rest.positions.size());
  MotionData motion{rest.positions, &poses, &adjacency, longestBoxSide(rest.positions)};
};

Clustering cluster(const MotionData& motion, bool skip_cycles) {
  ClusterOptions options;
  options.skip_cycles = skip_cycles;
  Result<Clustering> c = clusterRigidMotion(motion, options);
  if (!c.ok()) throw std::runtime_error(c.status().toString());
  return std::move(c).value();
}

TEST(RigidClusters, SkippingACycleEndsWhereTheCapWould) {
  const CatMotion cat;
  const Clustering all_rounds = cluster(cat.motion, false);
  const Clustering skipped = cluster(cat.motion, true);
  EXPECT_LT(skipped.lloyd_rounds, all_rounds.lloyd_rounds);
  EXPECT_EQ(skipped.labels, all_rounds.labels);
  ASSERT_EQ(skipped.clusterCount(), all_rounds.clusterCount());
  ASSERT_EQ(skipped.transforms.size(), all_rounds.transforms.size());
  for (std::size_t k = 0; k < skipped.transforms.size(); ++k) {
    EXPECT_EQ(std::memcmp(skipped.transforms[k].data(), all_rounds.transforms[k].data(),
                          skipped.transforms[k].size() * sizeof(RigidTransform)),
              0)
        << "pose " << k;
  }
  EXPECT_EQ(skipped.vertex_error, all_rounds.vertex_error);
  EXPECT_EQ(skipped.rms_error, all_rounds.rms_error);
  std::printf("Lloyd rounds: %zu of %zu, %zu clusters\n", skipped.lloyd_rounds, all_rounds.lloyd_rounds,
              skipped.clusterCount());
}

}  // namespace
}  // namespace odeskin

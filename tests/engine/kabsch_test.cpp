// SPDX-License-Identifier: MIT
#include "engine/rig/kabsch.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "engine/io/obj_reader.hpp"
#include "engine/kernels/lbs_job.hpp"
#include "rigid_transform_test_support.hpp"

namespace odeskin {
namespace {

using testing::transformDistance;

const std::string kCylinder = std::string(ODESKIN_DATA_DIR) + "/cylinder/";

RigidTransform randomRigid(std::mt19937& rng, double translation_scale) {
  std::normal_distribution<double> normal(0.0, 1.0);
  RigidTransform m;
  m.rotation = glm::normalize(glm::dquat(normal(rng), normal(rng), normal(rng), normal(rng)));
  m.translation = translation_scale * Vec3(normal(rng), normal(rng), normal(rng));
  return m;
}

// libigl ASCII .DMAT (first line "cols rows", then column-major values) as a row-major matrix.
std::vector<double> readDmatRowMajor(const std::string& path, std::size_t& rows, std::size_t& cols) {
  std::ifstream in(path);
  if (!(in >> cols >> rows)) throw std::runtime_error("cannot read the header of " + path);
  std::vector<double> m(rows * cols);
  for (std::size_t c = 0; c < cols; ++c) {
    for (std::size_t r = 0; r < rows; ++r) {
      if (!(in >> m[r * cols + c])) throw std::runtime_error("short matrix in " + path);
    }
  }
  return m;
}

// .Tmat: per bone four lines, the columns of R then t.
std::vector<RigidTransform> readTmat(const std::string& path, std::size_t bones) {
  std::ifstream in(path);
  std::vector<RigidTransform> out(bones);
  for (std::size_t b = 0; b < bones; ++b) {
    glm::dmat3 r;
    for (int c = 0; c < 3; ++c) {
      for (int row = 0; row < 3; ++row) {
        if (!(in >> r[c][row])) throw std::runtime_error("short transform file " + path);
      }
    }
    for (int row = 0; row < 3; ++row) {
      if (!(in >> out[b].translation[row])) throw std::runtime_error("short transform file " + path);
    }
    out[b].rotation = glm::normalize(glm::quat_cast(r));
  }
  return out;
}

std::vector<Vec3> randomPoints(std::mt19937& rng, std::size_t count) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec3> points(count);
  for (Vec3& p : points) p = Vec3(unit(rng), unit(rng), unit(rng)) + Vec3(3.0, -2.0, 5.0);
  return points;
}

std::vector<Vec3> applied(const RigidTransform& m, std::span<const Vec3> points) {
  std::vector<Vec3> out;
  for (const Vec3& p : points) out.push_back(m.apply(p));
  return out;
}

TEST(WeightedKabsch, RecoversRandomRigidTransforms) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> positive(0.01, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<Vec3> from = randomPoints(rng, 3 + static_cast<std::size_t>(trial % 40));
    std::vector<double> weights(from.size());
    for (double& w : weights) w = positive(rng);
    const RigidTransform truth = randomRigid(rng, 10.0);
    const Result<RigidTransform> fit = weightedKabsch(from, applied(truth, from), weights);
    ASSERT_TRUE(fit.ok()) << fit.status().toString();
    EXPECT_LT(transformDistance(fit.value(), truth), 1e-12) << "trial " << trial;
    EXPECT_NEAR(glm::length(fit->rotation), 1.0, 1e-15);
  }
}

TEST(WeightedKabsch, ZeroWeightPointsDoNotCount) {
  std::mt19937 rng(11);
  std::vector<Vec3> from = randomPoints(rng, 10);
  const RigidTransform truth = randomRigid(rng, 1.0);
  std::vector<Vec3> to = applied(truth, from);
  std::vector<double> weights(10, 1.0);
  to[3] += Vec3(100.0, 0.0, 0.0);
  weights[3] = 0.0;
  from[8] = Vec3(std::numeric_limits<double>::quiet_NaN());  // ignored: weight 0
  weights[8] = 0.0;
  const Result<RigidTransform> fit = weightedKabsch(from, to, weights);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  EXPECT_LT(transformDistance(fit.value(), truth), 1e-12);
}

TEST(WeightedKabsch, ReflectionBecomesAProperRotation) {
  // Planar points mirrored across the plane x = 0 inside their own plane z = 0: the half turn about
  // y maps them exactly, while the unconstrained optimum would be the mirror itself (det -1).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec3> from(12);
  for (Vec3& p : from) p = Vec3(unit(rng), unit(rng), 0.0);
  std::vector<Vec3> to;
  to.reserve(from.size());
  for (const Vec3& p : from) to.push_back(Vec3(-p.x, p.y, p.z));
  std::vector<double> weights(from.size(), 1.0);
  Result<RigidTransform> fit = weightedKabsch(from, to, weights);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  EXPECT_NEAR(glm::determinant(glm::mat3_cast(fit->rotation)), 1.0, 1e-12);
  for (std::size_t i = 0; i < from.size(); ++i) EXPECT_LT(glm::length(fit->apply(from[i]) - to[i]), 1e-12);
  const RigidTransform half_turn = rotationAbout(Vec3(0.0), Vec3(0.0, 1.0, 0.0), std::numbers::pi);
  EXPECT_LT(transformDistance(fit.value(), half_turn), 1e-12);

  // A solid mirrored: no rotation fits, but the answer must still be one (det +1), and no random
  // rotation may fit better.
  const std::vector<Vec3> solid = randomPoints(rng, 30);
  to.clear();
  for (const Vec3& p : solid) to.push_back(Vec3(-p.x, p.y, p.z));
  weights.assign(solid.size(), 1.0);
  fit = weightedKabsch(solid, to, weights);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  EXPECT_NEAR(glm::determinant(glm::mat3_cast(fit->rotation)), 1.0, 1e-12);
  auto error = [&](const RigidTransform& m) {
    double e = 0.0;
    for (std::size_t i = 0; i < solid.size(); ++i) e += glm::dot(m.apply(solid[i]) - to[i], m.apply(solid[i]) - to[i]);
    return e;
  };
  const double best = error(fit.value());
  for (int trial = 0; trial < 200; ++trial) {
    RigidTransform other = randomRigid(rng, 0.0);
    // Give each random rotation its own best translation so only the rotation is compared.
    Vec3 from_c(0.0);
    Vec3 to_c(0.0);
    for (std::size_t i = 0; i < solid.size(); ++i) {
      from_c += solid[i] / static_cast<double>(solid.size());
      to_c += to[i] / static_cast<double>(solid.size());
    }
    other.translation = to_c - other.rotation * from_c;
    EXPECT_LE(best, error(other) + 1e-12);
  }
}

TEST(WeightedKabsch, BadAndDegenerateInput) {
  std::mt19937 rng(5);
  const std::vector<Vec3> from = randomPoints(rng, 6);
  const std::vector<Vec3>& to = from;
  std::vector<double> weights(6, 1.0);
  EXPECT_EQ(weightedKabsch(from, std::span(to).first(5), weights).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(weightedKabsch(from, to, std::span(weights).first(5)).status().code(), StatusCode::kInvalidArgument);
  weights[2] = -0.5;
  EXPECT_EQ(weightedKabsch(from, to, weights).status().code(), StatusCode::kInvalidArgument);
  weights[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(weightedKabsch(from, to, weights).status().code(), StatusCode::kInvalidArgument);
  std::vector<Vec3> bad = to;
  bad[1].y = std::numeric_limits<double>::quiet_NaN();
  weights.assign(6, 1.0);
  EXPECT_EQ(weightedKabsch(from, bad, weights).status().code(), StatusCode::kInvalidArgument);

  weights.assign(6, 0.0);
  EXPECT_EQ(weightedKabsch(from, to, weights).status().code(), StatusCode::kDegenerate);
  EXPECT_EQ(weightedKabsch({}, {}, {}).status().code(), StatusCode::kDegenerate);
  // Two points with weight, or many on one line: a turn about that line is free.
  weights[0] = 1.0;
  weights[4] = 2.0;
  EXPECT_EQ(weightedKabsch(from, to, weights).status().code(), StatusCode::kDegenerate);
  std::vector<Vec3> line;
  line.reserve(10);
  for (int i = 0; i < 10; ++i) line.push_back(Vec3(1.0, 2.0, 3.0) + 0.3 * i * Vec3(1.0, -1.0, 2.0));
  std::vector<double> ones(line.size(), 1.0);
  EXPECT_EQ(weightedKabsch(line, applied(randomRigid(rng, 1.0), line), ones).status().code(),
            StatusCode::kDegenerate);
  // Three non-collinear points are enough.
  weights[2] = 0.5;
  EXPECT_TRUE(weightedKabsch(from, to, weights).ok());
  // Finite points whose products overflow: refused as such, not as collinear points.
  std::vector<Vec3> far = from;
  for (Vec3& p : far) p *= 1e200;
  const Status overflow = weightedKabsch(far, far, weights).status();
  EXPECT_EQ(overflow.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(overflow.message().find("too far apart for double precision"), std::string::npos) << overflow.message();
}

struct Cylinder {
  ObjMesh rest;
  Influences influences;
  Skeleton skeleton;
  std::vector<std::vector<Vec3>> poses;
  std::vector<std::vector<RigidTransform>> transforms;  // .Tmat, K x 4
};

// The cylinder's rest mesh, its 4-bone skeleton (README joints, parents [-1, 0, -1, 2]), weights
// and the 8 posed meshes with their ground-truth transforms.
Cylinder loadCylinder() {
  Cylinder c;
  Result<ObjMesh> rest = readObj(kCylinder + "cylinder.obj");
  if (!rest.ok()) throw std::runtime_error(rest.status().toString());
  c.rest = std::move(rest).value();
  std::size_t rows = 0;
  std::size_t cols = 0;
  const std::vector<double> w = readDmatRowMajor(kCylinder + "cylinder.DMAT", rows, cols);
  if (rows != c.rest.positions.size() || cols != 4) throw std::runtime_error("cylinder.DMAT is not 420 x 4");
  c.influences = influencesFromDense(w, rows, 4);
  c.skeleton.parents = {-1, 0, -1, 2};
  c.skeleton.heads = {Vec3(0.0), Vec3(0.9, 0.0, 0.0), Vec3(0.0), Vec3(-0.9, 0.0, 0.0)};
  c.skeleton.tails = {Vec3(0.9, 0.0, 0.0), Vec3(1.8, 0.0, 0.0), Vec3(-0.9, 0.0, 0.0), Vec3(-1.8, 0.0, 0.0)};
  for (const char* set : {"poses-1", "poses-2"}) {
    for (int k = 1; k <= 4; ++k) {
      const std::string stem = kCylinder + set + "/cylinder-" + std::to_string(k);
      Result<ObjMesh> pose = readObj(stem + ".obj");
      if (!pose.ok()) throw std::runtime_error(pose.status().toString());
      c.poses.push_back(pose->positions);
      c.transforms.push_back(readTmat(stem + ".Tmat", 4));
    }
  }
  return c;
}

TEST(FitBoneTransforms, RecoversTheCylinderTransforms) {
  const Cylinder c = loadCylinder();
  const auto fit = fitBoneTransforms(c.rest.positions, c.poses, c.influences, c.skeleton);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  ASSERT_EQ(fit->size(), c.poses.size());
  for (std::size_t k = 0; k < c.poses.size(); ++k) {
    ASSERT_EQ((*fit)[k].size(), 4u);
    std::vector<BoneTransform> bones;
    for (std::size_t b = 0; b < 4; ++b) {
      // .Tmat holds about 6 significant digits.
      EXPECT_LT(transformDistance((*fit)[k][b], c.transforms[k][b]), 1e-4) << "pose " << k << " bone " << b;
      bones.push_back((*fit)[k][b].matrix());
    }
    // And they reproduce the pose as well as the published transforms do (README: 1.8e-6).
    for (std::size_t i = 0; i < c.rest.positions.size(); ++i) {
      const Vec3 p = skinPoint(c.influences, bones, i, c.rest.positions[i]);
      ASSERT_LT(glm::length(p - c.poses[k][i]), 4e-6) << "pose " << k << " vertex " << i;
    }
  }
}

TEST(FitBoneTransforms, BindPoseGivesIdentity) {
  const Cylinder c = loadCylinder();
  const std::vector<std::vector<Vec3>> poses{c.rest.positions};
  const auto fit = fitBoneTransforms(c.rest.positions, poses, c.influences, c.skeleton);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  for (const RigidTransform& m : (*fit)[0]) EXPECT_LT(transformDistance(m, RigidTransform{}), 1e-13);
}

TEST(FitBoneTransforms, UnweightedBoneFollowsItsParent) {
  Cylinder c = loadCylinder();
  // Bone 4, a child of bone 1, with no vertex; bone 5, a root with only two vertices (collinear).
  c.skeleton.parents.push_back(1);
  c.skeleton.parents.push_back(-1);
  for (int extra = 0; extra < 2; ++extra) {
    c.skeleton.heads.push_back(Vec3(1.8, 0.0, 0.0));
    c.skeleton.tails.push_back(Vec3(2.0, 0.0, 0.0));
  }
  Influences in;
  for (std::size_t i = 0; i < c.rest.positions.size(); ++i) {
    for (std::uint32_t e = c.influences.offsets[i]; e < c.influences.offsets[i + 1]; ++e) {
      in.bones.push_back(c.influences.bones[e]);
      in.weights.push_back(c.influences.weights[e] * (i < 2 ? 0.5 : 1.0));
    }
    if (i < 2) {
      in.bones.push_back(5);
      in.weights.push_back(0.5);
    }
    in.offsets.push_back(static_cast<std::uint32_t>(in.bones.size()));
  }
  const auto fit = fitBoneTransforms(c.rest.positions, c.poses, in, c.skeleton);
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  for (std::size_t k = 0; k < c.poses.size(); ++k) {
    EXPECT_LT(transformDistance((*fit)[k][4], (*fit)[k][1]), 1e-15) << "pose " << k;
    EXPECT_LT(transformDistance((*fit)[k][5], RigidTransform{}), 1e-15) << "pose " << k;
  }
}

TEST(FitBoneTransforms, BadInput) {
  const Cylinder c = loadCylinder();
  std::vector<std::vector<Vec3>> poses = c.poses;
  poses[2].pop_back();
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, poses, c.influences, c.skeleton).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, {}, c.influences, c.skeleton).status().code(),
            StatusCode::kInvalidArgument);
  poses = c.poses;
  poses[1][7].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, poses, c.influences, c.skeleton).status().code(),
            StatusCode::kInvalidArgument);
  Skeleton three = c.skeleton;  // the weights name bone 3
  three.parents.pop_back();
  three.heads.pop_back();
  three.tails.pop_back();
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, c.poses, c.influences, three).status().code(),
            StatusCode::kInvalidArgument);
  Skeleton cycle = c.skeleton;
  cycle.parents = {1, 0, -1, 2};
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, c.poses, c.influences, cycle).status().code(),
            StatusCode::kInvalidArgument);
  Influences unnormalised = c.influences;
  unnormalised.weights[0] += 0.1;
  EXPECT_EQ(fitBoneTransforms(c.rest.positions, c.poses, unnormalised, c.skeleton).status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace odeskin

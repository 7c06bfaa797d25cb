// SPDX-License-Identifier: MIT
// glTF stores positions as float32: the writers refuse meshes whose coordinates float cannot hold,
// where they wrote infinities (and null accessor bounds) or zeros before.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/io/gltf_baked_writer.hpp"
#include "engine/io/gltf_buffer_builder.hpp"
#include "engine/io/gltf_rig_writer.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

namespace fs = std::filesystem;

// A unit square as one quad, scaled.
std::vector<Vec3> square(double scale) {
  return {Vec3(0.0), Vec3(scale, 0.0, 0.0), Vec3(scale, scale, 0.0), Vec3(0.0, scale, 0.0)};
}

FaceList quad() {
  FaceList faces;
  faces.indices = {0, 1, 2, 3};
  faces.face_offsets = {0, 4};
  return faces;
}

fs::path scratch(const std::string& name) { return odeskin::testing::scratchDir("gltf_float_range_" + name); }

void expectMessage(const Status& status, const std::string& part) {
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << status.toString();
  EXPECT_NE(status.message().find(part), std::string::npos) << status.message();
}

TEST(GltfFloatRange, PositionsFloatCanHoldPass) {
  for (const double scale : {1.0, 1e37, 1e-29}) EXPECT_TRUE(gltf::checkFloat32Positions(square(scale), "m").ok()) << scale;
  EXPECT_TRUE(gltf::checkFloat32Positions(std::vector<Vec3>(3, Vec3(1e-40)), "m").ok()) << "one point: no span to lose";
  EXPECT_TRUE(gltf::checkFloat32Positions({}, "m").ok());
}

TEST(GltfFloatRange, TooLargeOrTooSmallIsRefusedNamingTheVertexOrSpan) {
  std::vector<Vec3> far = square(1.0);
  far[2].y = -2e38;
  expectMessage(gltf::checkFloat32Positions(far, "m"), "m: vertex 2 is outside glTF's float32 range");
  expectMessage(gltf::checkFloat32Positions(square(1e-35), "m"), "m: the mesh spans 1e-35, too small for glTF's float32 positions");
}

TEST(GltfFloatRange, BakedAndRigWritersRefuseAndWriteNothing) {
  const fs::path dir = scratch("writers");
  const std::vector<std::vector<Vec3>> frames{square(1.0), square(1e50)};
  const std::vector<double> seconds{0.0, 1.0};
  expectMessage(writeBakedGlb(dir / "baked.glb", quad(), frames, seconds),
                (dir / "baked.glb").string() + ": baked glTF: frame 1: vertex 1 is outside glTF's float32 range");
  EXPECT_FALSE(fs::exists(dir / "baked.glb"));

  Rig rig;
  rig.skeleton.names = {"root"};
  rig.skeleton.parents = {-1};
  rig.skeleton.heads = {Vec3(0.0)};
  rig.skeleton.tails = {Vec3(0.0, 1.0, 0.0)};
  rig.influences.offsets = {0, 1, 2, 3, 4};
  rig.influences.bones = {0, 0, 0, 0};
  rig.influences.weights = {1.0, 1.0, 1.0, 1.0};
  ASSERT_TRUE(writeRigGlb(dir / "unit.glb", square(1.0), quad(), rig).ok());
  expectMessage(writeRigGlb(dir / "tiny.glb", square(1e-40), quad(), rig), (dir / "tiny.glb").string() + ": the mesh spans 1e-40");
  EXPECT_FALSE(fs::exists(dir / "tiny.glb"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace odeskin

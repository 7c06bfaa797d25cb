// SPDX-License-Identifier: MIT
// The PC2 point cache writer: the byte layout other tools read (checked field by field, not with a
// reader of our own), and the refusals that keep a wrong cache from being written at all.
#include "engine/io/point_cache.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "little_endian_reading.hpp"
#include "temp_dir_test.hpp"

namespace odeskin {
namespace {

class PointCache : public testing::TempDirTest {
 protected:
  PointCache() : TempDirTest("odeskin_point_cache_test_") {}

  std::string bytes(const std::string& name) const { return testing::fileBytes(dir_ / name); }
};

using testing::f32At;
using testing::u32At;

TEST_F(PointCache, WritesTheLayoutOtherToolsRead) {
  const std::vector<Vec3> first{{0.0, 1.0, 2.0}, {-3.5, 4.25, 1e-3}};
  const std::vector<Vec3> second{{0.5, 1.5, 2.5}, {-3.0, 4.0, 0.1}};
  Pc2Builder cache(2, 2);
  ASSERT_TRUE(cache.add(first).ok());
  ASSERT_TRUE(cache.add(second).ok());
  EXPECT_EQ(cache.samples(), 2u);
  ASSERT_TRUE(cache.write(dir_ / "out.pc2", 1.0, 0.5).ok());

  const std::string b = bytes("out.pc2");
  ASSERT_EQ(b.size(), kPc2HeaderBytes + std::size_t{2} * 2 * 12);
  EXPECT_EQ(std::memcmp(b.data(), "POINTCACHE2\0", 12), 0);
  EXPECT_EQ(u32At(b, 12), 1u);     // version
  EXPECT_EQ(u32At(b, 16), 2u);     // vertices
  EXPECT_EQ(f32At(b, 20), 1.0F);   // first frame
  EXPECT_EQ(f32At(b, 24), 0.5F);   // frames per sample
  EXPECT_EQ(u32At(b, 28), 2u);     // samples
  std::size_t at = kPc2HeaderBytes;
  for (const std::vector<Vec3>* frame : {&first, &second}) {
    for (const Vec3& p : *frame) {
      for (int axis = 0; axis < 3; ++axis, at += 4) EXPECT_EQ(f32At(b, at), static_cast<float>(p[axis]));
    }
  }
}

TEST_F(PointCache, RefusesFramesThatDoNotFit) {
  Pc2Builder cache(2, 1);
  const std::vector<Vec3> three(3, Vec3(0.0));
  Status s = cache.add(three);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "point cache frame 0 has 3 vertices, the cache 2");

  std::vector<Vec3> bad(2, Vec3(0.0));
  bad[1].y = std::nan("");
  s = cache.add(bad);
  EXPECT_NE(s.message().find("point cache frame 0, vertex 1: nan is not a finite float32 coordinate"),
            std::string::npos) << s.message();
  bad[1].y = 1e39;  // finite as a double, infinite as float32
  EXPECT_FALSE(cache.add(bad).ok());
  EXPECT_EQ(cache.samples(), 0u);  // a refused frame leaves nothing behind

  // Nothing added: no cache is written.
  s = cache.write(dir_ / "empty.pc2");
  EXPECT_EQ(s.message(), (dir_ / "empty.pc2").string() + ": a point cache needs at least one frame");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "empty.pc2"));

  ASSERT_TRUE(cache.add(std::vector<Vec3>(2, Vec3(1.0))).ok());
  EXPECT_NE(cache.write(dir_ / "x.pc2", 0.0, 0.0).message().find("frames per sample must be positive, got 0"),
            std::string::npos);
  EXPECT_FALSE(cache.write(dir_ / "x.pc2", std::numeric_limits<double>::infinity()).ok());
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.pc2"));
  EXPECT_TRUE(cache.write(dir_ / "x.pc2").ok());
}

TEST(Pc2Size, NamesWhatDoesNotFit) {
  EXPECT_EQ(pc2SizeProblem(10, 100), "");
  EXPECT_EQ(pc2SizeProblem(1, 0), "a point cache needs at least one vertex");
  EXPECT_EQ(pc2SizeProblem(0, 5), "a point cache needs at least one frame");
  // 4 GiB of floats is the limit: 357,913,941 frames of one vertex are 4 bytes under it.
  EXPECT_EQ(pc2SizeProblem(357913941, 1), "");
  EXPECT_NE(pc2SizeProblem(357913942, 1), "");
  EXPECT_EQ(pc2SizeProblem(1000000, 1000), "1000000 frames of 1000 vertices need 11.1759 GiB, over the 4 GiB one point cache holds");
}

}  // namespace
}  // namespace odeskin

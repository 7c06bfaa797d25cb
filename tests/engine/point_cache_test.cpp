// SPDX-License-Identifier: MIT
// The point cache writer: the PC2 and MDD byte layouts other tools read (checked field by field,
// not with a reader of our own), and the refusals that keep a wrong cache from being written at all.
#include "engine/io/point_cache.hpp"

#include <bit>
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

};

using testing::f32At;
using testing::u32At;

TEST_F(PointCache, WritesTheLayoutOtherToolsRead) {
  const std::vector<Vec3> first{{0.0, 1.0, 2.0}, {-3.5, 4.25, 1e-3}};
  const std::vector<Vec3> second{{0.5, 1.5, 2.5}, {-3.0, 4.0, 0.1}};
  PointCacheBuilder cache(PointCacheFormat::kPc2, 2, 2);
  ASSERT_TRUE(cache.add(first).ok());
  ASSERT_TRUE(cache.add(second).ok());
  EXPECT_EQ(cache.samples(), 2u);
  ASSERT_TRUE(cache.write(dir_ / "out.pc2", PointCacheTiming{30.0, 1.0}).ok());

  const std::string b = read("out.pc2");
  ASSERT_EQ(b.size(), kPc2HeaderBytes + std::size_t{2} * 2 * 12);
  EXPECT_EQ(std::memcmp(b.data(), "POINTCACHE2\0", 12), 0);
  EXPECT_EQ(u32At(b, 12), 1u);     // version
  EXPECT_EQ(u32At(b, 16), 2u);     // vertices
  EXPECT_EQ(f32At(b, 20), 1.0F);   // first frame
  EXPECT_EQ(f32At(b, 24), 1.0F);   // frames per sample
  EXPECT_EQ(u32At(b, 28), 2u);     // samples
  std::size_t at = kPc2HeaderBytes;
  for (const std::vector<Vec3>* frame : {&first, &second}) {
    for (const Vec3& p : *frame) {
      for (int axis = 0; axis < 3; ++axis, at += 4) EXPECT_EQ(f32At(b, at), static_cast<float>(p[axis]));
    }
  }
}

std::uint32_t bigEndianU32At(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<std::uint8_t>(b[at + i]);
  return v;
}
float bigEndianF32At(const std::string& b, std::size_t at) { return std::bit_cast<float>(bigEndianU32At(b, at)); }

TEST_F(PointCache, WritesMddBigEndianWithSecondsPerSample) {
  const std::vector<Vec3> first{{0.0, 1.0, 2.0}, {-3.5, 4.25, 1e-3}};
  const std::vector<Vec3> second{{0.5, 1.5, 2.5}, {-3.0, 4.0, 0.1}};
  const std::vector<Vec3> third{{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}};
  PointCacheBuilder cache(PointCacheFormat::kMdd, 2, 3);
  for (const auto* frame : {&first, &second, &third}) ASSERT_TRUE(cache.add(*frame).ok());
  ASSERT_TRUE(cache.write(dir_ / "out.mdd", PointCacheTiming{4.0, 0.0}).ok());
  const std::string b = read("out.mdd");
  ASSERT_EQ(b.size(), 8 + 3 * 4 + std::size_t{3} * 2 * 12);
  EXPECT_EQ(bigEndianU32At(b, 0), 3u);  // samples
  EXPECT_EQ(bigEndianU32At(b, 4), 2u);  // vertices
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(bigEndianF32At(b, 8 + 4 * k), static_cast<float>(k) / 4.0F);
  std::size_t at = 20;
  for (const auto* frame : {&first, &second, &third}) {
    for (const Vec3& p : *frame) {
      for (int axis = 0; axis < 3; ++axis, at += 4) EXPECT_EQ(bigEndianF32At(b, at), static_cast<float>(p[axis]));
    }
  }
  // Writing again gives the same file: the header is not left in the samples.
  ASSERT_TRUE(cache.write(dir_ / "again.mdd", PointCacheTiming{4.0, 0.0}).ok());
  EXPECT_EQ(read("again.mdd"), b);
}

TEST_F(PointCache, RefusesFramesThatDoNotFit) {
  PointCacheBuilder cache(PointCacheFormat::kPc2, 2, 1);
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
  s = cache.write(dir_ / "empty.pc2", {});
  EXPECT_EQ(s.message(), (dir_ / "empty.pc2").string() + ": a point cache needs at least one frame");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "empty.pc2"));

  ASSERT_TRUE(cache.add(std::vector<Vec3>(2, Vec3(1.0))).ok());
  EXPECT_NE(cache.write(dir_ / "x.pc2", PointCacheTiming{0.0, 0.0}).message().find("frames per second must be positive, got 0"),
            std::string::npos);
  EXPECT_NE(cache.write(dir_ / "x.pc2", PointCacheTiming{24.0, std::numeric_limits<double>::infinity()})
                .message()
                .find("the first frame inf is not a float32 number"),
            std::string::npos);
  // The frame is fine; its time is not (play --fps 1e-320).
  EXPECT_NE(cache.write(dir_ / "x.pc2", PointCacheTiming{1e-320, 0.0})
                .message()
                .find("frame 1 at 9.99988867e-321 frames per second lies at a time past float32's range"),
            std::string::npos)
      << cache.write(dir_ / "x.pc2", PointCacheTiming{1e-320, 0.0}).message();
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x.pc2"));
  EXPECT_TRUE(cache.write(dir_ / "x.pc2", {}).ok());
}

TEST(PointCacheSize, NamesWhatDoesNotFit) {
  EXPECT_EQ(pointCacheSizeProblem(10, 100), "");
  EXPECT_EQ(pointCacheSizeProblem(1, 0), "a point cache needs at least one vertex");
  EXPECT_EQ(pointCacheSizeProblem(0, 5), "a point cache needs at least one frame");
  // 4 GiB of floats is the limit: 357,913,941 frames of one vertex are 4 bytes under it.
  EXPECT_EQ(pointCacheSizeProblem(357913941, 1), "");
  EXPECT_NE(pointCacheSizeProblem(357913942, 1), "");
  EXPECT_EQ(pointCacheSizeProblem(1000000, 1000), "1000000 frames of 1000 vertices need 11.1759 GiB, over the 4 GiB one point cache holds");
}

}  // namespace
}  // namespace odeskin

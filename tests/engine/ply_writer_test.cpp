// SPDX-License-Identifier: MIT
// The PLY writer: the header MeshLab and Blender parse, the binary records after it, and the
// refusals that keep a broken mesh from being written.
#include "engine/io/ply_writer.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "little_endian_reading.hpp"
#include "temp_dir_test.hpp"

namespace odeskin {
namespace {

class PlyWriter : public testing::TempDirTest {
 protected:
  PlyWriter() : TempDirTest("odeskin_ply_writer_test_") {}

};

using testing::f32At;
using testing::u32At;

FaceList quadAndTriangle() {
  FaceList faces;
  faces.indices = {0, 1, 2, 3, 0, 2, 4};
  faces.face_offsets = {0, 4, 7};
  return faces;
}

const std::vector<Vec3> kPositions{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 2.25}};

TEST_F(PlyWriter, WritesColoursQualityAndFaces) {
  const std::vector<std::array<std::uint8_t, 3>> colours{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}, {255, 0, 128}};
  const std::vector<float> quality{0.0F, 0.25F, 0.5F, 0.75F, 1.0F};
  ASSERT_TRUE(writePly(dir_ / "m.ply", kPositions, quadAndTriangle(), {colours, quality}, "made by a test").ok());
  const std::string b = read("m.ply");
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment made by a test\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
      "property float quality\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  ASSERT_EQ(b.substr(0, header.size()), header);
  std::size_t at = header.size();
  for (std::size_t i = 0; i < kPositions.size(); ++i, at += 19) {
    EXPECT_EQ(f32At(b, at), static_cast<float>(kPositions[i].x));
    EXPECT_EQ(f32At(b, at + 4), static_cast<float>(kPositions[i].y));
    EXPECT_EQ(f32At(b, at + 8), static_cast<float>(kPositions[i].z));
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(static_cast<std::uint8_t>(b[at + 12 + c]), colours[i][c]);
    EXPECT_EQ(f32At(b, at + 15), quality[i]);
  }
  EXPECT_EQ(static_cast<std::uint8_t>(b[at]), 4);  // the quad
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(u32At(b, at + 1 + 4 * k), k);
  at += 17;
  EXPECT_EQ(static_cast<std::uint8_t>(b[at]), 3);
  EXPECT_EQ(u32At(b, at + 9), 4u);
  EXPECT_EQ(b.size(), at + 13);
}

TEST_F(PlyWriter, PositionsOnly) {
  ASSERT_TRUE(writePly(dir_ / "m.ply", kPositions, quadAndTriangle()).ok());
  const std::string b = read("m.ply");
  EXPECT_EQ(b.find("red"), std::string::npos);
  EXPECT_EQ(b.find("quality"), std::string::npos);
  EXPECT_EQ(b.find("comment"), std::string::npos);
  EXPECT_EQ(b.size(), b.find("end_header\n") + 11 + std::size_t{5} * 12 + 17 + 13);
}

TEST_F(PlyWriter, RefusesWhatItCannotWrite) {
  const std::string out = (dir_ / "m.ply").string();
  const std::vector<std::array<std::uint8_t, 3>> two_colours(2);
  EXPECT_EQ(writePly(out, kPositions, quadAndTriangle(), {two_colours, {}}).message(), out + ": 2 colours for 5 vertices");
  const std::vector<float> one_quality(1);
  EXPECT_EQ(writePly(out, kPositions, quadAndTriangle(), {{}, one_quality}).message(),
            out + ": 1 quality values for 5 vertices");
  FaceList faces = quadAndTriangle();
  faces.indices[6] = 5;
  EXPECT_EQ(writePly(out, kPositions, faces).message(), out + ": face 1 names vertex 5 of 5");
  faces = quadAndTriangle();
  faces.face_offsets = {0, 2, 7};
  EXPECT_EQ(writePly(out, kPositions, faces).message(), out + ": face 0 has 2 corners (PLY here takes 3 to 255)");
  std::vector<Vec3> bad = kPositions;
  bad[3].z = std::nan("");
  EXPECT_EQ(writePly(out, bad, quadAndTriangle()).message(), out + ": vertex 3: nan is not a finite float32 coordinate");
  EXPECT_EQ(writePly(out, kPositions, quadAndTriangle(), {}, "two\nlines").message(), out + ": the comment has a line break");
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace odeskin

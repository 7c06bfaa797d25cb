// SPDX-License-Identifier: MIT
#include "engine/io/obj_reader.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "temp_dir_test.hpp"

#include "engine/io/obj_io.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;

const fs::path kData = ODESKIN_DATA_DIR;

std::string slurp(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

std::vector<std::uint32_t> face(const FaceList& faces, std::size_t f) {
  return std::vector<std::uint32_t>(faces.indices.begin() + faces.face_offsets[f],
                                    faces.indices.begin() + faces.face_offsets[f + 1]);
}

class ObjTempDir : public testing::TempDirTest {
 protected:
  ObjTempDir() : TempDirTest("odeskin_obj_reader_test_") {}

  // Expects readObj(text) to fail with `code` and a message containing `path` and `needle`.
  void expectError(const std::string& text, StatusCode code, const std::string& needle) const {
    const fs::path path = write("bad.obj", text);
    const Result<ObjMesh> mesh = readObj(path);
    ASSERT_FALSE(mesh.ok()) << text;
    EXPECT_EQ(mesh.status().code(), code) << mesh.status().toString();
    EXPECT_NE(mesh.status().message().find(path.string()), std::string::npos) << mesh.status().message();
    EXPECT_NE(mesh.status().message().find(needle), std::string::npos) << mesh.status().message();
  }
};

void expectTriangles(const ObjMesh& mesh, std::size_t vertices, std::size_t faces) {
  EXPECT_EQ(mesh.positions.size(), vertices);
  ASSERT_EQ(mesh.faces.faceCount(), faces);
  for (std::size_t f = 0; f < faces; ++f) ASSERT_EQ(mesh.faces.face_offsets[f + 1] - mesh.faces.face_offsets[f], 3u);
  for (std::uint32_t i : mesh.faces.indices) ASSERT_LT(i, vertices);
}

TEST(ReadObj, CatReferenceWithCrlfLineEndings) {
  const fs::path path = kData / "cat-poses/cat-00.obj";
  ASSERT_NE(slurp(path).find("\r\n"), std::string::npos) << "the data quirk this test covers is gone";
  const Result<ObjMesh> mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 7207, 14410);
  EXPECT_EQ(mesh->positions[0], Vec3(0.0334364212, 0.5303362761, -0.4207956109));
  EXPECT_EQ(face(mesh->faces, 0), (std::vector<std::uint32_t>{7206, 0, 1}));
}

TEST(ReadObj, CatPoseWithExponentNotation) {
  const Result<ObjMesh> mesh = readObj(kData / "cat-poses/cat-01.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 7207, 14410);
  EXPECT_EQ(mesh->positions[196], Vec3(3.93978e-05, 0.073814242, -0.3751113886));  // line 197
}

TEST(ReadObj, HorseFirstFrame) {
  const Result<ObjMesh> mesh = readObj(kData / "horse-gallop/horse-01.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 8431, 16843);
  EXPECT_EQ(mesh->positions[0], Vec3(-0.022739015899999999, 0.97907069999999996, -0.63614849900000003));
  EXPECT_EQ(mesh->positions[4228], Vec3(-4.84786e-05, 0.95982354250000002, 0.62491002929999995));
}

TEST(ReadObj, CylinderRestWithTexcoordCornersAndNoVt) {
  const fs::path path = kData / "cylinder/cylinder.obj";
  ASSERT_NE(slurp(path).find("f 1/1 2/2 21/22"), std::string::npos);
  const Result<ObjMesh> mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 420, 800);
  EXPECT_EQ(mesh->positions[0], Vec3(2.0, 0.475529, -0.154509));
  EXPECT_EQ(face(mesh->faces, 0), (std::vector<std::uint32_t>{0, 1, 20}));
  EXPECT_EQ(face(mesh->faces, 1), (std::vector<std::uint32_t>{20, 1, 21}));
  // The posed files write the same faces as plain `f i j k`.
  const Result<ObjMesh> posed = readObj(kData / "cylinder/poses-1/cylinder-1.obj");
  ASSERT_TRUE(posed.ok()) << posed.status().toString();
  EXPECT_EQ(posed->faces.indices, mesh->faces.indices);
  EXPECT_EQ(posed->faces.face_offsets, mesh->faces.face_offsets);
}

TEST(ReadObj, CheburashkaWithoutFinalNewline) {
  const fs::path path = kData / "cheburashka/cheburashka.obj";
  const std::string text = slurp(path);
  ASSERT_FALSE(text.empty());
  ASSERT_NE(text.back(), '\n') << "the data quirk this test covers is gone";
  const Result<ObjMesh> mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 6669, 13334);
  EXPECT_EQ(mesh->positions[6668], Vec3(0.515443, 0.161067, 0.585582));
  EXPECT_EQ(face(mesh->faces, 13333), (std::vector<std::uint32_t>{2, 1, 0}));  // the unterminated "f 3 2 1"
}

TEST(ReadObj, FaceReferenceFirstFile) {
  const Result<ObjMesh> mesh = readObj(kData / "face-poses/face-00.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  expectTriangles(*mesh, 29299, 57836);
}

TEST_F(ObjTempDir, QuadsAndMixedPolygons) {
  const Result<ObjMesh> mesh = readObj(write("mixed.obj",
                                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 3 0.5 0\n"
                                             "f 1 2 3 4\nf 2 5 6 3\nf 5 7 6\nf 1 2 5 7 6 3\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  EXPECT_EQ(mesh->positions.size(), 7u);
  EXPECT_EQ(mesh->faces.face_offsets, (std::vector<std::uint32_t>{0, 4, 8, 11, 17}));
  EXPECT_EQ(face(mesh->faces, 1), (std::vector<std::uint32_t>{1, 4, 5, 2}));
  EXPECT_EQ(face(mesh->faces, 3), (std::vector<std::uint32_t>{0, 1, 4, 6, 5, 2}));
}

TEST_F(ObjTempDir, NegativeIndicesCountBackFromVerticesReadSoFar) {
  const Result<ObjMesh> mesh =
      readObj(write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3 -1 -2\nf 2 -1 3\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  EXPECT_EQ(face(mesh->faces, 0), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(face(mesh->faces, 1), (std::vector<std::uint32_t>{1, 3, 2}));
  EXPECT_EQ(face(mesh->faces, 2), (std::vector<std::uint32_t>{1, 3, 2}));
}

TEST_F(ObjTempDir, CommentsAndOtherStatementsAreSkipped) {
  const Result<ObjMesh> mesh = readObj(write("extras.obj",
                                             "# exported by hand\r\nmtllib a.mtl\r\no thing\r\ng part\r\n"
                                             "v 0 0 0 # origin\r\nv 1e0 0 0 1.0\r\n\tv  0 +1 0 \r\n"
                                             "vt 0 0\r\nvt 1 0\r\nvn 0 0 1\r\nusemtl skin\r\ns 1\r\n"
                                             "f 1/1/1 2/2/1 3//1 # one\r\n\r\n# f 9 9 9\r\nl 1 2\r\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  ASSERT_EQ(mesh->positions.size(), 3u);
  EXPECT_EQ(mesh->positions[1], Vec3(1.0, 0.0, 0.0));
  EXPECT_EQ(mesh->positions[2], Vec3(0.0, 1.0, 0.0));
  ASSERT_EQ(mesh->faces.faceCount(), 1u);
  EXPECT_EQ(face(mesh->faces, 0), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST_F(ObjTempDir, MalformedFilesNamePathAndLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectError("v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n", StatusCode::kParseError, ":2: ");
  expectError("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", StatusCode::kParseError, ":2: ");
  expectError("v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", StatusCode::kParseError, ":2: ");
  expectError("v 0 0 0\nv 1 0 1e999\nv 0 1 0\nf 1 2 3\n", StatusCode::kParseError, ":2: ");
  expectError(tri + "f 1 2 x\n", StatusCode::kParseError, ":4: ");
  expectError(tri + "f 0 1 2\n", StatusCode::kParseError, ":4: bad face index '0'");
  expectError(tri + "f 1 2 3\nf 1 2 4\n", StatusCode::kParseError, ":5: face index 4 > vertex count 3");
  expectError(tri + "f 1 -4 3\n", StatusCode::kParseError, ":4: face index '-4' points before the first vertex");
  expectError(tri + "f 1 2\n", StatusCode::kParseError, ":4: face has 2 corners");
  expectError("", StatusCode::kParseError, "no vertices");
  expectError("# nothing\n", StatusCode::kParseError, "no vertices");
  expectError(tri, StatusCode::kParseError, "no faces");
}

// A square of two triangles with a UV seam at its corner 3 (1-based), which takes vt 3 in the first
// face and vt 5 (written -1) in the second; every corner names the one normal.
const std::string kSeamSquare =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0.25\n"
    "vn 0 0 2\n"
    "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/-1/-1 4/4/1\n";

TEST_F(ObjTempDir, TexcoordsAndNormalsArePerCorner) {
  const Result<ObjMesh> mesh = readObj(write("square.obj", kSeamSquare));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  EXPECT_EQ(mesh->texcoords.size(), 5u);
  EXPECT_EQ(mesh->texcoords[4], Vec2(1.0, 0.25));
  EXPECT_EQ(mesh->corner_texcoords, (std::vector<std::uint32_t>{0, 1, 2, 0, 4, 3}));
  EXPECT_EQ(mesh->normals, std::vector<Vec3>{Vec3(0.0, 0.0, 2.0)});
  EXPECT_EQ(mesh->corner_normals, (std::vector<std::uint32_t>(6, 0)));
  EXPECT_TRUE(mesh->texcoord_warning.empty() && mesh->normal_warning.empty());
  EXPECT_EQ(face(mesh->faces, 1), (std::vector<std::uint32_t>{0, 2, 3}));
}

// Render vertices are the distinct (v, vt, vn) corners in first-use order; UVs turn to run down the
// image as RenderLayout's do; the render faces map back onto the topology faces.
TEST_F(ObjTempDir, RenderLayoutSplitsVerticesAtUvSeams) {
  const Result<ObjMesh> mesh = readObj(write("square.obj", kSeamSquare));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  const RenderLayout layout = objRenderLayout(*mesh);
  EXPECT_TRUE(layout.obj_order);
  EXPECT_EQ(layout.topology_of_render, (std::vector<std::uint32_t>{0, 1, 2, 2, 3}));
  EXPECT_EQ(layout.faces.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 3, 4}));
  EXPECT_EQ(layout.faces.face_offsets, mesh->faces.face_offsets);
  for (std::size_t k = 0; k < layout.faces.indices.size(); ++k) {
    EXPECT_EQ(layout.topology_of_render[layout.faces.indices[k]], mesh->faces.indices[k]) << "corner " << k;
  }
  EXPECT_EQ(layout.uvs, (std::vector<Vec2>{{0.0, 1.0}, {0.5, 1.0}, {0.5, 0.0}, {1.0, 0.75}, {0.0, 0.0}}));
  EXPECT_EQ(layout.normals, std::vector<Vec3>(5, Vec3(0.0, 0.0, 2.0)));

  // Without vt and vn there is nothing to lay out.
  const Result<ObjMesh> plain = readObj(write("plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(objRenderLayout(*plain).empty());
  EXPECT_FALSE(objRenderLayout(*plain).obj_order);
}

// A broken texture mapping or normal set drops only itself, with a warning naming the file and
// the line; the positions and faces still read. Corners naming a `vt` in a file without any (the
// data's cylinder) drop them silently: there is nothing to lose.
TEST_F(ObjTempDir, BrokenTexcoordsOrNormalsAreDroppedWithAWarning) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n";
  auto warnings = [&](const std::string& text) {
    const fs::path path = write("w.obj", text);
    const Result<ObjMesh> mesh = readObj(path);
    EXPECT_TRUE(mesh.ok()) << mesh.status().toString();
    if (!mesh.ok()) return std::string();
    EXPECT_EQ(mesh->faces.faceCount(), 1u);
    EXPECT_EQ(mesh->texcoords.empty(), mesh->corner_texcoords.empty());
    EXPECT_EQ(mesh->normals.empty(), mesh->corner_normals.empty());
    std::string all;
    for (const std::string& w : objLayoutWarnings(*mesh)) {
      EXPECT_NE(w.find(path.string()), std::string::npos) << w;
      all += w + "\n";
    }
    return all;
  };
  EXPECT_EQ(warnings(tri + "f 1/1/1 2/2/1 3/3/1\n"), "");
  EXPECT_NE(warnings(tri + "f 1/1 2/2 3\n").find("texture coordinates (vt) are not kept: " + (dir_ / "w.obj").string() +
                                                  ": 2 of 3 face corners name a `vt`; all or none must"),
            std::string::npos);
  EXPECT_NE(warnings(tri + "f 1/1 2/2 3/4\n").find("w.obj:8: texture coordinate index '4', but only 3 `vt` lines come before it"), std::string::npos);
  EXPECT_NE(warnings(tri + "f 1/1 2/x 3/3\n").find("w.obj:8: texture coordinate index 'x' is not an index (a whole number other than 0)"), std::string::npos);
  EXPECT_NE(warnings(tri + "f 1/1 2/2 3/99999999999999999999\n").find("index '99999999999999999999' is not an index"),
            std::string::npos);
  EXPECT_NE(warnings(tri + "f 1/-4 2/2 3/3\n").find("texture coordinate index '-4' points before the first `vt`"), std::string::npos);
  EXPECT_NE(warnings("vt 0 nan\n" + tri + "f 1/1 2/2 3/3\n").find("w.obj:1: `vt` needs finite coordinates"),
            std::string::npos);
  EXPECT_NE(warnings(tri + "vn 0 0 0\nf 1//1 2//2 3//1\n").find("normals (vn) are not kept: " + (dir_ / "w.obj").string() +
                                                               ": normal 2 is zero"),
            std::string::npos);
  EXPECT_NE(warnings(tri + "f 1 2 3\n").find("3 `vt` lines, but no face names one"), std::string::npos);
  const std::string only_texcoords = warnings(tri + "f 1/1 2/2 3/3\n");  // the unused vn line is reported too
  EXPECT_NE(only_texcoords.find("1 `vn` line, but no face names one"), std::string::npos);
  EXPECT_EQ(only_texcoords.find("texture coordinates"), std::string::npos);
  EXPECT_EQ(warnings("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\n"), "");
}

TEST(ReadObj, MissingFileIsAnIoError) {
  const fs::path path = fs::temp_directory_path() / "odeskin_obj_reader_test_no_such_dir/none.obj";
  const Result<ObjMesh> mesh = readObj(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.status().code(), StatusCode::kIoError);
  EXPECT_NE(mesh.status().message().find(path.string()), std::string::npos);
}

TEST(ParseObj, TextInMemoryReadsAsTheFileAndErrorsNameTheSource) {
  const fs::path path = kData / "cylinder/cylinder.obj";
  const Result<ObjMesh> from_file = readObj(path);
  const Result<ObjMesh> from_text = parseObj(slurp(path), "cylinder in memory");
  ASSERT_TRUE(from_file.ok() && from_text.ok());
  EXPECT_EQ(from_text->positions, from_file->positions);
  EXPECT_EQ(from_text->faces.indices, from_file->faces.indices);
  const Result<ObjMesh> bad = parseObj("v 0 0 0\nf 1 2 x\n", "memory.obj");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "memory.obj:2: bad face index 'x'");
}

// Line ends and a byte order mark change nothing: CR-only lines read as one line ("no faces"), and
// a UTF-8 BOM hid the first vertex, so every face named the wrong vertices. Errors still name the
// right line.
TEST(ParseObj, CrOnlyLinesAndAByteOrderMarkReadAsPlainLf) {
  const fs::path path = kData / "cylinder/cylinder.obj";
  std::string lf = slurp(path);
  std::erase(lf, '\r');
  const Result<ObjMesh> plain = parseObj(lf, "lf.obj");
  ASSERT_TRUE(plain.ok()) << plain.status().toString();
  std::string cr = lf;
  std::replace(cr.begin(), cr.end(), '\n', '\r');
  std::string crlf;
  for (const char c : lf) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const auto& [text, name] : {std::pair{cr, "cr.obj"}, std::pair{crlf, "crlf.obj"}, std::pair{"\xEF\xBB\xBF" + lf, "bom.obj"},
                                   std::pair{"\xEF\xBB\xBF" + cr, "bom-cr.obj"}}) {
    const Result<ObjMesh> mesh = parseObj(text, name);
    ASSERT_TRUE(mesh.ok()) << name << ": " << mesh.status().toString();
    EXPECT_EQ(mesh->positions, plain->positions) << name;
    EXPECT_EQ(mesh->faces.indices, plain->faces.indices) << name;
  }
  const Result<ObjMesh> bad = parseObj("\xEF\xBB\xBFv 0 0 0\rv 1 0 0\r\nv 0 1 0\rf 1 2 x\r", "memory.obj");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "memory.obj:4: bad face index 'x'");
}

// --- readObjSequence ---

TEST(ReadObjSequence, AllTenCatPosesShareOneTopology) {
  std::vector<fs::path> paths;
  paths.reserve(10);
  for (int k = 0; k < 10; ++k) paths.push_back(kData / ("cat-poses/cat-0" + std::to_string(k) + ".obj"));
  const Result<ExampleSet> set = readObjSequence(paths);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  ASSERT_EQ(set->poses.size(), 10u);
  ASSERT_EQ(set->pose_labels.size(), 10u);
  const Result<ObjMesh> first = readObj(paths[0]);
  const Result<ObjMesh> last = readObj(paths[9]);
  ASSERT_TRUE(first.ok() && last.ok());
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(set->pose_labels[static_cast<std::size_t>(k)], "cat-0" + std::to_string(k) + ".obj");
    EXPECT_EQ(set->poses[static_cast<std::size_t>(k)].size(), 7207u);
  }
  EXPECT_EQ(set->poses[0], first->positions);
  EXPECT_EQ(set->poses[9], last->positions);
  EXPECT_EQ(set->rest_positions, first->positions);  // no bind file: X = pose 0
  EXPECT_EQ(set->faces.indices, first->faces.indices);
  EXPECT_EQ(set->faces.face_offsets, first->faces.face_offsets);
  EXPECT_FALSE(set->rig.has_value());
  EXPECT_TRUE(set->render.empty());
}

TEST(ReadObjSequence, BindMeshBecomesTheRestPositions) {
  std::vector<fs::path> paths;
  for (int k = 1; k <= 4; ++k) paths.push_back(kData / ("cylinder/poses-1/cylinder-" + std::to_string(k) + ".obj"));
  const fs::path bind = kData / "cylinder/cylinder.obj";  // `a/t` faces, same topology as the plain posed ones
  const Result<ExampleSet> set = readObjSequence(paths, &bind);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  const Result<ObjMesh> rest = readObj(bind);
  const Result<ObjMesh> pose0 = readObj(paths[0]);
  ASSERT_TRUE(rest.ok() && pose0.ok());
  EXPECT_EQ(set->rest_positions, rest->positions);
  EXPECT_EQ(set->poses[0], pose0->positions);
  EXPECT_NE(set->rest_positions, set->poses[0]);
  EXPECT_EQ(set->pose_labels,
            (std::vector<std::string>{"cylinder-1.obj", "cylinder-2.obj", "cylinder-3.obj", "cylinder-4.obj"}));
}

// The first pose's `vt` and `vn` (or the bind mesh's) make the render layout, with their warnings.
TEST_F(ObjTempDir, SequenceTakesTheBindMeshsOrFirstPosesTexcoords) {
  std::string moved = kSeamSquare;
  moved.replace(moved.find("v 1 1 0"), 7, "v 1 1 1");
  const std::vector<fs::path> poses{write("a.obj", kSeamSquare), write("b.obj", moved)};
  Result<ExampleSet> set = readObjSequence(poses);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  EXPECT_TRUE(set->render.obj_order);
  EXPECT_EQ(set->render.topology_of_render, (std::vector<std::uint32_t>{0, 1, 2, 2, 3}));
  EXPECT_EQ(set->render.uvs.size(), 5u);
  EXPECT_TRUE(set->warnings.empty());

  std::string partial = kSeamSquare;
  partial.replace(partial.find("4/4/1"), 5, "4");
  const std::vector<fs::path> broken{write("c.obj", partial), write("b.obj", moved)};
  set = readObjSequence(broken);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  EXPECT_TRUE(set->render.uvs.empty());
  ASSERT_EQ(set->warnings.size(), 2u);
  EXPECT_NE(set->warnings[0].find("texture coordinates (vt) are not kept: " + (dir_ / "c.obj").string() +
                                  ": 5 of 6 face corners name a `vt`"),
            std::string::npos)
      << set->warnings[0];
  EXPECT_NE(set->warnings[1].find("normals (vn) are not kept"), std::string::npos) << set->warnings[1];

  // A bind mesh with texture coordinates gives them to poses without (a simulation's output).
  const fs::path bind = write("rest.obj", kSeamSquare);
  const std::vector<fs::path> bare{write("d.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"), poses[1]};
  set = readObjSequence(bare, &bind);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  EXPECT_EQ(set->render.topology_of_render, (std::vector<std::uint32_t>{0, 1, 2, 2, 3}));
  EXPECT_TRUE(set->warnings.empty());
  // ... and a bind mesh without them leaves the first pose's.
  const fs::path plain_bind = bare[0];
  set = readObjSequence(poses, &plain_bind);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  EXPECT_EQ(set->render.uvs.size(), 5u);
}

// Poses written from the cylinder, then edited one way or another.
class ObjSequenceTempDir : public ObjTempDir {
 protected:
  void SetUp() override {
    ObjTempDir::SetUp();
    const Result<ObjMesh> a = readObj(kData / "cylinder/poses-1/cylinder-1.obj");
    const Result<ObjMesh> b = readObj(kData / "cylinder/poses-1/cylinder-2.obj");
    ASSERT_TRUE(a.ok() && b.ok());
    a_ = *a;
    b_ = *b;
  }
  fs::path save(const std::string& name, const ObjMesh& mesh) const {
    fs::path path = dir_ / name;
    EXPECT_TRUE(writeObj(path, mesh.positions, mesh.faces).ok());
    return path;
  }
  std::string errorOf(const std::vector<fs::path>& poses, const fs::path* bind = nullptr) const {
    const Result<ExampleSet> set = readObjSequence(poses, bind);
    EXPECT_FALSE(set.ok());
    if (set.ok()) return {};
    EXPECT_EQ(set.status().code(), StatusCode::kInvalidArgument) << set.status().toString();
    return set.status().message();
  }

  ObjMesh a_, b_;
};

TEST_F(ObjSequenceTempDir, WrittenCopiesRoundTrip) {
  const std::vector<fs::path> paths{save("pose-a.obj", a_), save("pose-b.obj", b_)};
  const Result<ExampleSet> set = readObjSequence(paths);
  ASSERT_TRUE(set.ok()) << set.status().toString();
  EXPECT_EQ(set->poses[1].size(), 420u);
}

// Texture coordinates go out as `vt` (v flipped from glTF's downward to OBJ's upward) with faces
// `f i/i`, and the file reads back as the same mesh.
TEST_F(ObjSequenceTempDir, TexcoordsAreWrittenAsVtAndReadBack) {
  std::vector<Vec2> uvs;
  for (std::size_t i = 0; i < a_.positions.size(); ++i) uvs.emplace_back(static_cast<double>(i) / 512.0, 0.25);
  const fs::path path = dir_ / "textured.obj";
  ASSERT_TRUE(writeObj(path, a_.positions, a_.faces, "frame 0", uvs).ok());
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nvt 0 0.75\nvt 0.001953125 0.75\n"), std::string::npos);
  const std::uint32_t first = a_.faces.indices[0] + 1;
  EXPECT_NE(text.find("\nf " + std::to_string(first) + "/" + std::to_string(first) + " "), std::string::npos);
  const Result<ObjMesh> back = readObj(path);
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->positions, a_.positions);
  EXPECT_EQ(back->faces.indices, a_.faces.indices);
  EXPECT_EQ(back->faces.face_offsets, a_.faces.face_offsets);

  uvs.pop_back();
  const Status wrong = writeObj(dir_ / "wrong.obj", a_.positions, a_.faces, {}, uvs);
  EXPECT_NE(wrong.message().find("419 texture coordinates for 420 vertices"), std::string::npos) << wrong.message();
  EXPECT_FALSE(fs::exists(dir_ / "wrong.obj"));
}

// An OBJ input's layout goes back out with its `v` lines in the input's order and each corner naming
// its own `vt`: the written file reads back as the mesh and layout it came from.
TEST_F(ObjTempDir, CornerTexcoordsKeepThePositionsOrder) {
  const Result<ObjMesh> mesh = readObj(write("square.obj", kSeamSquare));
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  const RenderLayout layout = objRenderLayout(*mesh);
  const fs::path path = dir_ / "out.obj";
  ASSERT_TRUE(writeObj(path, mesh->positions, layout.faces, {}, layout.uvs, layout.topology_of_render).ok());
  EXPECT_NE(slurp(path).find("f 1/1 2/2 3/3\nf 1/1 3/4 4/5\n"), std::string::npos) << slurp(path);
  const Result<ObjMesh> back = readObj(path);
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->positions, mesh->positions);
  EXPECT_EQ(back->faces.indices, mesh->faces.indices);
  const RenderLayout again = objRenderLayout(*back);
  EXPECT_EQ(again.topology_of_render, layout.topology_of_render);
  EXPECT_EQ(again.uvs, layout.uvs);

  // Without UVs (a layout of normals only) the faces are the topology's.
  ASSERT_TRUE(writeObj(path, mesh->positions, layout.faces, {}, {}, layout.topology_of_render).ok());
  EXPECT_NE(slurp(path).find("f 1 2 3\nf 1 3 4\n"), std::string::npos) << slurp(path);

  const fs::path refused = dir_ / "refused.obj";
  std::vector<std::uint32_t> wrong = layout.topology_of_render;
  wrong[2] = 4;
  Status s = writeObj(refused, mesh->positions, layout.faces, {}, layout.uvs, wrong);
  EXPECT_NE(s.message().find("refused.obj: texture coordinate 2 belongs to vertex 4 of 4"), std::string::npos) << s.message();
  s = writeObj(refused, mesh->positions, layout.faces, {}, std::span(layout.uvs).first(4), layout.topology_of_render);
  EXPECT_NE(s.message().find("refused.obj: 4 texture coordinates for 5 corner vertices"), std::string::npos) << s.message();
  EXPECT_FALSE(fs::exists(refused));
}

// Output that a reader would take for a mesh it is not: a NaN position or texture coordinate, or
// a face past the vertices, is refused by name, and nothing is left at the path.
TEST_F(ObjSequenceTempDir, WriterRefusesNonFiniteValuesAndFacesPastTheVertices) {
  auto expectRefused = [&](const Status& s, const std::string& message, const fs::path& path) {
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.toString();
    EXPECT_NE(s.message().find(message), std::string::npos) << s.message();
    EXPECT_FALSE(fs::exists(path)) << path;
  };
  std::vector<Vec3> positions = a_.positions;
  positions[7].y = std::numeric_limits<double>::quiet_NaN();
  expectRefused(writeObj(dir_ / "nan.obj", positions, a_.faces), "nan.obj: vertex 7 is not finite", dir_ / "nan.obj");

  std::vector<Vec2> uvs(a_.positions.size(), Vec2(0.5));
  uvs[3].x = std::numeric_limits<double>::infinity();
  expectRefused(writeObj(dir_ / "uv.obj", a_.positions, a_.faces, {}, uvs), "uv.obj: texture coordinate 3 is not finite",
                dir_ / "uv.obj");

  FaceList faces = a_.faces;
  faces.indices[faces.face_offsets[5] + 1] = 420;
  expectRefused(writeObj(dir_ / "face.obj", a_.positions, faces), "face.obj: face 5 references vertex 420 of 420",
                dir_ / "face.obj");
}

TEST_F(ObjSequenceTempDir, ChangedFaceIndexNamesFileFaceAndBothVersions) {
  ObjMesh bad = b_;
  // Face 17 (1-based): give it another third corner.
  const std::uint32_t k = bad.faces.face_offsets[16] + 2;
  const std::string expected_a =
      std::to_string(a_.faces.indices[k - 2] + 1) + " " + std::to_string(a_.faces.indices[k - 1] + 1) + " ";
  bad.faces.indices[k] = (bad.faces.indices[k] + 7) % 420;
  const std::vector<fs::path> paths{save("pose-a.obj", a_), save("pose-a2.obj", a_), save("pose-b.obj", bad),
                                    save("pose-c.obj", bad)};
  const std::string message = errorOf(paths);
  const std::string want = "pose-b.obj: face 17 is " + expected_a + std::to_string(bad.faces.indices[k] + 1) +
                           " but pose-a.obj has " + expected_a + std::to_string(a_.faces.indices[k] + 1);
  EXPECT_EQ(message, want);
}

TEST_F(ObjSequenceTempDir, SwappedCornersAreADifferentFace) {
  ObjMesh bad = b_;
  std::swap(bad.faces.indices[bad.faces.face_offsets[4]], bad.faces.indices[bad.faces.face_offsets[4] + 1]);
  const std::string message = errorOf({save("pose-a.obj", a_), save("pose-b.obj", bad)});
  EXPECT_EQ(message.rfind("pose-b.obj: face 5 is ", 0), 0u) << message;
}

TEST_F(ObjSequenceTempDir, DroppedOrExtraVertexNamesFileAndBothCounts) {
  // Drop the last vertex and the faces that use it, so the file itself stays valid.
  ObjMesh dropped;
  dropped.positions.assign(b_.positions.begin(), b_.positions.end() - 1);
  for (std::size_t f = 0; f < b_.faces.faceCount(); ++f) {
    const std::vector<std::uint32_t> corners = face(b_.faces, f);
    if (std::find(corners.begin(), corners.end(), 419u) != corners.end()) continue;
    dropped.faces.indices.insert(dropped.faces.indices.end(), corners.begin(), corners.end());
    dropped.faces.face_offsets.push_back(static_cast<std::uint32_t>(dropped.faces.indices.size()));
  }
  EXPECT_EQ(errorOf({save("pose-a.obj", a_), save("pose-b.obj", dropped)}),
            "pose-b.obj: 419 vertices but pose-a.obj has 420");
  ObjMesh extra = b_;
  extra.positions.push_back(Vec3(9.0));
  EXPECT_EQ(errorOf({save("pose-a.obj", a_), save("pose-b.obj", extra)}),
            "pose-b.obj: 421 vertices but pose-a.obj has 420");
}

TEST_F(ObjSequenceTempDir, MissingTrailingFacesNameBothFaceCounts) {
  ObjMesh fewer = b_;
  fewer.faces.face_offsets.pop_back();
  fewer.faces.indices.resize(fewer.faces.face_offsets.back());
  EXPECT_EQ(errorOf({save("pose-a.obj", a_), save("pose-b.obj", fewer)}),
            "pose-b.obj: 799 faces but pose-a.obj has 800");
}

TEST_F(ObjSequenceTempDir, BindMeshWithOtherTopologyIsNamed) {
  ObjMesh bad = b_;
  std::swap(bad.faces.indices[0], bad.faces.indices[1]);
  const fs::path bind = save("rest.obj", bad);
  const std::string message = errorOf({save("pose-a.obj", a_), save("pose-b.obj", b_)}, &bind);
  EXPECT_EQ(message.rfind("rest.obj: face 1 is ", 0), 0u) << message;
  EXPECT_NE(message.find("but pose-a.obj has"), std::string::npos) << message;
}

TEST_F(ObjSequenceTempDir, FewerThanTwoPosesIsInvalid) {
  EXPECT_NE(errorOf({save("pose-a.obj", a_)}).find("at least 2"), std::string::npos);
  EXPECT_NE(errorOf({}).find("at least 2"), std::string::npos);
}

TEST_F(ObjSequenceTempDir, ReaderErrorsPassThrough) {
  const std::vector<fs::path> paths{save("pose-a.obj", a_), dir_ / "missing.obj"};
  const Result<ExampleSet> set = readObjSequence(paths);
  ASSERT_FALSE(set.ok());
  EXPECT_EQ(set.status().code(), StatusCode::kIoError);
  EXPECT_NE(set.status().message().find("missing.obj"), std::string::npos);
}

TEST_F(ObjSequenceTempDir, NonManifoldFaceIsNamed) {
  // Three triangles on the edge 1-2: the third cannot be added to a half-edge mesh.
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  const std::vector<fs::path> paths{write("fan-1.obj", text), write("fan-2.obj", text)};
  const std::string message = errorOf(paths);
  EXPECT_EQ(message.rfind("fan-1.obj: face 3 ", 0), 0u) << message;
  EXPECT_NE(message.find("non-manifold"), std::string::npos) << message;
}

}  // namespace
}  // namespace odeskin

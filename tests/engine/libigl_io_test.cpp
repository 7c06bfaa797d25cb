// SPDX-License-Identifier: MIT
#include "engine/io/libigl_io.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "engine/core/json_path.hpp"
#include "temp_dir_test.hpp"

#include "engine/io/obj_reader.hpp"
#include "engine/kernels/lbs_job.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;

const fs::path kData = ODESKIN_DATA_DIR;

// The posed files of ../shared/data with their .Tmat and .json (README: 8 + 16 = 24 poses).
struct PoseFiles {
  fs::path obj, tmat, json;
};
std::vector<PoseFiles> posesOf(const std::string& model) {
  std::vector<std::string> stems;
  if (model == "cylinder") {
    for (int set = 1; set <= 2; ++set) {
      for (int k = 1; k <= 4; ++k) stems.push_back("poses-" + std::to_string(set) + "/cylinder-" + std::to_string(k));
    }
  } else {
    stems.push_back("poses-1/cheburashka-1");
    for (int k = 1; k <= 11; ++k)
      stems.push_back(std::string("poses-2/cheburashka-") + (k < 10 ? "0" : "") + std::to_string(k));
    for (int k = 1; k <= 4; ++k) stems.push_back("poses-3/cheburashka-" + std::to_string(k));
  }
  std::vector<PoseFiles> out;
  for (const std::string& stem : stems) {
    const fs::path base = kData / model / stem;
    out.push_back(
        {fs::path(base.string() + ".obj"), fs::path(base.string() + ".Tmat"), fs::path(base.string() + ".json")});
  }
  return out;
}

double maxAbsDifference(const BoneTransform& a, const BoneTransform& b) {
  double worst = 0.0;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(a[c][r] - b[c][r]));
  }
  return worst;
}

class TempDir : public testing::TempDirTest {
 protected:
  TempDir() : TempDirTest("odeskin_libigl_io_test_") {}
};

// The failed Result's code, checking the message names `path` and contains `needle`.
template <typename T>
void expectError(const Result<T>& result, StatusCode code, const fs::path& path, const std::string& needle) {
  ASSERT_FALSE(result.ok()) << needle;
  EXPECT_EQ(result.status().code(), code) << result.status().toString();
  EXPECT_NE(result.status().message().find(path.string()), std::string::npos) << result.status().message();
  EXPECT_NE(result.status().message().find(needle), std::string::npos) << result.status().message();
}

// --- .tgf ---

TEST(ReadTgf, CylinderTwoArmsFromTheCentre) {
  const Result<Skeleton> s = readTgf(kData / "cylinder/cylinder.tgf");
  ASSERT_TRUE(s.ok()) << s.status().toString();
  ASSERT_EQ(s->boneCount(), 4u);
  EXPECT_EQ(s->parents, (std::vector<std::int32_t>{-1, 0, -1, 2}));
  EXPECT_EQ(s->names, (std::vector<std::string>{"bone0", "bone1", "bone2", "bone3"}));
  // Joints 1 (0,0,0), 2 (0.9,0,0), 3 (1.8,0,0), 4 (-0.9,0,0), 5 (-1.8,0,0); bones 1-2, 2-3, 1-4, 4-5.
  EXPECT_EQ(s->heads, (std::vector<Vec3>{Vec3(0.0), Vec3(0.9, 0, 0), Vec3(0.0), Vec3(-0.9, 0, 0)}));
  EXPECT_EQ(s->tails, (std::vector<Vec3>{Vec3(0.9, 0, 0), Vec3(1.8, 0, 0), Vec3(-0.9, 0, 0), Vec3(-1.8, 0, 0)}));
  Rig rig;
  rig.skeleton = *s;
  EXPECT_TRUE(validateRig(rig, 0, 0).ok());
}

TEST(ReadTgf, CheburashkaParentsComeInAnyOrder) {
  const Result<Skeleton> s = readTgf(kData / "cheburashka/cheburashka.tgf");
  ASSERT_TRUE(s.ok()) << s.status().toString();
  ASSERT_EQ(s->boneCount(), 11u);
  EXPECT_EQ(s->parents, (std::vector<std::int32_t>{-1, 5, 9, 6, 10, -1, -1, -1, 7, 8, 8}));
  // Bone 1 = joints 9 -> 10; all four roots start at joint 1.
  EXPECT_EQ(s->heads[1], Vec3(0.35123043, 0.43319543, 0.46019698));
  EXPECT_EQ(s->tails[1], Vec3(0.2614806, 0.32338386, 0.46019698));
  for (std::size_t b : {0u, 5u, 6u, 7u}) EXPECT_EQ(s->heads[b], Vec3(0.49052238, 0.54181994, 0.46019698));
  // A child's head is its parent's tail.
  for (std::size_t b = 0; b < 11; ++b) {
    if (s->parents[b] >= 0) {
      EXPECT_EQ(s->heads[b], s->tails[static_cast<std::size_t>(s->parents[b])]) << b;
    }
  }
}

// A UTF-8 byte order mark and CR-only lines read as plain LF text; errors keep their line numbers.
TEST_F(TempDir, TgfAndDmatWithAByteOrderMarkAndCrLines) {
  const Result<Skeleton> plain = readTgf(write("lf.tgf", "1 0 0 0\n2 1 0 0\n3 2 0 0\n#\n1 2\n2 3\n#\n"));
  const Result<Skeleton> marked = readTgf(write("cr.tgf", "\xEF\xBB\xBF" "1 0 0 0\r2 1 0 0\r3 2 0 0\r#\r1 2\r2 3\r#\r"));
  ASSERT_TRUE(plain.ok() && marked.ok()) << marked.status().toString();
  EXPECT_EQ(marked->heads, plain->heads);
  EXPECT_EQ(marked->tails, plain->tails);
  EXPECT_EQ(marked->parents, plain->parents);
  const fs::path bad = write("bad.tgf", "\xEF\xBB\xBF" "1 0 0 0\r2 1 0 0\r3 2 0 0\r#\r1 2\r2 9\r#\r");
  expectError(readTgf(bad), StatusCode::kParseError, bad, ":6: bone end '9' is not a joint number in 1..3");
  const Result<Influences> w = readWeightsDmat(write("w.dmat", "\xEF\xBB\xBF" "2 3\r1\r0\r0.25\r0\r1\r0.75\r"), 3, 2);
  ASSERT_TRUE(w.ok()) << w.status().toString();
}

TEST_F(TempDir, MalformedTgfNamesPathAndLine) {
  const std::string joints = "1 0 0 0\n2 1 0 0\n3 2 0 0\n#\n";
  fs::path p = write("a.tgf", joints + "1 2\n2 9\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":6: bone end '9' is not a joint number in 1..3");
  p = write("b.tgf", "1 0 0 0\n3 1 0 0\n#\n1 2\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":2: expected joint number 2");
  p = write("c.tgf", "1 0 0 0\n2 1 zero 0\n#\n1 2\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":2: joint needs 3 finite coordinates");
  p = write("d.tgf", joints + "#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, "no bones");
  p = write("e.tgf", joints + "1 2\n2 1\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, "cycle");
  p = write("f.tgf", joints + "1 3\n2 3\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":6: joint 3 already ends bone 0 (line 5)");
  p = write("g.tgf", joints + "2 2\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":5: bone starts and ends at joint 2");
  p = write("h.tgf", joints + "1\n#\n");
  expectError(readTgf(p), StatusCode::kParseError, p, ":5: bone end ''");
  p = dir_ / "missing.tgf";
  expectError(readTgf(p), StatusCode::kIoError, p, "cannot open");
  // Without the closing '#', and with tabs and CRLF, the file is still whole.
  p = write("ok.tgf", "1\t0 0 0 \r\n2 1 0 0\r\n#\r\n1 \t2 0 1\r\n");
  const Result<Skeleton> ok = readTgf(p);
  ASSERT_TRUE(ok.ok()) << ok.status().toString();
  EXPECT_EQ(ok->tails[0], Vec3(1.0, 0.0, 0.0));
}

TEST(ParseTgf, TextInMemoryReadsAsTheFileAndErrorsNameTheSource) {
  const Result<Skeleton> from_file = readTgf(kData / "cylinder/cylinder.tgf");
  std::ifstream in(kData / "cylinder/cylinder.tgf", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Result<Skeleton> from_text = parseTgf(text, "tgf in memory");
  ASSERT_TRUE(from_file.ok() && from_text.ok());
  EXPECT_EQ(from_text->parents, from_file->parents);
  EXPECT_EQ(from_text->heads, from_file->heads);
  const Result<Skeleton> bad = parseTgf("1 0 0 0\n#\n1 1\n", "memory.tgf");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "memory.tgf:3: bone starts and ends at joint 1");
}

// --- .Tmat and pose .json in memory ---

TEST(ParseTmat, TextInMemoryReadsAsTheFileAndErrorsNameTheSource) {
  const fs::path path = kData / "cylinder/poses-1/cylinder-1.Tmat";
  const Result<std::vector<RigidTransform>> from_file = readTmat(path, 4);
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Result<std::vector<RigidTransform>> from_text = parseTmat(text, "tmat in memory", 4);
  ASSERT_TRUE(from_file.ok() && from_text.ok());
  for (std::size_t b = 0; b < 4; ++b) {
    EXPECT_EQ((*from_text)[b].rotation, (*from_file)[b].rotation);
    EXPECT_EQ((*from_text)[b].translation, (*from_file)[b].translation);
  }
  const Result<std::vector<RigidTransform>> bad = parseTmat("1 0 0\n0 1 0\n0 0 x\n", "memory.Tmat", 1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("memory.Tmat:3: expected 3 finite numbers", 0), 0u) << bad.status().message();
}

TEST(ParsePoseJson, TextInMemoryErrorsNameTheSource) {
  const Result<std::vector<glm::dquat>> q = parsePoseJson(R"({"dQ-1": [0, 0, 0.6, 0.8]})", "pose in memory", 2);
  ASSERT_TRUE(q.ok()) << q.status().toString();
  EXPECT_NEAR((*q)[1].z, 0.6, 1e-15);
  const Result<std::vector<glm::dquat>> bad = parsePoseJson("{\"dQ-0\": [0, 0, 1]}", "memory.json", 2);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "memory.json: \"dQ-0\" must be an array [x, y, z, w]");
}

TEST(ParsePoseJson, TwoKeysNamingOneBoneAreRefused) {
  const Result<std::vector<glm::dquat>> q =
      parsePoseJson(R"({"dQ-01": [0, 0, 0.6, 0.8], "dQ-1": [0, 0, 0, 1]})", "twice.json", 2);
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.status().code(), StatusCode::kParseError);
  EXPECT_EQ(q.status().message(), "twice.json: \"dQ-1\" names bone 1, as \"dQ-01\" does") << q.status().message();
  // The same key twice: JSON allows it and nlohmann keeps the last copy, so it was read silently.
  const Result<std::vector<glm::dquat>> same =
      parsePoseJson(R"({"dQ-1": [0, 0, 0.6, 0.8], "Camera": {}, "dQ-1": [0, 0, 0, 1]})", "same.json", 2);
  ASSERT_FALSE(same.ok());
  EXPECT_EQ(same.status().code(), StatusCode::kParseError);
  EXPECT_EQ(same.status().message(), "same.json: (top level): \"dQ-1\" appears twice in one object");
}

// The path names where the repeated key is, through objects and arrays.
TEST(DuplicateJsonKey, NamesTheKeyAndItsObject) {
  EXPECT_EQ(duplicateJsonKey(R"({"a": 1, "b": {"c": [1, {"d": 1}], "e": 2}})"), "");
  EXPECT_EQ(duplicateJsonKey(R"({"a": [{"x": 1}, {"y": 1, "y": 2}]})"), "a[1]: \"y\" appears twice in one object");
  EXPECT_EQ(duplicateJsonKey(R"({"a": {"b": [[0], [1, {"k": 1, "k": 1}]]}})"), "a.b[1][1]: \"k\" appears twice in one object");
  EXPECT_EQ(duplicateJsonKey(R"([{"k": 1}, {"k": 1}])"), "");  // two objects, each with k once
  EXPECT_EQ(duplicateJsonKey("{\"k\": "), "");                    // not JSON: the caller's parse says so
}

// --- .dmat ---

TEST(ParseDmat, TextInMemoryErrorsNameTheSource) {
  const Result<DenseMatrix> m = parseDmat("2 1\n0.25 0.75\n", "dmat in memory");
  ASSERT_TRUE(m.ok()) << m.status().toString();
  EXPECT_EQ(m->values, (std::vector<double>{0.25, 0.75}));
  const Result<DenseMatrix> bad = parseDmat("2 1\n0.25\n", "memory.dmat");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message().rfind("memory.dmat: header says 2 columns x 1 rows", 0), 0u) << bad.status().message();
}

TEST(ReadDmat, CylinderWeightsAreColumnMajor) {
  const Result<DenseMatrix> w = readDmat(kData / "cylinder/cylinder.DMAT");
  ASSERT_TRUE(w.ok()) << w.status().toString();
  ASSERT_EQ(w->rows, 420u);
  ASSERT_EQ(w->cols, 4u);
  EXPECT_EQ(w->at(0, 0), 5.365736535231259e-05);  // the first two values: column 0, rows 0 and 1
  EXPECT_EQ(w->at(1, 0), 9.3174280085594216e-05);
  // README: 27 vertices have 1 non-zero weight, 132 have 2, 196 have 3 and 65 have 4.
  std::vector<int> histogram(5, 0);
  for (std::size_t v = 0; v < w->rows; ++v) {
    double sum = 0.0;
    int nonzero = 0;
    for (std::size_t b = 0; b < w->cols; ++b) {
      EXPECT_GE(w->at(v, b), 0.0);
      EXPECT_LE(w->at(v, b), 1.0);
      sum += w->at(v, b);
      nonzero += w->at(v, b) != 0.0;
    }
    EXPECT_NEAR(sum, 1.0, 1e-15) << v;
    ++histogram[static_cast<std::size_t>(nonzero)];
  }
  EXPECT_EQ(histogram, (std::vector<int>{0, 27, 132, 196, 65}));
}

TEST(ReadDmat, CheburashkaWeightsAreDense) {
  const Result<Influences> in = readWeightsDmat(kData / "cheburashka/cheburashka.DMAT", 6669, 11);
  ASSERT_TRUE(in.ok()) << in.status().toString();
  EXPECT_TRUE(validateInfluences(in.value(), 6669, 11, 1e-15).ok());
  EXPECT_EQ(in->maxInfluences(), 11u);
  std::size_t all_eleven = 0;
  for (std::size_t v = 0; v < 6669; ++v) all_eleven += in->offsets[v + 1] - in->offsets[v] == 11;
  EXPECT_EQ(all_eleven, 214u);  // README
}

TEST(ReadDmat, PerVertexTransformsReproduceThePosedMesh) {
  // poses-*/cylinder-k.DMAT: row v = M_v flattened column by column (README), p' = M_v [p; 1].
  const Result<ObjMesh> rest = readObj(kData / "cylinder/cylinder.obj");
  ASSERT_TRUE(rest.ok());
  for (const PoseFiles& pose : posesOf("cylinder")) {
    const fs::path dmat = fs::path(pose.obj).replace_extension(".DMAT");
    const Result<DenseMatrix> m = readDmat(dmat);
    const Result<ObjMesh> posed = readObj(pose.obj);
    ASSERT_TRUE(m.ok() && posed.ok()) << dmat;
    ASSERT_EQ(m->rows, 420u);
    ASSERT_EQ(m->cols, 12u);
    double worst = 0.0;
    for (std::size_t v = 0; v < 420; ++v) {
      BoneTransform mv;
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 3; ++r) mv[c][r] = m->at(v, 3 * static_cast<std::size_t>(c) + static_cast<std::size_t>(r));
      }
      const Vec3 d = mv * glm::dvec4(rest->positions[v], 1.0) - posed->positions[v];
      worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    EXPECT_LT(worst, 1e-6) << dmat;
  }
}

TEST(ReadWeightsDmat, CylinderAsInfluences) {
  const fs::path path = kData / "cylinder/cylinder.DMAT";
  const Result<Influences> in = readWeightsDmat(path, 420, 4);
  ASSERT_TRUE(in.ok()) << in.status().toString();
  EXPECT_TRUE(validateInfluences(in.value(), 420, 4, 1e-15).ok());
  EXPECT_EQ(in->offsets.back(), 27u * 1 + 132u * 2 + 196u * 3 + 65u * 4);  // zero weights dropped
  expectError(readWeightsDmat(path, 421, 4), StatusCode::kInvalidArgument, path, "420 x 4, expected 421 vertices x 4");
  expectError(readWeightsDmat(path, 420, 5), StatusCode::kInvalidArgument, path, "expected 420 vertices x 5 bones");
}

TEST_F(TempDir, MalformedDmatNamesPath) {
  fs::path p = write("short.dmat", "2 3\n1\n0\n1\n0\n1\n");
  expectError(readDmat(p), StatusCode::kParseError, p, "= 6 values, found 5");
  p = write("text.dmat", "2 2\n1\n0\nx\n1\n");
  expectError(readDmat(p), StatusCode::kParseError, p, ":4: 'x' is not a finite number");
  p = write("long.dmat", "1 2\n1\n0\n1\n");
  expectError(readDmat(p), StatusCode::kParseError, p, ":4: more than the 2 values");
  p = write("header.dmat", "2\n");
  expectError(readDmat(p), StatusCode::kParseError, p, ":1: header must be 'cols rows'");
  p = write("binary.dmat", "0 0\n");
  expectError(readDmat(p), StatusCode::kParseError, p, "binary DMAT");
  p = write("empty.dmat", "");
  expectError(readDmat(p), StatusCode::kParseError, p, "empty file");
  p = write("huge.dmat", "4000000000 4000000000\n1\n");
  expectError(readDmat(p), StatusCode::kParseError, p, "found 1");
  p = dir_ / "missing.dmat";
  expectError(readDmat(p), StatusCode::kIoError, p, "cannot open");
  // Weights: a negative entry, a row that does not sum to 1 (column-major: rows 0..2 of column 0, then column 1).
  p = write("negative.dmat", "2 3\n1.5\n0\n0.5\n-0.5\n1\n0.5\n");
  expectError(readWeightsDmat(p, 3, 2), StatusCode::kInvalidArgument, p,
              "vertex 0 has weight -0.5 < 0 for bone 1");
  // A small negative weight is named as it is ("%f" read "-0.000000 < 0"), and a sum as far from 1 as
  // it is (6 decimals read 1.0000015 as "1.000002" and 1 + 1e-12 as "1.000000").
  p = write("small.dmat", "2 3\n1\n-2e-6\n0.5\n0\n1.000002\n0.5\n");
  expectError(readWeightsDmat(p, 3, 2), StatusCode::kInvalidArgument, p, "vertex 1 has weight -2e-06 < 0 for bone 0");
  // Within the 1e-6 the sums are held to, a solver's -1e-9 is a zero.
  p = write("tiny.dmat", "2 3\n1\n-1e-9\n0.5\n0\n1.000000001\n0.5\n");
  const Result<Influences> tiny = readWeightsDmat(p, 3, 2);
  ASSERT_TRUE(tiny.ok()) << tiny.status().toString();
  EXPECT_EQ(tiny->offsets, (std::vector<std::uint32_t>{0, 1, 2, 4}));
  EXPECT_EQ(tiny->bones, (std::vector<std::uint32_t>{0, 1, 0, 1}));
  EXPECT_EQ(tiny->weights, (std::vector<double>{1.0, 1.000000001, 0.5, 0.5}));
  p = write("sum.dmat", "2 3\n1\n0\n0.5\n0\n1\n0.4\n");
  expectError(readWeightsDmat(p, 3, 2), StatusCode::kInvalidArgument, p, "weights of vertex 2 sum to 0.9, not 1");
  p = write("near.dmat", "2 3\n1\n0\n0.5\n0\n1\n0.5000015\n");
  expectError(readWeightsDmat(p, 3, 2), StatusCode::kInvalidArgument, p, "weights of vertex 2 sum to 1.0000015, not 1");
  // A valid small file: W = [1 0; 0 1; 0.25 0.75].
  p = write("ok.dmat", "2 3\n1\n0\n0.25\n0\n1\n0.75");
  const Result<Influences> ok = readWeightsDmat(p, 3, 2);
  ASSERT_TRUE(ok.ok()) << ok.status().toString();
  EXPECT_EQ(ok->offsets, (std::vector<std::uint32_t>{0, 1, 2, 4}));
  EXPECT_EQ(ok->bones, (std::vector<std::uint32_t>{0, 1, 0, 1}));
  EXPECT_EQ(ok->weights, (std::vector<double>{1.0, 1.0, 0.25, 0.75}));
}

// --- .Tmat and LBS against the posed OBJs ---

// max |LBS(rest, W, T) - posed| per coordinate over all vertices.
double lbsError(const std::vector<Vec3>& rest, const Influences& influences, const std::vector<RigidTransform>& pose,
                const std::vector<Vec3>& posed) {
  std::vector<BoneTransform> bones;
  bones.reserve(pose.size());
  for (const RigidTransform& t : pose) bones.push_back(t.matrix());
  double worst = 0.0;
  for (std::size_t v = 0; v < rest.size(); ++v) {
    const Vec3 d = skinPoint(influences, bones, v, rest[v]) - posed[v];
    worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
  }
  return worst;
}

void expectLbsReproducesPoses(const std::string& model, std::size_t bones, double tolerance) {
  const Result<ObjMesh> rest = readObj(kData / model / (model + ".obj"));
  ASSERT_TRUE(rest.ok()) << rest.status().toString();
  const Result<Influences> weights = readWeightsDmat(kData / model / (model + ".DMAT"), rest->positions.size(), bones);
  ASSERT_TRUE(weights.ok()) << weights.status().toString();
  for (const PoseFiles& pose : posesOf(model)) {
    const Result<std::vector<RigidTransform>> transforms = readTmat(pose.tmat, bones);
    const Result<ObjMesh> posed = readObj(pose.obj);
    ASSERT_TRUE(transforms.ok()) << transforms.status().toString();
    ASSERT_TRUE(posed.ok()) << posed.status().toString();
    const double error = lbsError(rest->positions, *weights, *transforms, posed->positions);
    EXPECT_LT(error, tolerance) << pose.tmat;
    // The identity transforms would be far off: the test can see a wrong reader.
    const std::vector<RigidTransform> identity(bones);
    EXPECT_GT(lbsError(rest->positions, *weights, identity, posed->positions), 100 * tolerance) << pose.tmat;
  }
}

TEST(ReadTmat, CylinderLbsReproducesEveryPose) { expectLbsReproducesPoses("cylinder", 4, 2e-6); }

// README: the published weights differ slightly from the generating ones at a few vertices (1.7e-4).
TEST(ReadTmat, CheburashkaLbsReproducesEveryPose) { expectLbsReproducesPoses("cheburashka", 11, 2e-4); }

TEST(ReadTmat, RotationsAreReorthonormalisedNearTheFile) {
  const Result<std::vector<RigidTransform>> t = readTmat(kData / "cylinder/poses-1/cylinder-1.Tmat", 4);
  ASSERT_TRUE(t.ok()) << t.status().toString();
  // Bone 1's block: columns (0.351629 -0.403743 0.8446), (-0.38437 0.760391 0.523512), ... t (0.583534 0.363369
  // -0.76014).
  const glm::dmat3 r = glm::mat3_cast((*t)[1].rotation);
  EXPECT_NEAR(r[0][0], 0.351629, 2e-6);
  EXPECT_NEAR(r[0][2], 0.8446, 2e-6);
  EXPECT_NEAR(r[1][0], -0.38437, 2e-6);
  EXPECT_NEAR(r[2][1], -0.508721, 2e-6);
  EXPECT_EQ((*t)[1].translation, Vec3(0.583534, 0.363369, -0.76014));
  for (const RigidTransform& x : *t) {
    EXPECT_NEAR(glm::length(x.rotation), 1.0, 1e-15);
    const glm::dmat3 m = glm::mat3_cast(x.rotation);
    const glm::dmat3 gram = glm::transpose(m) * m;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 1e-14);
    }
  }
  EXPECT_EQ((*t)[0].rotation, glm::dquat(1.0, 0.0, 0.0, 0.0));  // bone 0 is the identity block
}

TEST_F(TempDir, MalformedTmatNamesPath) {
  const std::string identity = "1 0 0\n0 1 0\n0 0 1\n0 0 0\n";
  fs::path p = write("short.Tmat", identity + "1 0 0\n0 1 0\n0 0 1\n");
  expectError(readTmat(p, 2), StatusCode::kInvalidArgument, p, "7 lines of 3 numbers, expected 4 x 2 bones = 8");
  expectError(readTmat(write("one.Tmat", identity), 2), StatusCode::kInvalidArgument, dir_ / "one.Tmat", "= 8");
  p = write("text.Tmat", "1 0 0\n0 1 0\n0 0 one\n0 0 0\n");
  expectError(readTmat(p, 1), StatusCode::kParseError, p, ":3: expected 3 finite numbers");
  p = write("four.Tmat", "1 0 0\n0 1 0 0\n0 0 1\n0 0 0\n");
  expectError(readTmat(p, 1), StatusCode::kParseError, p, ":2: more than 3 numbers");
  p = write("two.Tmat", "1 0 0\n0 1\n0 0 1\n0 0 0\n");
  expectError(readTmat(p, 1), StatusCode::kParseError, p, ":2: expected 3 finite numbers");
  p = write("mirror.Tmat", identity + "1 0 0\n0 1 0\n0 0 -1\n0 0 0\n");
  expectError(readTmat(p, 2), StatusCode::kInvalidArgument, p, ":5: bone 1 has determinant < 0");
  p = write("scaled.Tmat", "1.001 0 0\n0 1.001 0\n0 0 1.001\n0 0 0\n");
  expectError(readTmat(p, 1), StatusCode::kInvalidArgument, p, ":1: bone 0 is not a rotation within 1e-4");
  p = write("sheared.Tmat", "1 0 0\n0.01 1 0\n0 0 1\n0 0 0\n");
  expectError(readTmat(p, 1), StatusCode::kInvalidArgument, p, "not a rotation");
  expectError(readTmat(dir_ / "missing.Tmat", 1), StatusCode::kIoError, dir_ / "missing.Tmat", "cannot open");
  // Rounding in the 6th digit is within 1e-4 and gets snapped to a rotation.
  p = write("rounded.Tmat", "0.707107 0.707107 0\n-0.707107 0.707107 0\n0 0 1\n1 2 3\n");
  const Result<std::vector<RigidTransform>> ok = readTmat(p, 1);
  ASSERT_TRUE(ok.ok()) << ok.status().toString();
  const glm::dquat expected = glm::angleAxis(std::numbers::pi / 4, Vec3(0.0, 0.0, 1.0));
  EXPECT_NEAR(std::abs(glm::dot((*ok)[0].rotation, expected)), 1.0, 1e-12);
}

// --- .json poses and forward kinematics ---

void expectFkMatchesTmat(const std::string& model, std::size_t bones) {
  const Result<Skeleton> skeleton = readTgf(kData / model / (model + ".tgf"));
  ASSERT_TRUE(skeleton.ok()) << skeleton.status().toString();
  ASSERT_EQ(skeleton->boneCount(), bones);
  std::size_t poses = 0;
  for (const PoseFiles& pose : posesOf(model)) {
    const Result<std::vector<glm::dquat>> relative = readPoseJson(pose.json, bones);
    const Result<std::vector<RigidTransform>> expected = readTmat(pose.tmat, bones);
    ASSERT_TRUE(relative.ok()) << relative.status().toString();
    ASSERT_TRUE(expected.ok()) << expected.status().toString();
    const std::vector<RigidTransform> actual = forwardKinematics(*skeleton, *relative);
    ASSERT_EQ(actual.size(), bones);
    double worst = 0.0;
    std::size_t non_identity = 0;
    for (std::size_t b = 0; b < bones; ++b) {
      worst = std::max(worst, maxAbsDifference(actual[b].matrix(), (*expected)[b].matrix()));
      non_identity += maxAbsDifference(actual[b].matrix(), BoneTransform(1.0)) > 1e-3;
    }
    EXPECT_LT(worst, 2e-5) << pose.json;
    EXPECT_GT(non_identity, 0u) << pose.json;  // every pose moves something
    ++poses;
  }
  EXPECT_EQ(poses, model == "cylinder" ? 8u : 16u);
}

TEST(ForwardKinematics, CylinderJsonGivesTheTmat) { expectFkMatchesTmat("cylinder", 4); }
TEST(ForwardKinematics, CheburashkaJsonGivesTheTmat) { expectFkMatchesTmat("cheburashka", 11); }

TEST(ForwardKinematics, SingleBonePosesMoveOnlyThatBoneAndItsChildren) {
  // README: poses-2/cylinder-1 rotates bone 3 only, cylinder-2 bone 2 (and so its child 3).
  const Result<Skeleton> s = readTgf(kData / "cylinder/cylinder.tgf");
  const Result<std::vector<glm::dquat>> q1 = readPoseJson(kData / "cylinder/poses-2/cylinder-1.json", 4);
  const Result<std::vector<glm::dquat>> q2 = readPoseJson(kData / "cylinder/poses-2/cylinder-2.json", 4);
  ASSERT_TRUE(s.ok() && q1.ok() && q2.ok());
  const std::vector<RigidTransform> t1 = forwardKinematics(*s, *q1);
  const std::vector<RigidTransform> t2 = forwardKinematics(*s, *q2);
  for (std::size_t b = 0; b < 3; ++b) EXPECT_LT(maxAbsDifference(t1[b].matrix(), BoneTransform(1.0)), 1e-12) << b;
  EXPECT_GT(maxAbsDifference(t1[3].matrix(), BoneTransform(1.0)), 1e-2);
  // Each bone turns about its head: the head stays where its parent chain puts it.
  EXPECT_LT(glm::length(t1[3].apply(s->heads[3]) - s->heads[3]), 1e-12);
  EXPECT_LT(glm::length(t2[2].apply(s->heads[2]) - s->heads[2]), 1e-12);
  EXPECT_LT(glm::length(t2[3].apply(s->heads[3]) - t2[2].apply(s->heads[3])), 1e-12);  // joint 4 stays attached
  EXPECT_GT(maxAbsDifference(t2[3].matrix(), BoneTransform(1.0)), 1e-2);
}

TEST(ForwardKinematics, BoneOrderDoesNotMatter) {
  // Reverse the cheburashka bones: children now come before their parents everywhere.
  const Result<Skeleton> s = readTgf(kData / "cheburashka/cheburashka.tgf");
  const Result<std::vector<glm::dquat>> q = readPoseJson(kData / "cheburashka/poses-1/cheburashka-1.json", 11);
  ASSERT_TRUE(s.ok() && q.ok());
  Skeleton reversed;
  std::vector<glm::dquat> reversed_q;
  for (std::size_t i = 0; i < 11; ++i) {
    const std::size_t b = 10 - i;
    const std::int32_t p = s->parents[b];
    reversed.parents.push_back(p < 0 ? -1 : 10 - p);
    reversed.heads.push_back(s->heads[b]);
    reversed.tails.push_back(s->tails[b]);
    reversed_q.push_back((*q)[b]);
  }
  const std::vector<RigidTransform> a = forwardKinematics(*s, *q);
  const std::vector<RigidTransform> r = forwardKinematics(reversed, reversed_q);
  for (std::size_t b = 0; b < 11; ++b) EXPECT_LT(maxAbsDifference(a[b].matrix(), r[10 - b].matrix()), 1e-15) << b;
}

TEST(ForwardKinematics, CyclesAndMissingRotationsDoNotHang) {
  Skeleton s;
  s.parents = {1, 0, 5, 2};  // 0 <-> 1 loop; bone 2's parent is out of range
  s.heads = {Vec3(0.0), Vec3(1.0, 0, 0), Vec3(2.0, 0, 0), Vec3(3.0, 0, 0)};
  s.tails = s.heads;
  const glm::dquat turn = glm::angleAxis(0.5, Vec3(0, 0, 1));
  const std::vector<RigidTransform> t = forwardKinematics(s, {turn, turn, turn});  // bone 3: identity
  ASSERT_EQ(t.size(), 4u);
  for (const RigidTransform& x : t) {
    EXPECT_TRUE(std::isfinite(x.translation.x) && std::isfinite(glm::length(x.rotation)));
  }
  EXPECT_LT(glm::length(t[2].apply(s.heads[2]) - s.heads[2]), 1e-15);         // treated as a root
  EXPECT_NEAR(std::abs(glm::dot(t[3].rotation, t[2].rotation)), 1.0, 1e-15);  // child with identity q
}

TEST_F(TempDir, PoseJsonMissingBonesAreIdentity) {
  const fs::path p = write("pose.json", "{\"threshold\": 1, \"dQ-1\": [0, 0, 0.6, 0.8], \"Camera\": {}}");
  const Result<std::vector<glm::dquat>> q = readPoseJson(p, 3);
  ASSERT_TRUE(q.ok()) << q.status().toString();
  ASSERT_EQ(q->size(), 3u);
  EXPECT_EQ((*q)[0], glm::dquat(1.0, 0.0, 0.0, 0.0));
  EXPECT_NEAR((*q)[1].w, 0.8, 1e-15);  // file order x y z w
  EXPECT_NEAR((*q)[1].z, 0.6, 1e-15);
  EXPECT_EQ((*q)[1].x, 0.0);
  EXPECT_EQ((*q)[2], glm::dquat(1.0, 0.0, 0.0, 0.0));
}

TEST_F(TempDir, MalformedPoseJsonNamesPath) {
  fs::path p = write("syntax.json", "{\n  \"dQ-0\": [0, 0, 0, 1],\n  \"dQ-1\": [0, 0 0, 1]\n}\n");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, ":3: invalid JSON");
  p = write("array.json", "[1, 2]");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "not a JSON object");
  p = write("three.json", "{\"dQ-0\": [0, 0, 1]}");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "\"dQ-0\" must be an array [x, y, z, w]");
  p = write("range.json", "{\"dQ-2\": [0, 0, 0, 1]}");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "names bone 2 but the skeleton has 2 bones");
  p = write("name.json", "{\"dQ-x\": [0, 0, 0, 1]}");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "does not name a bone number");
  p = write("string.json", "{\"dQ-1\": [0, \"0\", 0, 1]}");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "component 1 is not a finite number");
  p = write("long.json", "{\"dQ-1\": [0, 0, 0, 2]}");
  expectError(readPoseJson(p, 2), StatusCode::kParseError, p, "not a unit quaternion");
  expectError(readPoseJson(dir_ / "missing.json", 2), StatusCode::kIoError, dir_ / "missing.json", "cannot open");
}

}  // namespace
}  // namespace odeskin

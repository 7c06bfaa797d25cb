// SPDX-License-Identifier: MIT
#include "engine/io/asset_file.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/offline/procedural_arm.hpp"
#include "scratch_dir.hpp"  // tests/

namespace odeskin {
namespace {

using testing::scratchDir;

// A small arm fitted over three keys (so segment 1 carries rates), with every optional field of
// the asset filled and a few doubles whose bits a lossy format would change.
DeformAsset makeAsset() {
  ArmOptions options;
  options.rings = 9;
  options.ring_vertices = 12;
  Result<ProceduralArm> arm = makeProceduralArm(options);
  EXPECT_TRUE(arm.ok()) << arm.status().toString();
  FitInput input = arm->fit_input;
  input.poses.push_back(input.poses[0]);
  input.key_poses.push_back(input.key_poses[0]);
  FitOptions fit;
  fit.modes = 3;
  fit.residual_space = ResidualSpace::kPosed;
  Material stiff = skinMaterial();
  stiff.bending = BendingSign::kStiffening;
  fit.materials = {skinMaterial(), stiff};
  for (std::size_t c = 0; c < input.curves.size(); ++c) fit.curve_materials.push_back(static_cast<std::uint32_t>(c % 2));
  fit.key_tolerance = 1e-9;  // forces sparse remainders
  Result<DeformAsset> fitted = fitDeformAsset(input, fit);
  EXPECT_TRUE(fitted.ok()) << fitted.status().toString();
  DeformAsset asset = std::move(fitted).value();
  asset.skinning = SkinningMode::kDualQuaternion;
  asset.segment_seconds = 0.1 + 0.2;  // not a short decimal
  asset.curves[1].closed = false;
  asset.curves[2].part = 1;
  asset.curves[0].points[1] = CurvePoint{0, 1, 1.0 / 3.0};
  asset.rest_positions[0].x = -0.0;
  asset.rest_positions[1].y = std::numeric_limits<double>::denorm_min();
  asset.rest_positions[2].z = std::nextafter(1.0, 2.0);
  // A render layout that splits vertex 0 into two render vertices.
  for (std::uint32_t i = 0; i < asset.vertexCount(); ++i) asset.render.topology_of_render.push_back(i);
  asset.render.topology_of_render.push_back(0);
  asset.render.faces = asset.faces;
  asset.render.faces.indices[0] = static_cast<std::uint32_t>(asset.vertexCount());
  asset.bone_parents = {-1, 0};
  asset.bone_names = {"upper arm", ""};
  return asset;
}

bool sameBits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }
bool sameBits(const Vec3& a, const Vec3& b) { return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z); }

template <typename T>
void expectSameVec3s(const std::vector<T>& a, const std::vector<T>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(sameBits(a[i], b[i])) << what << " " << i;
}

void expectSameFaces(const FaceList& a, const FaceList& b) {
  EXPECT_EQ(a.face_offsets, b.face_offsets);
  EXPECT_EQ(a.indices, b.indices);
}

void expectSameAsset(const DeformAsset& a, const DeformAsset& b) {
  EXPECT_EQ(a.modes, b.modes);
  EXPECT_EQ(a.residual_space, b.residual_space);
  EXPECT_EQ(a.skinning, b.skinning);
  EXPECT_TRUE(sameBits(a.segment_seconds, b.segment_seconds));
  expectSameVec3s(a.rest_positions, b.rest_positions, "rest position");
  expectSameFaces(a.faces, b.faces);
  EXPECT_EQ(a.render.topology_of_render, b.render.topology_of_render);
  expectSameFaces(a.render.faces, b.render.faces);
  expectSameVec3s(a.render.normals, b.render.normals, "render normal");
  ASSERT_EQ(a.render.uvs.size(), b.render.uvs.size());
  for (std::size_t r = 0; r < a.render.uvs.size(); ++r) {
    EXPECT_TRUE(sameBits(a.render.uvs[r].x, b.render.uvs[r].x) && sameBits(a.render.uvs[r].y, b.render.uvs[r].y)) << "UV " << r;
  }
  EXPECT_EQ(a.render.primitives, b.render.primitives);
  EXPECT_EQ(a.render.obj_order, b.render.obj_order);
  ASSERT_EQ(a.bindings.size(), b.bindings.size());
  for (std::size_t i = 0; i < a.bindings.size(); ++i) {
    EXPECT_EQ(a.bindings[i].curve_a, b.bindings[i].curve_a) << i;
    EXPECT_EQ(a.bindings[i].curve_b, b.bindings[i].curve_b) << i;
    EXPECT_TRUE(sameBits(a.bindings[i].w, b.bindings[i].w)) << i;
    EXPECT_TRUE(sameBits(a.bindings[i].v, b.bindings[i].v)) << i;
  }
  ASSERT_EQ(a.curves.size(), b.curves.size());
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    EXPECT_EQ(a.curves[c].closed, b.curves[c].closed) << c;
    EXPECT_EQ(a.curves[c].part, b.curves[c].part) << c;
    ASSERT_EQ(a.curves[c].points.size(), b.curves[c].points.size()) << c;
    for (std::size_t p = 0; p < a.curves[c].points.size(); ++p) {
      EXPECT_EQ(a.curves[c].points[p].a, b.curves[c].points[p].a);
      EXPECT_EQ(a.curves[c].points[p].b, b.curves[c].points[p].b);
      EXPECT_TRUE(sameBits(a.curves[c].points[p].t, b.curves[c].points[p].t));
    }
    expectSameVec3s(a.curves[c].v, b.curves[c].v, "curve v");
  }
  EXPECT_EQ(a.curve_materials, b.curve_materials);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t m = 0; m < a.materials.size(); ++m) {
    EXPECT_TRUE(sameBits(a.materials[m].rho, b.materials[m].rho));
    EXPECT_TRUE(sameBits(a.materials[m].eta, b.materials[m].eta));
    EXPECT_TRUE(sameBits(a.materials[m].zeta, b.materials[m].zeta));
    EXPECT_TRUE(sameBits(a.materials[m].xi, b.materials[m].xi));
    EXPECT_EQ(a.materials[m].bending, b.materials[m].bending);
  }
  EXPECT_EQ(a.influences.offsets, b.influences.offsets);
  EXPECT_EQ(a.influences.bones, b.influences.bones);
  expectSameVec3s(a.influences.weights, b.influences.weights, "weight");
  EXPECT_EQ(a.bone_count, b.bone_count);
  expectSameVec3s(a.bone_pivots, b.bone_pivots, "pivot");
  EXPECT_EQ(a.bone_parents, b.bone_parents);
  EXPECT_EQ(a.bone_names, b.bone_names);
  ASSERT_EQ(a.key_poses.size(), b.key_poses.size());
  for (std::size_t k = 0; k < a.key_poses.size(); ++k) {
    ASSERT_EQ(a.key_poses[k].size(), b.key_poses[k].size());
    for (std::size_t j = 0; j < a.key_poses[k].size(); ++j) {
      const glm::dquat& qa = a.key_poses[k][j].rotation;
      const glm::dquat& qb = b.key_poses[k][j].rotation;
      EXPECT_TRUE(sameBits(qa.w, qb.w) && sameBits(qa.x, qb.x) && sameBits(qa.y, qb.y) && sameBits(qa.z, qb.z));
      EXPECT_TRUE(sameBits(a.key_poses[k][j].translation, b.key_poses[k][j].translation));
    }
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t s = 0; s < a.segments.size(); ++s) {
    expectSameVec3s(a.segments[s].base_residuals, b.segments[s].base_residuals, "base residual");
    expectSameVec3s(a.segments[s].coefficients, b.segments[s].coefficients, "coefficient");
    expectSameVec3s(a.segments[s].rates, b.segments[s].rates, "rate");
    EXPECT_EQ(a.segments[s].remainder_indices, b.segments[s].remainder_indices);
    expectSameVec3s(a.segments[s].remainders, b.segments[s].remainders, "remainder");
  }
}

std::uint64_t readU64(const std::string& bytes, std::size_t at) {
  std::uint64_t x = 0;
  for (int i = 0; i < 8; ++i) x |= std::uint64_t{static_cast<unsigned char>(bytes[at + i])} << (8 * i);
  return x;
}

void writeU64(std::string& bytes, std::size_t at, std::uint64_t x) {
  for (int i = 0; i < 8; ++i) bytes[at + i] = static_cast<char>((x >> (8 * i)) & 0xFF);
}

// The file with its payload replaced and the header's size and checksum made consistent.
std::string withPayload(const std::string& file, const std::string& payload) {
  std::string out = file.substr(0, 32) + payload;
  writeU64(out, 16, payload.size());
  writeU64(out, 24, assetChecksum(payload));
  return out;
}

// Each section of the payload as (tag name, the section's bytes including its 12-byte header).
std::vector<std::pair<std::string, std::string>> sections(const std::string& file) {
  std::vector<std::pair<std::string, std::string>> out;
  std::size_t pos = 32;
  while (pos < file.size()) {
    const std::size_t size = readU64(file, pos + 4);
    out.emplace_back(file.substr(pos, 4), file.substr(pos, 12 + size));
    pos += 12 + size;
  }
  return out;
}

class AssetFile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    asset_ = new DeformAsset(makeAsset());
    Result<std::string> bytes = encodeAsset(*asset_);
    ASSERT_TRUE(bytes.ok()) << bytes.status().toString();
    bytes_ = new std::string(*bytes);
  }
  static void TearDownTestSuite() {
    delete asset_;
    delete bytes_;
  }
  static const DeformAsset* asset_;
  static const std::string* bytes_;

  // `asset` encodes with one `tag` section beside the 12 required ones and decodes to itself, and
  // the file without that section, as a writer that predates it made, still decodes: into `older`.
  static void expectOptionalSection(const DeformAsset& asset, const std::string& tag, DeformAsset& older) {
    Result<std::string> bytes = encodeAsset(asset);
    ASSERT_TRUE(bytes.ok()) << bytes.status().toString();
    const auto parts = sections(*bytes);
    ASSERT_EQ(parts.size(), 13u);
    EXPECT_EQ(std::count_if(parts.begin(), parts.end(), [&](const auto& p) { return p.first == tag; }), 1);
    Result<DeformAsset> decoded = decodeAsset(*bytes, tag + ".odsk");
    ASSERT_TRUE(decoded.ok()) << decoded.status().toString();
    expectSameAsset(asset, *decoded);
    std::string without;
    for (const auto& [section_tag, section] : parts) {
      if (section_tag != tag) without += section;
    }
    decoded = decodeAsset(withPayload(*bytes, without), "older.odsk");
    ASSERT_TRUE(decoded.ok()) << decoded.status().toString();
    older = std::move(decoded).value();
  }
};
const DeformAsset* AssetFile::asset_ = nullptr;
const std::string* AssetFile::bytes_ = nullptr;

TEST_F(AssetFile, TheTestAssetFillsEveryField) {
  const DeformAsset& a = *asset_;
  EXPECT_EQ(a.segments.size(), 2u);
  EXPECT_GT(a.segments[0].remainders.size(), 0u);
  bool any_rate = false;
  for (const Vec3& r : a.segments[1].rates) any_rate = any_rate || r != Vec3(0.0);
  EXPECT_TRUE(any_rate);
  EXPECT_FALSE(a.render.empty());
  EXPECT_FALSE(a.curves.empty());
  EXPECT_EQ(a.materials.size(), 2u);
}

TEST_F(AssetFile, RoundTripIsBitExact) {
  EXPECT_EQ(bytes_->substr(0, 8), std::string("ODSK\r\n\x1a\n", 8));
  Result<DeformAsset> decoded = decodeAsset(*bytes_, "mem");
  ASSERT_TRUE(decoded.ok()) << decoded.status().toString();
  expectSameAsset(*asset_, *decoded);
  // Encoding is deterministic: the decoded asset encodes to the same bytes.
  Result<std::string> again = encodeAsset(*decoded);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, *bytes_);
}

TEST_F(AssetFile, SaveAndLoad) {
  const std::filesystem::path path = scratchDir("save") / "arm.odsk";
  ASSERT_TRUE(saveAsset(path, *asset_).ok());
  EXPECT_EQ(std::filesystem::file_size(path), bytes_->size());
  Result<DeformAsset> loaded = loadAsset(path);
  ASSERT_TRUE(loaded.ok()) << loaded.status().toString();
  expectSameAsset(*asset_, *loaded);
  // Only the asset is left in the folder: the temporary file was renamed, not copied.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path.parent_path()), {}), 1);
}

TEST_F(AssetFile, TruncatedAnywhereIsAParseError) {
  std::vector<std::size_t> cuts{0, 1, 7, 8, 12, 16, 24, 31, 32, 33, 40, 44, bytes_->size() - 1};
  for (std::size_t cut = 45; cut < bytes_->size(); cut += bytes_->size() / 97) cuts.push_back(cut);
  for (std::size_t cut : cuts) {
    const Result<DeformAsset> r = decodeAsset(bytes_->substr(0, cut), "cut.odsk");
    ASSERT_FALSE(r.ok()) << "cut at " << cut;
    EXPECT_EQ(r.status().code(), StatusCode::kParseError) << "cut at " << cut;
    EXPECT_NE(r.status().message().find("cut.odsk"), std::string::npos) << r.status().message();
  }
  EXPECT_NE(decodeAsset(bytes_->substr(0, 100), "x").status().message().find("truncated"), std::string::npos);
}

TEST_F(AssetFile, FlippedPayloadByteIsAChecksumError) {
  std::vector<std::size_t> where{32, 33, 36, 44, bytes_->size() - 1};
  for (std::size_t at = 45; at < bytes_->size(); at += bytes_->size() / 251) where.push_back(at);
  for (std::size_t at : where) {
    for (int mask : {0x01, 0x80, 0xFF}) {
      std::string bad = *bytes_;
      bad[at] = static_cast<char>(static_cast<unsigned char>(bad[at]) ^ mask);
      const Result<DeformAsset> r = decodeAsset(bad, "flip.odsk");
      ASSERT_EQ(r.status().code(), StatusCode::kParseError) << "byte " << at;
      EXPECT_NE(r.status().message().find("checksum"), std::string::npos) << r.status().message();
    }
  }
}

TEST_F(AssetFile, BadMagicVersionFlagsAndSize) {
  std::string bad = *bytes_;
  bad[0] = 'X';
  EXPECT_NE(decodeAsset(bad, "m").status().message().find("bad magic"), std::string::npos);
  EXPECT_NE(decodeAsset("glTF", "m").status().message().find("truncated"), std::string::npos);
  EXPECT_NE(decodeAsset("# an OBJ file, not an asset\nv 0 0 0\n", "m").status().message().find("bad magic"),
            std::string::npos);
  bad = *bytes_;
  bad[8] = static_cast<char>(kAssetVersion + 1);
  Result<DeformAsset> r = decodeAsset(bad, "future.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  EXPECT_NE(r.status().message().find("version 2 is not supported"), std::string::npos) << r.status().message();
  bad = *bytes_;
  bad[8] = 0;
  EXPECT_EQ(decodeAsset(bad, "v0").status().code(), StatusCode::kParseError);
  bad = *bytes_;
  bad[12] = 1;
  EXPECT_NE(decodeAsset(bad, "f").status().message().find("flags"), std::string::npos);
  EXPECT_EQ(decodeAsset(*bytes_ + "x", "padded").status().code(), StatusCode::kParseError);
}

TEST_F(AssetFile, UnknownSectionsAreSkipped) {
  std::string payload = bytes_->substr(32);
  const std::string extra = std::string("XTRA") + std::string("\x05\0\0\0\0\0\0\0", 8) + "hello";
  Result<DeformAsset> r = decodeAsset(withPayload(*bytes_, extra + payload + extra), "newer.odsk");
  ASSERT_TRUE(r.ok()) << r.status().toString();
  expectSameAsset(*asset_, *r);
}

// A render layout's bind normals (hard edges) go in the optional RNRM section, written only when
// there are some: files without it load as before, and a reader that predates it skips it.
TEST_F(AssetFile, RenderNormalsAreAnOptionalSection) {
  DeformAsset asset = *asset_;
  for (std::size_t r = 0; r < asset.render.topology_of_render.size(); ++r) {
    asset.render.normals.emplace_back(0.0, 1.0, r == 0 ? 0.5 : std::nextafter(0.0, 1.0));
  }
  DeformAsset older;
  ASSERT_NO_FATAL_FAILURE(expectOptionalSection(asset, "RNRM", older));
  EXPECT_TRUE(older.render.normals.empty());

  asset.render.normals.pop_back();
  EXPECT_NE(encodeAsset(asset).status().message().find("render normals for"), std::string::npos);
  asset.render.normals.emplace_back(0.0, 0.0, 0.0);
  EXPECT_NE(encodeAsset(asset).status().message().find("render normal " + std::to_string(asset.render.normals.size() - 1) +
                                                       " is zero or not finite"),
            std::string::npos);
}

// The render layout's TEXCOORD_0 goes in the optional RUV0 section, bit-exactly, in the same way.
TEST_F(AssetFile, RenderTexcoordsAreAnOptionalSection) {
  DeformAsset asset = *asset_;
  for (std::size_t r = 0; r < outputVertexCount(asset); ++r) {
    asset.render.uvs.emplace_back(0.1 * static_cast<double>(r), r == 0 ? -3.5 : std::nextafter(1.0, 2.0));
  }
  DeformAsset older;
  ASSERT_NO_FATAL_FAILURE(expectOptionalSection(asset, "RUV0", older));
  EXPECT_TRUE(older.render.uvs.empty());

  asset.render.uvs.pop_back();
  EXPECT_NE(encodeAsset(asset).status().message().find("render UVs for"), std::string::npos);
  asset.render.uvs.emplace_back(std::numeric_limits<double>::infinity(), 0.0);
  EXPECT_NE(encodeAsset(asset).status().message().find("render UV " + std::to_string(asset.render.uvs.size() - 1) +
                                                       " is not finite"),
            std::string::npos);
}

// A layout read from an OBJ's corners is marked by an empty ROBJ section, so OBJ frames keep the
// input's vertex order; a file without it plays in render order, as every layout did before.
TEST_F(AssetFile, ObjVertexOrderIsAnOptionalSection) {
  DeformAsset asset = *asset_;
  asset.render.obj_order = true;
  DeformAsset older;
  ASSERT_NO_FATAL_FAILURE(expectOptionalSection(asset, "ROBJ", older));
  EXPECT_FALSE(older.render.obj_order);

  asset.render = RenderLayout{};
  asset.render.obj_order = true;
  EXPECT_NE(encodeAsset(asset).status().message().find("an OBJ render layout without render vertices"), std::string::npos);
}

// The input's primitives (face runs and materials) go in the optional RPRM section; runs must
// follow each other and end at the last face.
TEST_F(AssetFile, RenderPrimitivesAreAnOptionalSection) {
  DeformAsset asset = *asset_;
  const auto faces = static_cast<std::uint32_t>(outputFaces(asset).faceCount());
  asset.render.primitives = {{faces / 2, 3}, {faces / 2, -1}, {faces, 0}};
  DeformAsset older;
  ASSERT_NO_FATAL_FAILURE(expectOptionalSection(asset, "RPRM", older));
  EXPECT_TRUE(older.render.primitives.empty());

  asset.render.primitives.back().face_end = faces - 1;
  EXPECT_NE(encodeAsset(asset).status().message().find("the render primitives end at face " + std::to_string(faces - 1)),
            std::string::npos);
  asset.render.primitives = {{faces, 0}, {faces / 2, 0}};
  EXPECT_NE(encodeAsset(asset).status().message().find("render primitive 1 ends at face"), std::string::npos);
  asset.render.primitives = {{faces, -2}};
  EXPECT_NE(encodeAsset(asset).status().message().find("with material -2"), std::string::npos);
}

// Face rows are checked as a whole, not only their indices: the runtime and the export walk them
// (fuzz_odsk, tests/fuzz/regressions/odsk/face-rows-past-the-indices.odsk: a row past the indices
// read out of bounds in RuntimeAsset::create).
TEST_F(AssetFile, FaceRowsMustSpanTheirIndices) {
  DeformAsset asset = *asset_;
  asset.faces.face_offsets.back() += 3;
  EXPECT_NE(encodeAsset(asset).status().message().find("the face rows do not span the"), std::string::npos);
  asset = *asset_;
  std::swap(asset.render.faces.face_offsets[1], asset.render.faces.face_offsets[2]);
  EXPECT_NE(encodeAsset(asset).status().message().find("render face 1 ends before it starts"), std::string::npos)
      << encodeAsset(asset).status().message();
  asset = *asset_;
  asset.faces.face_offsets.front() = 1;
  EXPECT_EQ(validateDeformAsset(asset).code(), StatusCode::kInvalidArgument);
}

TEST_F(AssetFile, MissingDuplicateOrOverrunningSectionsAreErrors) {
  const auto parts = sections(*bytes_);
  ASSERT_EQ(parts.size(), 12u);
  for (std::size_t drop = 0; drop < parts.size(); ++drop) {
    std::string payload;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (i != drop) payload += parts[i].second;
    }
    const Result<DeformAsset> r = decodeAsset(withPayload(*bytes_, payload), "partial.odsk");
    EXPECT_EQ(r.status().code(), StatusCode::kParseError) << parts[drop].first;
    EXPECT_NE(r.status().message().find("missing required section '" + parts[drop].first + "'"), std::string::npos)
        << r.status().message();
  }
  std::string payload = bytes_->substr(32) + parts[0].second;
  EXPECT_NE(decodeAsset(withPayload(*bytes_, payload), "dup").status().message().find("twice"), std::string::npos);
  // The last section claims one byte more than the payload holds.
  payload = bytes_->substr(32);
  const std::size_t last = payload.size() - parts.back().second.size();
  writeU64(payload, last + 4, parts.back().second.size() - 12 + 1);
  EXPECT_NE(decodeAsset(withPayload(*bytes_, payload), "o").status().message().find("overruns"), std::string::npos);
}

// Found by a review of the runtime API: these passed validation and played NaN positions (a
// binding of 1e300 became inf in float32, NaN on the GPU alone), with every call returning ok.
TEST_F(AssetFile, KeyPosesPivotsAndBindingsMustBeUsable) {
  const std::vector<std::pair<std::function<void(DeformAsset&)>, std::string>> cases{
      {[](DeformAsset& a) { a.key_poses[1][0].rotation.w = std::nan(""); }, "key pose 1 moves bone 0 by a non-finite"},
      {[](DeformAsset& a) { a.key_poses[0][0].translation.y = INFINITY; }, "key pose 0 moves bone 0 by a non-finite"},
      {[](DeformAsset& a) { a.key_poses[1][0].rotation *= 2.0; }, "a rotation that is not unit"},
      {[](DeformAsset& a) { a.bone_pivots[0].x = std::nan(""); }, "the pivot of bone 0 is not finite"},
      // Finite in double, inf in the float32 key paths: every vertex between keys played inf.
      {[](DeformAsset& a) { a.bone_pivots[1].y = -1e300; }, "the pivot of bone 1 is not finite or beyond float32's range"},
      {[](DeformAsset& a) { a.key_poses[1][0].translation.x = 1e300; },
       "key pose 1 moves bone 0 by a translation beyond float32's range"},
      {[](DeformAsset& a) { a.bindings[0].v = 1e300; }, "vertex 0 has an invalid curve binding"},
      {[](DeformAsset& a) { a.bindings[1].v = -0.25; }, "vertex 1 has an invalid curve binding"},
  };
  for (const auto& [change, message] : cases) {
    DeformAsset asset = *asset_;
    change(asset);
    const Status s = validateDeformAsset(asset);
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << message;
    EXPECT_NE(s.message().find(message), std::string::npos) << s.message();
  }
}

TEST_F(AssetFile, ConsistentChecksumButBadContentIsRejected) {
  auto parts = sections(*bytes_);
  // META with its modes set to 0: parses, then fails validation naming the source.
  std::string payload;
  for (auto& [tag, data] : parts) {
    if (tag == "META") data[12] = 0;
    payload += data;
  }
  Result<DeformAsset> r = decodeAsset(withPayload(*bytes_, payload), "zero_modes.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(r.status().message().rfind("zero_modes.odsk: ", 0), 0u) << r.status().message();
  // REST claiming 2^60 positions must not allocate them.
  parts = sections(*bytes_);
  payload.clear();
  for (auto& [tag, data] : parts) {
    if (tag == "REST") writeU64(data, 12, std::uint64_t{1} << 60);
    payload += data;
  }
  r = decodeAsset(withPayload(*bytes_, payload), "huge.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  EXPECT_NE(r.status().message().find("'REST'"), std::string::npos) << r.status().message();
}

// Fuzz finding (tests/fuzz/regressions/odsk/influence-offset-past-end.odsk): validation compared
// only the last influence offset with the arrays, so a middle offset past the end read out of bounds.
TEST_F(AssetFile, InfluenceOffsetPastTheArraysIsRejected) {
  auto parts = sections(*bytes_);
  std::string payload;
  for (auto& [tag, data] : parts) {
    if (tag == "INFL") {
      // section header (12), offsets count (8), offsets[0] (4): offsets[1] = 0x7fffff00.
      for (int i = 0; i < 4; ++i) data[24 + i] = static_cast<char>((0x7fffff00u >> (8 * i)) & 0xFF);
    }
    payload += data;
  }
  const Result<DeformAsset> r = decodeAsset(withPayload(*bytes_, payload), "offsets.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(r.status().message().rfind("offsets.odsk: influences: offset 2147483392 of vertex 0 is past the", 0), 0u)
      << r.status().message();
}

TEST_F(AssetFile, SavingFailsWithoutLeavingAFile) {
  const std::filesystem::path dir = scratchDir("atomic");
  const std::filesystem::path missing = dir / "no-such-folder" / "arm.odsk";
  const Status s = saveAsset(missing, *asset_);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find(missing.string()), std::string::npos) << s.message();
  EXPECT_FALSE(std::filesystem::exists(missing.parent_path()));
  // An inconsistent asset is refused before anything is written, and an existing file survives.
  const std::filesystem::path path = dir / "arm.odsk";
  ASSERT_TRUE(saveAsset(path, *asset_).ok());
  DeformAsset broken = *asset_;
  broken.bindings.pop_back();
  EXPECT_EQ(saveAsset(path, broken).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  EXPECT_TRUE(loadAsset(path).ok());
}

TEST_F(AssetFile, LoadErrorsNameThePath) {
  const std::filesystem::path dir = scratchDir("load");
  Result<DeformAsset> r = loadAsset(dir / "absent.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kIoError);
  EXPECT_NE(r.status().message().find("absent.odsk"), std::string::npos);
  EXPECT_EQ(loadAsset(dir).status().code(), StatusCode::kIoError);
  std::ofstream(dir / "empty.odsk").flush();
  r = loadAsset(dir / "empty.odsk");
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  EXPECT_NE(r.status().message().find("empty.odsk"), std::string::npos);
}

}  // namespace
}  // namespace odeskin

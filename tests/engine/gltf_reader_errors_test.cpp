// SPDX-License-Identifier: MIT
// What the glTF reader refuses, with the file and the problem named: malformed and hostile files
// (several found by fuzz_gltf, docs/reliability.md), declared sizes beyond the bytes behind them,
// and models the fit cannot use.
#include "engine/io/gltf_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "engine/gltf_tube_model.hpp"  // tests/engine
#include <tiny_gltf.h>

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using namespace testing;  // odeskin::testing: the tube model

class GltfFormats : public ::testing::TestWithParam<bool> {};  // parameter: write GLB
INSTANTIATE_TEST_SUITE_P(GltfAndGlb, GltfFormats, ::testing::Bool());

TEST(GltfReaderErrors, MaterialThatDoesNotExist) {
  tinygltf::Model model = dressedTube();
  model.meshes[0].primitives[1].material = 9;
  const auto examples = read(write(model, "bad-material.glb", true), {1.0});
  ASSERT_FALSE(examples.ok());
  EXPECT_NE(examples.status().message().find("bad-material.glb: mesh 0 primitive 1 uses material 9 of 2"), std::string::npos)
      << examples.status().message();
}

TEST(GltfReaderErrors, BytesInMemoryCannotReferToFiles) {
  tinygltf::Model model = makeTube().model;
  const fs::path path = tempDir() / "external.gltf";
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), true, false, true, false));  // buffer in external.bin
  const std::string bytes = fileBytes(path);
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples(bytes, "memory.gltf", request), StatusCode::kParseError,
              {"memory.gltf: tinygltf cannot read it", "external.bin"});
  EXPECT_TRUE(readGltfExamples(path, request).ok());  // the same file on disk finds its .bin
}

// tinygltf calls both "JSON string too short".
TEST(GltfReaderErrors, EmptyAndTinyFilesSaySo) {
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples("", "empty.gltf", request), StatusCode::kParseError, {"empty.gltf: the file is empty"});
  expectError(parseGltfExamples("{}", "braces.gltf", request), StatusCode::kParseError,
              {"braces.gltf: 2 bytes, too short to be glTF"});
  expectError(parseGltfExamples("{}  ", "spaced.gltf", request), StatusCode::kParseError,
              {"spaced.gltf: tinygltf cannot read it", "\"asset\""});
}

// Found with the fuzz target (tests/fuzz/regressions/gltf/unbacked-position-count.gltf): an
// accessor without a bufferView is zeros, and 300 bytes of JSON declared 44.7M of them (over 2 GB
// with the copies behind it). Its count may not exceed one element per byte of the file's buffers.
TEST(GltfReaderErrors, UnbackedAccessorCountIsBoundedByTheBuffers) {
  const std::string json = R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"componentType":5126,"count":44739240,"type":"VEC3","min":[0,0,0],"max":[0,0,0]}]})";
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples(json, "unbacked.gltf", request), StatusCode::kParseError,
              {"unbacked.gltf: ", "count 44739240 without a bufferView is beyond the limit of 65536"});
}

// Primitives, morph targets and animation channels may each repeat what a few bytes declare, and
// every repetition is decoded again: what one read decodes is bounded by 32 values per byte of the
// file's buffers, and 2^24 in any case. A primitive below decodes 65,535 x 3 zeros and as many
// triangle corners (262,140 values), so with accessors of their own primitive 64 is the first past
// 2^24. Primitives over the same accessor share their vertices and decode only their 65,535
// corners again, so there primitive 253 is the first.
TEST(GltfReaderErrors, RepeatedPrimitivesAreBoundedByTheBuffers) {
  for (const bool shared : {false, true}) {
    const int count = shared ? 300 : 70;
    std::string primitives, accessors;
    for (int p = 0; p < count; ++p) {
      const std::string separator = p > 0 ? "," : "";
      primitives += separator + R"({"attributes":{"POSITION":)" + std::to_string(shared ? 0 : p) + "}}";
      if (shared && p > 0) continue;
      accessors += separator + R"({"componentType":5126,"count":65535,"type":"VEC3","min":[0,0,0],"max":[0,0,0]})";
    }
    const std::string json = R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],"meshes":[{"primitives":[)" + primitives +
                             R"(]}],"accessors":[)" + accessors + "]}";
    GltfPoseRequest request;
    request.min_poses = 1;
    const std::string first_past = shared ? "repeated.gltf: mesh 0 primitive 253 unindexed triangles: its 65535 values"
                                          : "repeated.gltf: accessor 64 (mesh 0 primitive 64 POSITION): its 196605 values";
    expectError(parseGltfExamples(json, "repeated.gltf", request), StatusCode::kParseError,
                {first_past, "past 16777216 values (32 per byte of its buffers, at least 16777216)", "repeat too often"});
  }
}

// A target without POSITION costs nothing in the file but 3 zeros per vertex in memory.
TEST(GltfReaderErrors, EmptyMorphTargetsAreBoundedByTheBuffers) {
  std::string targets;
  for (int t = 0; t < 90; ++t) targets += std::string(t > 0 ? "," : "") + "{}";
  const std::string json = std::string(R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0}],"meshes":[{"primitives":[)") +
                           R"({"attributes":{"POSITION":0},"targets":[)" + targets +
                           R"(]}]}],"accessors":[{"componentType":5126,"count":65535,"type":"VEC3",)" +
                           R"("min":[0,0,0],"max":[0,0,0]}]})";
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples(json, "targets.gltf", request), StatusCode::kParseError,
              {"targets.gltf: mesh 0 primitive 0 target 84 (zeros: no POSITION): its 196605 values", "repeat too often"});
}

// 200 channels of one sampler of 65,536 keys (1 MiB of the buffer): each channel decodes the
// sampler again, 262,144 values, and the budget (32 per byte, 33,588,224 values) runs out at
// channel 128; the same animation with one channel reads.
TEST(GltfReaderErrors, RepeatedAnimationChannelsAreBoundedByTheBuffers) {
  Tube tube = makeTube();
  Builder b;
  b.model = std::move(tube.model);
  std::vector<double> times(65536);
  std::vector<double> shifts(3 * times.size(), 0.0);
  for (std::size_t k = 0; k < times.size(); ++k) times[k] = 0.001 * static_cast<double>(k);
  tinygltf::Animation slide;
  slide.name = "slide";
  addChannel(b, slide, 1, "translation", "LINEAR", times, shifts, TINYGLTF_TYPE_VEC3);
  b.model.animations.push_back(slide);
  EXPECT_TRUE(read(write(b.model, "few.glb", true), {1.0}, {}, "slide").ok());
  for (int c = 0; c < 199; ++c) b.model.animations.back().channels.push_back(b.model.animations.back().channels[0]);
  expectError(read(write(b.model, "many.glb", true), {1.0}, {}, "slide"), StatusCode::kParseError,
              {"many.glb: accessor 17 (animation 3 channel 128 input): its 65536 values", "repeat too often"});
}

TEST(GltfReaderErrors, MissingFile) {
  const fs::path path = tempDir() / "absent.glb";
  expectError(read(path, {1.0}), StatusCode::kIoError, {path.string()});
}

TEST(GltfReaderErrors, TruncatedGlb) {
  const fs::path path = write(makeTube().model, "truncated.glb", true);
  const std::string bytes = fileBytes(path);
  ASSERT_GT(bytes.size(), 100u);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  }
  expectError(read(path, {1.0}), StatusCode::kParseError, {path.string(), "tinygltf"});
}

// Found reading tinygltf's GLB checks while instrumenting it for the fuzz build, and confirmed by
// ASan there (tests/fuzz/regressions/gltf/bin-chunk-past-end.glb): tinygltf 2.7 compares a BIN chunk's length with the file's without the chunk's 8-byte header,
// so a file cut by 8 bytes (and its total length fixed up) read 8 bytes from past its end into
// the buffer, and the picture or fit went ahead. Both readers now refuse it.
TEST(GltfReaderErrors, BinChunkPastTheEndIsRefused) {
  const fs::path whole = write(makeTube().model, "whole.glb", true);
  std::string bytes = fileBytes(whole);
  bytes.resize(bytes.size() - 8);
  const auto length = static_cast<std::uint32_t>(bytes.size());
  std::memcpy(bytes.data() + 8, &length, 4);  // the header's total length, little-endian like the file
  const fs::path cut = tempDir() / "cut.glb";
  {
    std::ofstream out(cut, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  expectError(read(cut, {1.0}), StatusCode::kParseError,
              {cut.string() + ": the GLB's second chunk declares", "past the end of its " + std::to_string(length) + " bytes"});
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples(bytes, "cut.glb", request), StatusCode::kParseError,
              {"cut.glb: the GLB's second chunk declares"});
  EXPECT_TRUE(read(whole, {1.0}).ok());
}

// tinygltf 2.7 fills every buffer without a uri with a copy of the BIN chunk: 2,000 of them in
// a 2 MB GLB asked for 4 GB. Only the first buffer may stand for the chunk; a second is refused.
TEST(GltfReaderErrors, SecondBufferWithoutUriIsRefused) {
  const fs::path whole = write(makeTube().model, "whole.glb", true);
  const std::string glb = fileBytes(whole);
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  nlohmann::json doc = nlohmann::json::parse(glb.substr(20, json_length));
  ASSERT_TRUE(doc["buffers"].is_array() && !doc["buffers"][0].contains("uri"));
  doc["buffers"].push_back({{"byteLength", 4}});
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string bytes = glb.substr(0, 12);
  const auto new_json_length = static_cast<std::uint32_t>(json.size());
  bytes.append(reinterpret_cast<const char*>(&new_json_length), 4);
  bytes += "JSON" + json + glb.substr(20 + json_length);
  const auto total = static_cast<std::uint32_t>(bytes.size());
  std::memcpy(bytes.data() + 8, &total, 4);
  GltfPoseRequest request;
  request.min_poses = 1;
  expectError(parseGltfExamples(bytes, "two-bins.glb", request), StatusCode::kParseError,
              {"two-bins.glb: buffers 0 and 1 both have no uri"});
  const fs::path path = tempDir() / "two-bins.glb";
  {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  expectError(read(path, {1.0}), StatusCode::kParseError, {path.string() + ": buffers 0 and 1 both have no uri"});
}

// tinygltf 2.7 takes the address of an image's first byte in its buffer without checking that
// the bufferView lies inside it (odeskin skips images, but the address itself is out of bounds).
TEST_P(GltfFormats, ImageViewOutsideItsBufferIsRefused) {
  Tube tube = makeTube();
  tinygltf::Model& m = tube.model;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = m.buffers[0].data.size() + 100;
  view.byteLength = 4;
  m.bufferViews.push_back(view);
  tinygltf::Image image;
  image.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  image.mimeType = "image/png";
  m.images.push_back(image);
  const fs::path path = write(m, GetParam() ? "image.glb" : "image.gltf", GetParam());
  expectError(read(path, {1.0}), StatusCode::kParseError,
              {path.string() + ": image 0's bufferView " + std::to_string(image.bufferView) + " (byteOffset " +
               std::to_string(view.byteOffset) + ", byteLength 4) lies outside buffer 0"});
  if (!GetParam()) {  // the key spelt with an escape is the same key
    std::string json = fileBytes(path);
    const std::size_t key = json.find("\"images\"");
    ASSERT_NE(key, std::string::npos);
    json.replace(key, 8, "\"\\u0069mages\"");
    GltfPoseRequest request;
    request.min_poses = 1;
    expectError(parseGltfExamples(json, "escaped.gltf", request), StatusCode::kParseError,
                {"escaped.gltf: image 0's bufferView"});
  }
  m.bufferViews.back().byteOffset = 0;  // inside: the image is skipped and the tube reads
  EXPECT_TRUE(read(write(m, GetParam() ? "inside.glb" : "inside.gltf", GetParam()), {1.0}).ok());
}

// tinygltf 2.7 copies "extras" into its own Value type one stack frame per level: 200,000 nested
// arrays (a 400 KB file) crashed odeskin render with a stack overflow. JSON may nest 256 deep.
TEST(GltfReaderErrors, DeeplyNestedJsonIsRefused) {
  const std::string json = fileBytes(write(makeTube().model, "tube.gltf", false));
  const auto nested = [&json](int levels) {  // "extras" of the asset, `levels` arrays deep in all
    nlohmann::json doc = nlohmann::json::parse(json);
    nlohmann::json extras = 1;
    for (int k = 0; k < levels - 2; ++k) extras = nlohmann::json::array({extras});
    doc["asset"]["extras"] = extras;
    return doc.dump();
  };
  GltfPoseRequest request;
  request.min_poses = 1;
  EXPECT_TRUE(parseGltfExamples(nested(256), "256.gltf", request).ok());
  expectError(parseGltfExamples(nested(257), "257.gltf", request), StatusCode::kParseError,
              {"257.gltf: its JSON nests 257 levels deep, beyond the 256 odeskin reads"});
  const std::string deep = R"({"asset":{"version":"2.0","extras":)" + std::string(200000, '[') + "1" +
                           std::string(200000, ']') + "}}";
  expectError(parseGltfExamples(deep, "deep.gltf", request), StatusCode::kParseError,
              {"deep.gltf: its JSON nests 200002 levels deep"});
}

// tinygltf 2.7's own file callbacks opened any path a URI named and read it whole before comparing
// sizes: a buffer naming a FIFO blocked the read forever, and one naming a file of many gigabytes
// read all of it. External files must be regular and at most 2 GiB.
TEST(GltfReaderErrors, ExternalBuffersMustBeRegularFilesUpTo2GiB) {
  tinygltf::Model model = makeTube().model;
  const fs::path dir = tempDir();
  const fs::path path = dir / "tube.gltf";
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), true, false, true, false));  // buffer in its own .bin
  const std::string json = fileBytes(path);
  nlohmann::json doc = nlohmann::json::parse(json);
  ASSERT_TRUE(doc["buffers"][0].contains("uri"));
  ASSERT_TRUE(read(path, {1.0}).ok());
  const auto pointAt = [&](const std::string& uri, std::uint64_t bytes) {
    doc["buffers"][0]["uri"] = uri;
    doc["buffers"][0]["byteLength"] = bytes;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << doc.dump();
  };

  const fs::path fifo = dir / "pipe.bin";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  pointAt("pipe.bin", doc["buffers"][0]["byteLength"].get<std::uint64_t>());
  expectError(read(path, {1.0}), StatusCode::kParseError,
              {path.string() + ": tinygltf cannot read it", "pipe.bin", "not a regular file"});
  fs::remove(fifo);

  const fs::path huge = dir / "huge.bin";
  std::ofstream(huge, std::ios::binary).close();
  fs::resize_file(huge, (std::uintmax_t{1} << 31) + 8);  // sparse: no disk space is used
  pointAt("huge.bin", (std::uint64_t{1} << 31) + 8);
  expectError(read(path, {1.0}), StatusCode::kParseError,
              {"huge.bin", "2147483656 bytes, over the 2 GiB tinygltf 2.7 can read"});
  fs::remove(huge);
}

TEST(GltfReaderErrors, MalformedJson) {
  const fs::path path = tempDir() / "broken.gltf";
  std::ofstream(path) << "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [";
  expectError(read(path, {1.0}), StatusCode::kParseError, {path.string(), "tinygltf"});
}

// tinygltf quotes the failing buffer's URI: a data: URI is the whole buffer in base64, and the
// message was kilobytes long (megabytes for a real mesh). It keeps the head and says how long it was.
TEST(GltfReaderErrors, ADataUriInAnErrorIsCutShort) {
  const fs::path embedded = write(makeTube().model, "embedded.gltf", false);
  nlohmann::json json = nlohmann::json::parse(fileBytes(embedded));
  ASSERT_EQ(json["buffers"][0]["uri"].get<std::string>().rfind("data:", 0), 0u);
  json["buffers"][0]["byteLength"] = json["buffers"][0]["byteLength"].get<std::size_t>() + 40;  // more than the URI holds
  const fs::path path = tempDir() / "short-data.gltf";
  std::ofstream(path) << json.dump();
  const auto examples = read(path, {1.0});
  expectError(examples, StatusCode::kParseError, {path.string(), "tinygltf cannot read it", " characters)"});
  EXPECT_LT(examples.status().message().size(), 400u) << examples.status().message();
}

TEST(GltfReaderErrors, UnknownAnimationListsTheAvailableOnes) {
  const fs::path path = write(makeTube().model, "tube.gltf", false);
  expectError(read(path, {1.0}, {}, "walk"), StatusCode::kInvalidArgument, {path.string(), "walk", "bend", "wiggle", "squash"});
  expectError(read(path, {1.0}, {}, "3"), StatusCode::kInvalidArgument, {"'3'"});
}

TEST(GltfReaderErrors, UnimplementedRequiredExtensionIsNamed) {
  tinygltf::Model model = makeTube().model;
  model.extensionsUsed.push_back("KHR_draco_mesh_compression");
  model.extensionsRequired.push_back("KHR_draco_mesh_compression");
  expectError(read(write(model, "draco.glb", true), {1.0}), StatusCode::kInvalidArgument, {"KHR_draco_mesh_compression"});
}

TEST(GltfReaderErrors, JointIndexOutOfRange) {
  TubeOptions o;
  o.tweak = [](Prim& p) { p.joints0[3][1] = 7; };
  expectError(read(write(makeTube(o).model, "joints.gltf", false), {1.0}), StatusCode::kParseError,
              {"render vertex 3", "joint 7", "2 joints"});
}

TEST(GltfReaderErrors, AccessorOutOfBufferBounds) {
  Tube tube = makeTube();
  tinygltf::Accessor& a = tube.model.accessors[static_cast<std::size_t>(tube.position_accessor)];
  a.byteOffset = 12;  // the last vertex now runs past its bufferView
  const std::string name = "accessor " + std::to_string(tube.position_accessor);
  expectError(read(write(tube.model, "offset.glb", true), {1.0}), StatusCode::kParseError, {name, "POSITION", "past the end"});
  a.byteOffset = 0;
  tube.model.bufferViews[static_cast<std::size_t>(a.bufferView)].byteLength = 1u << 20;  // past the buffer
  expectError(read(write(tube.model, "view.glb", true), {1.0}), StatusCode::kParseError, {name, "past the end of buffer"});
}

TEST(GltfReaderErrors, FewerThanTwoPoses) {
  const fs::path path = write(makeTube().model, "tube.gltf", false);
  expectError(read(path, {}), StatusCode::kInvalidArgument, {"at least 2"});
  GltfPoseRequest request;
  request.include_bind_pose = false;
  request.times = {1.0};
  expectError(readGltfExamples(path, request), StatusCode::kInvalidArgument, {"at least 2"});
}

// An unskinned mesh has poses at times too (odeskin's own baked files are weights animations of
// one); they come without a rig.
TEST(GltfReaderErrors, TimesOfAnUnskinnedMeshComeWithoutARig) {
  tinygltf::Model model = makeTube().model;
  model.nodes[0].skin = -1;
  const auto timed = read(write(model, "unskinned.gltf", false), {1.0});
  ASSERT_TRUE(timed.ok()) << timed.status().toString();
  EXPECT_FALSE(timed->rig.has_value());
  EXPECT_EQ(timed->poses.size(), 2u);  // the bind pose, then the one at 1 s
  model.animations.clear();
  expectError(read(write(model, "still.gltf", false), {1.0}), StatusCode::kInvalidArgument,
              {"poses at times need an animation, and the file has none"});
  // Morph targets alone still read, without a rig.
  const auto examples = read(write(model, "unskinned.gltf", false), {}, {0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_FALSE(examples->rig.has_value());
}

// Where the joints' rest transforms and the inverse bind matrices do not cancel, viewers show the
// file at rest otherwise than the bind mesh odeskin takes as key 0: read, with a warning naming the joint.
TEST(GltfReaderErrors, ARestPoseAwayFromTheBindMeshIsWarnedOf) {
  tinygltf::Model model = makeTube().model;
  const auto restWarnings = [](const ExampleSet& examples) {
    std::vector<std::string> out;
    std::copy_if(examples.warnings.begin(), examples.warnings.end(), std::back_inserter(out),
                 [](const std::string& w) { return w.find("rest pose") != std::string::npos; });
    return out;
  };
  const auto matched = read(write(model, "rest-matched.gltf", false), {1.0});
  ASSERT_TRUE(matched.ok()) << matched.status().toString();
  EXPECT_TRUE(restWarnings(*matched).empty()) << restWarnings(*matched).front();
  model.nodes[2].translation = {0.0, 1.5, 0.0};  // the tip's rest; its inverse bind matrix still undoes 1
  const auto moved = read(write(model, "rest-moved.gltf", false), {1.0});
  ASSERT_TRUE(moved.ok()) << moved.status().toString();
  const std::vector<std::string> warned = restWarnings(*moved);
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_NE(warned[0].find("the nodes' rest pose moves the mesh by up to "), std::string::npos) << warned[0];
  EXPECT_NE(warned[0].find("(joint 1 'tip': its inverse bind matrix does not undo its rest transform)"), std::string::npos)
      << warned[0];
}

TEST(GltfReaderErrors, OnlyTriangles) {
  tinygltf::Model model = makeTube().model;
  model.meshes[0].primitives[0].mode = TINYGLTF_MODE_TRIANGLE_STRIP;
  expectError(read(write(model, "strip.gltf", false), {1.0}), StatusCode::kParseError, {"mode 5", "TRIANGLES"});
}

TEST(GltfReaderErrors, WeightsSummingToZero) {
  TubeOptions o;
  o.tweak = [](Prim& p) { p.weights0[6] = {0, 0, 0, 0}; };
  expectError(read(write(makeTube(o).model, "zero.gltf", false), {1.0}), StatusCode::kParseError, {"render vertex 6", "sum to 0"});
}

// Weights that do not sum to 1 are scaled to, as three.js does, and counted in a warning: glTF
// forbids them, and renderers that skin them as stored would show another shape.
TEST(GltfReaderErrors, WeightsNotSummingToOneAreScaledWithAWarning) {
  TubeOptions o;
  o.tweak = [](Prim& p) {
    for (auto& w : p.weights0) {
      for (auto& x : w) x *= 0.5;
    }
  };
  const auto halved = read(write(makeTube(o).model, "halved.gltf", false), {1.0});
  ASSERT_TRUE(halved.ok()) << halved.status().toString();
  ASSERT_EQ(halved->warnings.size(), 1u);
  const std::string all = std::to_string(halved->render.topology_of_render.size());
  EXPECT_NE(halved->warnings[0].find("halved.gltf: the skin weights of " + all +
                                     " render vertices do not sum to 1 (vertex 0: 0.5); they are scaled to sum to 1"),
            std::string::npos)
      << halved->warnings[0];
  const auto whole = read(write(makeTube().model, "whole.gltf", false), {1.0});
  ASSERT_TRUE(whole.ok()) << whole.status().toString();
  EXPECT_TRUE(whole->warnings.empty()) << whole->warnings.front();
  ASSERT_TRUE(halved->rig && whole->rig);
  EXPECT_EQ(halved->rig->influences.weights, whole->rig->influences.weights);
}

TEST(GltfReaderErrors, WeldedCopiesWithDifferentWeights) {
  TubeOptions o;
  o.tweak = [](Prim& p) { p.weights0[9] = {0.5, 0.5, 0, 0}; };  // ring 1's seam copy of vertex 5 (1:3 there)
  expectError(read(write(makeTube(o).model, "seam.gltf", false), {1.0}), StatusCode::kParseError,
              {"topology vertex 4", "render vertices 5 and 9"});
}

TEST(GltfReaderErrors, ScalingJointIsNotARigidKeyPose) {
  const fs::path path = write(makeTube().model, "squash.gltf", false);
  expectError(read(path, {1.0}, {}, "squash"), StatusCode::kInvalidArgument, {"joint 1 'tip'", "squash.gltf squash at 1 s"});
}

TEST(GltfReaderErrors, MorphTargetOutOfRange) {
  expectError(read(write(makeTube().model, "tube.gltf", false), {}, {1}), StatusCode::kInvalidArgument, {"morph target 1"});
}

}  // namespace
}  // namespace odeskin

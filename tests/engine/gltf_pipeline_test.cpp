// SPDX-License-Identifier: MIT
// glTF input through the whole pipeline: the tube model's poses fitted, stored in an .odsk file,
// played and exported again, keeping the render layout, normals, texture coordinates, primitives
// and (with --materials) materials of the input.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/export/gltf_export.hpp"
#include "engine/gltf_tube_model.hpp"  // tests/engine
#include "engine/io/asset_file.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/offline/deform_player.hpp"
#include "engine/one_pixel_png.hpp"  // tests/engine
#include "engine/pipeline/fit_pipeline.hpp"
#include "engine/runtime/runtime_asset.hpp"
#include <tiny_gltf.h>

namespace odeskin {
namespace {

namespace fs = std::filesystem;
using namespace testing;  // odeskin::testing: the tube model

// The examples fitted, stored as an .odsk file's bytes and read back: the asset a loader hands to
// the exports and the runtime.
Result<DeformAsset> fittedThroughAssetFile(const ExampleSet& examples, const std::string& name) {
  ODESKIN_ASSIGN_OR_RETURN(const PipelineResult fit, runFitPipeline(examples, PipelineOptions{}));
  ODESKIN_ASSIGN_OR_RETURN(const std::string bytes, encodeAsset(fit.asset));
  return decodeAsset(bytes, name);
}

// End to end: the animated glTF's poses become an asset whose playback hits every key, and the asset
// keeps the seam-split render layout so play writes the input's vertices.
TEST(GltfPipeline, FittedAssetReproducesAnimatedPosesInRenderLayout) {
  const Tube tube = makeTube();
  const auto examples = read(write(tube.model, "pipeline.glb", true), {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  EXPECT_EQ(fit->asset.render.topology_of_render.size(), tube.render_positions.size());
  Result<DeformPlayer> player = DeformPlayer::create(fit->asset);
  ASSERT_TRUE(player.ok());
  std::vector<Vec3> out(fit->asset.vertexCount());
  for (std::size_t k = 0; k < examples->poses.size(); ++k) {
    const auto [segment, tau] = player->locate(static_cast<double>(k));
    ASSERT_TRUE(player->play(fit->asset, segment, tau, out).ok());
    for (std::size_t i = 0; i < out.size(); ++i) {
      EXPECT_LT(glm::length(out[i] - examples->poses[k][i]), 1e-4 * longestBoxSide(examples->poses[k])) << k;
    }
  }
}

// The bind normals travel from the glTF through the fit and the .odsk file to the runtime, which
// finds the hard edge of the seam (one per ring) and none where the seam is only a UV seam.
TEST(GltfPipeline, HardEdgesSurviveTheFitAndTheAssetFile) {
  for (const bool hard_seam : {true, false}) {
    TubeOptions o;
    o.normal = [hard_seam](int, int column) { return cornerNormal(column, hard_seam); };
    const auto examples = read(write(makeTube(o).model, "hard.glb", true), {0.5, 1.0});
    ASSERT_TRUE(examples.ok()) << examples.status().toString();
    Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
    ASSERT_TRUE(fit.ok()) << fit.status().toString();
    ASSERT_EQ(fit->asset.render.normals, examples->render.normals);
    Result<std::string> bytes = encodeAsset(fit->asset);
    ASSERT_TRUE(bytes.ok());
    Result<DeformAsset> loaded = decodeAsset(*bytes, "hard.odsk");
    ASSERT_TRUE(loaded.ok()) << loaded.status().toString();
    EXPECT_EQ(loaded->render.normals, fit->asset.render.normals);
    Result<RuntimeAsset> runtime_asset = RuntimeAsset::create(*loaded);
    ASSERT_TRUE(runtime_asset.ok()) << runtime_asset.status().toString();
    EXPECT_EQ(runtime_asset->hasHardEdges(), hard_seam);
    EXPECT_EQ(runtime_asset->hardEdgeVertices(), hard_seam ? 3u : 0u);
  }
}

tinygltf::Model loadWritten(const fs::path& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) << err;
  return model;
}

// The float VEC2 TEXCOORD_0 of mesh 0's first primitive in a written .glb.
std::vector<Vec2> writtenTexcoords(const fs::path& path) {
  const tinygltf::Model model = loadWritten(path);
  const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
  if (prim.attributes.count("TEXCOORD_0") == 0) return {};
  const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(prim.attributes.at("TEXCOORD_0")));
  EXPECT_EQ(a.componentType, kFloatType);
  EXPECT_EQ(a.type, TINYGLTF_TYPE_VEC2);
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const unsigned char* data = model.buffers.at(static_cast<std::size_t>(view.buffer)).data.data() + view.byteOffset + a.byteOffset;
  std::vector<Vec2> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    float uv[2];
    std::memcpy(uv, data + 8 * i, sizeof uv);
    out[i] = Vec2(uv[0], uv[1]);
  }
  return out;
}

// The input's TEXCOORD_0 travels through the fit and the .odsk file to both forms of `export`, so
// a textured character keeps its texture mapping in the file an artist opens elsewhere.
TEST(GltfPipeline, TexcoordsReachTheExports) {
  const auto examples = read(write(makeTube().model, "textured.glb", true), {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  const Result<DeformAsset> loaded = fittedThroughAssetFile(*examples, "textured.odsk");
  ASSERT_TRUE(loaded.ok()) << loaded.status().toString();
  EXPECT_EQ(loaded->render.uvs, examples->render.uvs);
  for (const bool bake : {false, true}) {
    GltfExportOptions options;
    options.bake = bake;
    const fs::path out = tempDir() / (bake ? "textured-baked.glb" : "textured-export.glb");
    ASSERT_TRUE(exportGltf(*loaded, out, options).ok());
    EXPECT_EQ(writtenTexcoords(out), examples->render.uvs) << out;  // the inputs are exact in float32
  }
}

// The input's primitives and their materials survive the fit and the .odsk file, and
// `--materials` puts the input's materials, textures and images back on them in both forms of the
// export, image bytes unchanged.
TEST(GltfPipeline, MaterialsDressTheExports) {
  const fs::path source = write(dressedTube(), "dressed.glb", true);
  const auto examples = read(source, {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const std::vector<RenderPrimitive> expected{{static_cast<std::uint32_t>(2 * (kColumns - 1)), 0},
                                              {static_cast<std::uint32_t>(4 * (kColumns - 1)), 1}};
  EXPECT_EQ(examples->render.primitives, expected);
  const Result<DeformAsset> loaded = fittedThroughAssetFile(*examples, "dressed.odsk");
  ASSERT_TRUE(loaded.ok()) << loaded.status().toString();
  EXPECT_EQ(loaded->render.primitives, expected);
  for (const bool bake : {false, true}) {
    GltfExportOptions options;
    options.bake = bake;
    options.materials = source;
    const fs::path out = tempDir() / (bake ? "dressed-baked.glb" : "dressed-export.glb");
    Result<GltfExportReport> report = exportGltf(*loaded, out, options);
    ASSERT_TRUE(report.ok()) << report.status().toString();
    EXPECT_EQ(report->materials, 2u);
    EXPECT_EQ(report->images, 1u);
    const tinygltf::Model written = loadWritten(out);
    ASSERT_EQ(written.meshes.at(0).primitives.size(), 2u) << out;
    EXPECT_EQ(written.meshes[0].primitives[0].material, 0);
    EXPECT_EQ(written.meshes[0].primitives[1].material, 1);
    EXPECT_EQ(written.meshes[0].primitives[0].attributes, written.meshes[0].primitives[1].attributes)
        << "the primitives share their vertices";
    ASSERT_EQ(written.materials.size(), 2u);
    EXPECT_EQ(written.materials[0].name, "skin");
    EXPECT_EQ(written.materials[1].name, "cloth");
    EXPECT_EQ(written.materials[0].pbrMetallicRoughness.baseColorTexture.extensions.count("KHR_texture_transform"), 1u);
    EXPECT_EQ(written.materials[1].extensions.count("KHR_materials_emissive_strength"), 1u);
    EXPECT_EQ(written.extensionsUsed, (std::vector<std::string>{"KHR_texture_transform", "KHR_materials_emissive_strength"}));
    ASSERT_EQ(written.images.size(), 1u);
    EXPECT_EQ(written.images[0].mimeType, "image/png");
    EXPECT_EQ(written.images[0].name, "skin-colour");
    const tinygltf::BufferView& view = written.bufferViews.at(static_cast<std::size_t>(written.images[0].bufferView));
    const auto* data = written.buffers[0].data.data() + view.byteOffset;
    EXPECT_TRUE(view.byteLength == kOnePixelPng.size() && std::equal(kOnePixelPng.begin(), kOnePixelPng.end(), data));
    ASSERT_EQ(written.textures.size(), 1u);
    EXPECT_EQ(written.samplers.at(0).magFilter, TINYGLTF_TEXTURE_FILTER_NEAREST);
  }
  // The same file written without materials still splits the mesh as the input did.
  const fs::path plain = tempDir() / "undressed.glb";
  ASSERT_TRUE(exportGltf(*loaded, plain, GltfExportOptions{}).ok());
  const tinygltf::Model written = loadWritten(plain);
  ASSERT_EQ(written.meshes.at(0).primitives.size(), 2u);
  EXPECT_EQ(written.meshes[0].primitives[0].material, -1);
  EXPECT_TRUE(written.materials.empty() && written.images.empty());
}

// odeskin's exports split a mesh into primitives over one set of vertex arrays. Read back, those
// primitives share their render vertices: a file fitted, exported and fitted again keeps its
// vertex count, where copying each primitive's arrays doubled it.
TEST(GltfPipeline, PrimitivesOverTheSameAccessorsShareTheirVertices) {
  const auto examples = read(write(dressedTube(), "split.glb", true), {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  const fs::path exported = tempDir() / "split-export.glb";
  ASSERT_TRUE(exportGltf(fit->asset, exported, GltfExportOptions{}).ok());
  const tinygltf::Model written = loadWritten(exported);
  ASSERT_EQ(written.meshes.at(0).primitives.size(), 2u);
  ASSERT_EQ(written.meshes[0].primitives[0].attributes, written.meshes[0].primitives[1].attributes);
  GltfPoseRequest request;
  request.min_poses = 1;
  Result<ExampleSet> back = readGltfExamples(exported, request);
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->render.topology_of_render, examples->render.topology_of_render);
  EXPECT_EQ(back->render.faces.indices, examples->render.faces.indices);
  ASSERT_EQ(back->render.primitives.size(), examples->render.primitives.size());
  for (std::size_t p = 0; p < back->render.primitives.size(); ++p) {
    EXPECT_EQ(back->render.primitives[p].face_end, examples->render.primitives[p].face_end);  // no --materials: none
  }
  EXPECT_EQ(back->rest_positions.size(), examples->rest_positions.size());
}

// What --materials cannot use is refused before anything is written, naming the file.
TEST(GltfPipeline, MaterialsThatDoNotFitAreRefused) {
  const fs::path source = write(dressedTube(), "two-materials.glb", true);
  const auto examples = read(source, {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  auto refused = [](const DeformAsset& asset, const fs::path& materials, const std::string& message) {
    GltfExportOptions options;
    options.materials = materials;
    const fs::path out = tempDir() / "refused.glb";
    fs::remove(out);  // the folder outlives a run
    Result<GltfExportReport> report = exportGltf(asset, out, options);
    ASSERT_FALSE(report.ok());
    EXPECT_NE(report.status().message().find(message), std::string::npos) << report.status().message();
    EXPECT_FALSE(fs::exists(out));
  };
  // A file with fewer materials than the asset's primitives used.
  tinygltf::Model one = dressedTube();
  one.materials.pop_back();
  refused(fit->asset, write(one, "one-material.glb", true),
          "one-material.glb: has 1 materials, but the asset's primitive 1 used material 1");
  // An asset that recorded no materials (fitted from OBJ, or before odeskin kept them) takes a
  // file's only material, and no choice among several.
  DeformAsset unrecorded = fit->asset;
  unrecorded.render.primitives.clear();
  refused(unrecorded, source, "two-materials.glb: has 2 materials, and the asset does not record which its primitives used");
  const fs::path out = tempDir() / "one.glb";
  GltfExportOptions options;
  options.materials = tempDir() / "one-material.glb";
  ASSERT_TRUE(exportGltf(unrecorded, out, options).ok());
  EXPECT_EQ(loadWritten(out).meshes.at(0).primitives.at(0).material, 0);
  // No materials at all; an image whose file is missing.
  tinygltf::Model none = dressedTube();
  none.materials.clear();
  for (auto& p : none.meshes[0].primitives) p.material = -1;
  refused(fit->asset, write(none, "no-materials.glb", true), "no-materials.glb: has no materials to copy");
  refused(fit->asset, write(dressedTube(true), "external-image.gltf", false),
          "external-image.gltf: image 0 (skin-colour.png) cannot be read");
  refused(fit->asset, tempDir() / "absent.glb", "absent.glb");
  // References the file cannot resolve, and an image cut short: copied, they made invalid outputs.
  tinygltf::Model dangling = dressedTube();
  dangling.materials[0].pbrMetallicRoughness.baseColorTexture.index = 9;
  refused(fit->asset, write(dangling, "dangling-texture.glb", true),
          "dangling-texture.glb: material 0 'skin': baseColorTexture names texture 9, and the file has 1");
  tinygltf::Model sourceless = dressedTube();
  sourceless.textures[0].source = 4;
  refused(fit->asset, write(sourceless, "dangling-image.glb", true),
          "dangling-image.glb: texture 0 names image 4, and the file has 1");
  tinygltf::Model cut = dressedTube();
  cut.bufferViews.at(static_cast<std::size_t>(cut.images[0].bufferView)).byteLength = 20;
  refused(fit->asset, write(cut, "cut-image.glb", true), "cut-image.glb: image 0 is not a whole png file");
}

// A mesh without texture coordinates cannot map a texture, and glTF refuses a textured material on
// it: the materials come without their textures (and the texture extensions), with their factors.
TEST(GltfPipeline, MaterialsOnAMeshWithoutTexcoordsLoseTheirTextures) {
  const fs::path source = write(dressedTube(), "textured-source.glb", true);
  const auto examples = read(source, {0.5, 1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  DeformAsset uv_less = fit->asset;
  uv_less.render.uvs.clear();
  GltfExportOptions options;
  options.materials = source;
  const fs::path out = tempDir() / "uv-less.glb";
  Result<GltfExportReport> report = exportGltf(uv_less, out, options);
  ASSERT_TRUE(report.ok()) << report.status().toString();
  EXPECT_EQ(report->untextured_materials, 1u);
  const tinygltf::Model written = loadWritten(out);
  EXPECT_EQ(written.meshes.at(0).primitives.at(0).attributes.count("TEXCOORD_0"), 0u);
  ASSERT_EQ(written.materials.size(), 2u);
  EXPECT_EQ(written.materials[0].pbrMetallicRoughness.baseColorTexture.index, -1);
  EXPECT_EQ(written.materials[1].extensions.count("KHR_materials_emissive_strength"), 1u);
  EXPECT_TRUE(written.textures.empty() && written.images.empty() && written.samplers.empty());
  EXPECT_EQ(written.extensionsUsed, (std::vector<std::string>{"KHR_materials_emissive_strength"}));
  // With its texture coordinates, nothing is dropped.
  Result<GltfExportReport> textured = exportGltf(fit->asset, tempDir() / "textured.glb", options);
  ASSERT_TRUE(textured.ok()) << textured.status().toString();
  EXPECT_EQ(textured->untextured_materials, 0u);
}

}  // namespace
}  // namespace odeskin

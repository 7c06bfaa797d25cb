// SPDX-License-Identifier: MIT
// `odeskin rig` on a glTF input (issue 8), called as the program calls it: the cylinder written as a
// textured glTF split at a seam into two primitives with two materials. The rig must be the one the
// same mesh gives as plain arrays, and --gltf must give the mesh back with its look and a new skin.
#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "engine/io/gltf_baked_writer.hpp"
#include "engine/io/gltf_reader.hpp"
#include "engine/io/libigl_io.hpp"
#include "engine/io/obj_io.hpp"
#include "engine/io/obj_reader.hpp"
#include "engine/rig/curve_rig.hpp"
#include "engine/data_mesh.hpp"  // tests/engine
#include "engine/float_rounding.hpp"  // tests/engine
#include "engine/one_pixel_png.hpp"  // tests/engine
#include "samples/command_test_support.hpp"
#include "samples/odeskin/rig_command.hpp"

namespace odeskin {
namespace {

namespace fs = std::filesystem;

const std::string kData = ODESKIN_DATA_DIR;

using testing::dataMesh;
using testing::kOnePixelPng;


std::vector<Vec3> roundedToFloat(std::vector<Vec3> positions) {
  for (Vec3& p : positions) p = testing::roundedToFloat(p);
  return positions;
}

// The cylinder as a character from a DCC: float32 positions (so the file holds them exactly), the
// first half of its faces in primitive 0 ("skin", textured) and the rest in primitive 1 ("cloth"),
// each vertex both halves use copied for primitive 1 (a seam), UVs and normals per render vertex.
struct SeamedCylinder {
  std::vector<Vec3> positions;  // topology: the OBJ's vertices, rounded to float
  FaceList faces;               // topology: the OBJ's triangles
  std::vector<std::vector<Vec3>> poses;  // poses-1, rounded to float
  RenderLayout render;
  std::size_t seam_copies = 0;
};

SeamedCylinder seamedCylinder() {
  SeamedCylinder c;
  const ObjMesh mesh = dataMesh("cylinder/cylinder.obj");
  c.positions = roundedToFloat(mesh.positions);
  c.faces = mesh.faces;
  for (const char* pose : {"cylinder/poses-1/cylinder-1.obj", "cylinder/poses-1/cylinder-2.obj"}) {
    c.poses.push_back(roundedToFloat(dataMesh(pose).positions));
  }
  const std::size_t v_count = c.positions.size();
  const std::size_t half = c.faces.faceCount() / 2;
  std::vector<char> in_first(v_count, 0);
  for (std::size_t k = 0; k < c.faces.face_offsets[half]; ++k) in_first[c.faces.indices[k]] = 1;
  for (std::uint32_t v = 0; v < v_count; ++v) c.render.topology_of_render.push_back(v);
  std::map<std::uint32_t, std::uint32_t> copy_of;
  c.render.faces = c.faces;
  for (std::size_t k = c.faces.face_offsets[half]; k < c.faces.indices.size(); ++k) {
    const std::uint32_t v = c.faces.indices[k];
    if (!in_first[v]) continue;
    auto [it, added] = copy_of.emplace(v, static_cast<std::uint32_t>(c.render.topology_of_render.size()));
    if (added) c.render.topology_of_render.push_back(v);
    c.render.faces.indices[k] = it->second;
  }
  c.seam_copies = copy_of.size();
  for (std::size_t r = 0; r < c.render.topology_of_render.size(); ++r) {
    const Vec3& p = c.positions[c.render.topology_of_render[r]];
    const bool copy = r >= v_count;
    c.render.uvs.emplace_back(0.25 * p.x + (copy ? 0.5 : 0.0), 0.5 + 0.5 * p.y);  // the copies sit elsewhere in UV space
    c.render.normals.push_back(glm::normalize(Vec3(0.0, p.y, p.z) + Vec3(copy ? 0.01 : 0.0, 0.0, 0.0)));
  }
  c.render.primitives = {{static_cast<std::uint32_t>(half), 0}, {static_cast<std::uint32_t>(c.faces.faceCount()), 1}};
  return c;
}

gltf::MaterialLibrary twoMaterials() {
  gltf::MaterialLibrary library;
  library.source = "two materials";
  library.images.push_back({"skin-colour", "image/png", {kOnePixelPng.begin(), kOnePixelPng.end()}});
  tinygltf::Texture texture;
  texture.source = 0;
  library.textures.push_back(texture);
  tinygltf::Material skin;
  skin.name = "skin";
  skin.pbrMetallicRoughness.baseColorTexture.index = 0;
  tinygltf::Material cloth;
  cloth.name = "cloth";
  cloth.emissiveFactor = {1.0, 0.5, 0.0};
  library.materials = {skin, cloth};
  return library;
}

// The cylinder written as an unskinned .glb: the bind pose, and the two poses as morph targets.
fs::path writeSeamedGlb(const SeamedCylinder& c, const fs::path& path) {
  std::vector<std::vector<Vec3>> frames;
  for (const std::vector<Vec3>* topology : {&c.positions, &c.poses[0], &c.poses[1]}) {
    std::vector<Vec3> frame;
    for (std::uint32_t t : c.render.topology_of_render) frame.push_back((*topology)[t]);
    frames.push_back(std::move(frame));
  }
  const std::vector<std::vector<Vec3>> normals(frames.size(), c.render.normals);
  const std::vector<double> seconds{0.0, 1.0, 2.0};
  const gltf::MaterialLibrary library = twoMaterials();
  BakedGlbOptions options;
  options.materials = &library;
  BakedVertexData data;
  data.normals = normals;
  data.uvs = c.render.uvs;
  data.primitives = c.render.primitives;
  const Status written = writeBakedGlb(path, c.render.faces, frames, seconds, options, data);
  if (!written.ok()) throw std::runtime_error(written.toString());
  return path;
}

tinygltf::Model loadGlb(const fs::path& path) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  if (!loader.LoadBinaryFromFile(&model, &err, &warn, path.string())) throw std::runtime_error(path.string() + ": " + err);
  return model;
}

class RigCommand : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::scratchDir("odeskin_rig_command_test_", "run"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// The glTF's mesh, welded back at its seam, gives the rig the arrays give, to the bit; --gltf keeps
// the render vertices, UVs, normals, primitives and materials, each render vertex weighted as its
// topology vertex; --weights holds the topology vertices' weights.
TEST_F(RigCommand, GltfInputKeepsItsLookAndGetsTheArraysRig) {
  const SeamedCylinder c = seamedCylinder();
  ASSERT_GT(c.seam_copies, 0u);
  const fs::path input = writeSeamedGlb(c, dir_ / "character.glb");
  RigCommandOptions o;
  o.meshes = {input};
  o.targets = {0, 1};
  o.template_kind = "none";
  o.output = dir_ / "character.tgf";
  o.weights = dir_ / "character.dmat";
  o.gltf = dir_ / "character-rigged.glb";
  testing::Captured io;
  ASSERT_EQ(runRigCommand(o, io.console), kExitOk) << io.err.str();
  EXPECT_NE(io.out.str().find("mesh: 420 vertices, 800 faces, 2 example poses"), std::string::npos) << io.out.str();
  EXPECT_NE(io.out.str().find("glTF: " + std::to_string(c.render.topology_of_render.size()) +
                              " render vertices welded into 420, 2 primitives"),
            std::string::npos)
      << io.out.str();

  CurveRigOptions options;
  options.animation.template_kind = SkeletonTemplateKind::kNone;
  options.compute_weights = true;
  Result<CurveRig> expected = buildCurveRig(c.positions, c.faces, c.poses, options);
  ASSERT_TRUE(expected.ok()) << expected.status().toString();
  const Skeleton& want = expected->rig.skeleton;
  Result<Skeleton> skeleton = readTgf(o.output);
  ASSERT_TRUE(skeleton.ok()) << skeleton.status().toString();
  ASSERT_EQ(skeleton->boneCount(), want.boneCount());
  EXPECT_EQ(skeleton->parents, want.parents);
  EXPECT_EQ(skeleton->heads, want.heads);
  Result<Influences> weights = readWeightsDmat(o.weights, c.positions.size(), want.boneCount());
  ASSERT_TRUE(weights.ok()) << weights.status().toString();
  EXPECT_EQ(weights->weights, expected->rig.influences.weights);

  // The rigged file read back: same welded mesh, the new skin, the look of the input.
  GltfPoseRequest request;
  request.min_poses = 1;
  Result<ExampleSet> back = readGltfExamples(o.gltf, request);
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->rest_positions, c.positions);
  EXPECT_EQ(back->faces.indices, c.faces.indices);
  ASSERT_TRUE(back->rig.has_value());
  EXPECT_EQ(back->rig->skeleton.boneCount(), want.boneCount());
  const tinygltf::Model model = loadGlb(o.gltf);
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 2u);
  EXPECT_EQ(model.meshes[0].primitives[0].material, 0);
  EXPECT_EQ(model.meshes[0].primitives[1].material, 1);
  const tinygltf::Accessor& positions = model.accessors.at(static_cast<std::size_t>(model.meshes[0].primitives[0].attributes.at("POSITION")));
  EXPECT_EQ(positions.count, c.render.topology_of_render.size()) << "one glTF vertex per render vertex of the input";
  for (const char* attribute : {"NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"}) {
    EXPECT_EQ(model.meshes[0].primitives[0].attributes.count(attribute), 1u) << attribute;
  }
  EXPECT_EQ(back->render.topology_of_render, c.render.topology_of_render);
  EXPECT_EQ(back->render.faces.indices, c.render.faces.indices);
  EXPECT_EQ(back->render.primitives, c.render.primitives);
  ASSERT_EQ(back->render.uvs.size(), c.render.uvs.size());
  ASSERT_EQ(back->render.normals.size(), c.render.normals.size());
  for (std::size_t r = 0; r < back->render.uvs.size(); ++r) {
    EXPECT_LT(glm::length(back->render.uvs[r] - c.render.uvs[r]), 1e-7) << r;
    EXPECT_LT(glm::length(back->render.normals[r] - c.render.normals[r]), 1e-6) << r;
  }
  ASSERT_EQ(model.materials.size(), 2u);
  EXPECT_EQ(model.materials[0].name, "skin");
  EXPECT_EQ(model.materials[1].name, "cloth");
  ASSERT_EQ(model.images.size(), 1u);
  const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(model.images[0].bufferView));
  EXPECT_TRUE(view.byteLength == kOnePixelPng.size() &&
              std::equal(kOnePixelPng.begin(), kOnePixelPng.end(), model.buffers[0].data.begin() + static_cast<std::ptrdiff_t>(view.byteOffset)));
}

// An OBJ's texture coordinates reach the skinned glTF too: its vertices are split where a
// corner's `vt` differs, as a glTF input's render vertices are.
TEST_F(RigCommand, ObjTexcoordsReachTheRiggedGlb) {
  const SeamedCylinder c = seamedCylinder();
  const fs::path obj = dir_ / "textured.obj";
  ASSERT_TRUE(writeObj(obj, c.positions, c.render.faces, {}, c.render.uvs, c.render.topology_of_render).ok());
  Result<ObjMesh> mesh = readObj(obj);
  ASSERT_TRUE(mesh.ok()) << mesh.status().toString();
  const RenderLayout layout = objRenderLayout(*mesh);
  ASSERT_GT(layout.topology_of_render.size(), c.positions.size()) << "the cylinder's UV seam splits vertices";
  RigCommandOptions o;
  o.meshes = {obj};
  o.template_kind = "none";
  o.output = dir_ / "textured.tgf";
  o.gltf = dir_ / "textured.glb";
  testing::Captured io;
  ASSERT_EQ(runRigCommand(o, io.console), kExitOk) << io.err.str();
  EXPECT_NE(io.out.str().find("OBJ: " + std::to_string(layout.topology_of_render.size()) + " render vertices welded into 420"),
            std::string::npos)
      << io.out.str();
  EXPECT_TRUE(io.err.str().empty()) << io.err.str();
  GltfPoseRequest request;
  request.min_poses = 1;
  Result<ExampleSet> back = readGltfExamples(o.gltf, request);
  ASSERT_TRUE(back.ok()) << back.status().toString();
  EXPECT_EQ(back->rest_positions.size(), c.positions.size());
  // The reader numbers the welded vertices its own way: render vertex r is compared by what it holds.
  ASSERT_EQ(back->render.topology_of_render.size(), layout.topology_of_render.size());
  ASSERT_EQ(back->render.uvs.size(), layout.uvs.size());
  for (std::size_t r = 0; r < layout.uvs.size(); ++r) {
    EXPECT_LT(glm::length(back->rest_positions[back->render.topology_of_render[r]] - c.positions[layout.topology_of_render[r]]),
              1e-6)
        << r;
    EXPECT_LT(glm::length(back->render.uvs[r] - layout.uvs[r]), 1e-7) << r;
  }
}

// The rigged file rigs again to the same skeleton, and says that its own skin is not used.
TEST_F(RigCommand, RiggedGlbRigsAgainToTheSameSkeleton) {
  const SeamedCylinder c = seamedCylinder();
  RigCommandOptions o;
  o.meshes = {writeSeamedGlb(c, dir_ / "character.glb")};
  o.template_kind = "none";
  o.output = dir_ / "first.tgf";
  o.gltf = dir_ / "first.glb";
  testing::Captured first;
  ASSERT_EQ(runRigCommand(o, first.console), kExitOk) << first.err.str();
  o.meshes = {o.gltf};
  o.output = dir_ / "second.tgf";
  o.gltf = dir_ / "second.glb";
  testing::Captured second;
  ASSERT_EQ(runRigCommand(o, second.console), kExitOk) << second.err.str();
  EXPECT_NE(second.out.str().find("its skin of "), std::string::npos) << second.out.str();
  Result<Skeleton> a = readTgf(dir_ / "first.tgf");
  Result<Skeleton> b = readTgf(dir_ / "second.tgf");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->heads, b->heads);
  EXPECT_EQ(a->parents, b->parents);
}

// glTF asks a skin's joints to share one root node (the Khronos validator's SKIN_NO_COMMON_ROOT).
// The cylinder's curve rig starts two bones at its middle joint: two root bones, one "skeleton" node.
TEST_F(RigCommand, RootBonesShareOneNodeInTheGlb) {
  RigCommandOptions o;
  o.meshes = {fs::path(kData) / "cylinder" / "cylinder.obj"};
  o.output = dir_ / "cylinder.tgf";
  o.gltf = dir_ / "cylinder.glb";
  testing::Captured io;
  ASSERT_EQ(runRigCommand(o, io.console), kExitOk) << io.err.str();
  Result<Skeleton> skeleton = readTgf(o.output);
  ASSERT_TRUE(skeleton.ok());
  EXPECT_GT(std::count(skeleton->parents.begin(), skeleton->parents.end(), -1), 1);
  const tinygltf::Model model = loadGlb(o.gltf);
  std::vector<int> parent(model.nodes.size(), -1);
  for (std::size_t n = 0; n < model.nodes.size(); ++n) {
    for (int child : model.nodes[n].children) parent.at(static_cast<std::size_t>(child)) = static_cast<int>(n);
  }
  ASSERT_EQ(model.skins.size(), 1u);
  const int root = model.skins[0].skeleton;
  ASSERT_GE(root, 0);
  EXPECT_EQ(model.nodes.at(static_cast<std::size_t>(root)).name, "skeleton");
  EXPECT_EQ(model.scenes.at(0).nodes, (std::vector<int>{0, root}));
  for (int joint : model.skins[0].joints) {
    int n = joint;
    while (n >= 0 && n != root) n = parent.at(static_cast<std::size_t>(n));
    EXPECT_EQ(n, root) << "joint node " << joint << " is not under the skeleton node";
  }
}

TEST_F(RigCommand, RejectsWhatAGltfInputCannotDo) {
  const SeamedCylinder c = seamedCylinder();
  const fs::path glb = writeSeamedGlb(c, dir_ / "character.glb");
  const std::string obj = kData + "/cylinder/cylinder.obj";
  // Every face drawn twice, by a second primitive: fit refuses it as non-manifold, and so must rig.
  SeamedCylinder twice = c;
  const auto faces = static_cast<std::uint32_t>(c.render.faces.faceCount());
  for (std::uint32_t f = 0; f < faces; ++f) {
    for (std::uint32_t k = c.render.faces.face_offsets[f]; k < c.render.faces.face_offsets[f + 1]; ++k) {
      twice.render.faces.indices.push_back(c.render.faces.indices[k]);
    }
    twice.render.faces.face_offsets.push_back(static_cast<std::uint32_t>(twice.render.faces.indices.size()));
  }
  twice.render.primitives = {{faces, 0}, {2 * faces, 1}};
  const fs::path doubled = writeSeamedGlb(twice, dir_ / "doubled.glb");
  // The options for `meshes`, changed by `edit`.
  auto options = [&](std::vector<fs::path> meshes, const std::function<void(RigCommandOptions&)>& edit = {}) {
    RigCommandOptions o;
    o.meshes = std::move(meshes);
    o.output = dir_ / "x.tgf";
    if (edit) edit(o);
    return o;
  };
  const auto run = [](const RigCommandOptions& o, testing::Captured& io) { return runRigCommand(o, io.console); };
  testing::expectRejected<RigCommandOptions>(
      {{options({glb, obj}), "give one .gltf/.glb file"},
       {options({dir_ / "character.fbx"}), "unknown mesh format '.fbx'"},
       {options({obj}, [](RigCommandOptions& o) { o.times = {0.5}; }),
        "--mesh, --animation, --times and --targets apply to a .gltf/.glb input"},
       {options({glb}, [](RigCommandOptions& o) { o.animation = "walk"; }), "--animation applies with --times"}},
      run, kExitUsage, "rig");
  testing::expectRejected<RigCommandOptions>(
      {{options({glb}, [](RigCommandOptions& o) { o.targets = {7}; }), "character.glb: morph target 7 requested; mesh 0 has 2"},
       {options({glb}, [](RigCommandOptions& o) { o.mesh = "body"; }), "no mesh node named 'body'"},
       {options({dir_ / "absent.glb"}), "absent.glb"},
       {options({doubled}), "doubled.glb: face "}},
      run, kExitFailure, "rig");
  EXPECT_FALSE(fs::exists(dir_ / "x.tgf"));
}

}  // namespace
}  // namespace odeskin

// SPDX-License-Identifier: MIT
// Writes generated seed files for the fuzz corpus (scripts/fuzz.sh): formats ../shared/data has no
// example of. A small procedural arm is fitted into a DeformAsset, then saved as an .odsk asset and
// exported as glTF: the compact form (skin, skeletal animation, morph targets with CUBICSPLINE
// weights, sparse accessors), the baked form (morph targets and a weights animation, no skin), both
// quantized (KHR_mesh_quantization), and the compact form again as JSON glTF with its buffer in a
// data: URI.
//   odeskin_fuzz_seeds <folder>   ->  <folder>/{odsk,gltf}/...
#include <cstdio>
#include <filesystem>
#include <string>

#include <tiny_gltf.h>

#include "engine/export/gltf_export.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/offline/procedural_arm.hpp"
#include "engine/offline/residual_fit.hpp"

namespace {

using namespace odeskin;
namespace fs = std::filesystem;

int fail(const std::string& what) {
  std::fprintf(stderr, "odeskin_fuzz_seeds: %s\n", what.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return fail("usage: odeskin_fuzz_seeds <folder>");
  const fs::path folder = argv[1];
  std::error_code ec;
  fs::create_directories(folder / "odsk", ec);
  fs::create_directories(folder / "gltf", ec);
  if (ec) return fail(folder.string() + ": " + ec.message());

  ArmOptions arm_options;  // small, so the seeds are a few kilobytes
  arm_options.rings = 5;
  arm_options.ring_vertices = 6;
  arm_options.curve_stride = 2;
  Result<ProceduralArm> arm = makeProceduralArm(arm_options);
  if (!arm.ok()) return fail(arm.status().toString());
  FitOptions fit;
  fit.modes = 2;
  Result<DeformAsset> asset = fitDeformAsset(arm->fit_input, fit);
  if (!asset.ok()) return fail(asset.status().toString());
  if (Status s = saveAsset(folder / "odsk" / "arm.odsk", *asset); !s.ok()) return fail(s.toString());
  // The same with a render layout whose bind normals put vertex 0 on a hard edge (the optional
  // RNRM section): its first face takes a second copy of it, with another normal; and with
  // texture coordinates (RUV0), the copy on the other side of a UV seam, and two primitives with
  // materials (RPRM).
  DeformAsset hard = *asset;
  for (std::uint32_t i = 0; i < hard.vertexCount(); ++i) hard.render.topology_of_render.push_back(i);
  hard.render.topology_of_render.push_back(hard.faces.indices[0]);
  hard.render.faces = hard.faces;
  hard.render.faces.indices[0] = static_cast<std::uint32_t>(hard.vertexCount());
  hard.render.normals.assign(hard.render.topology_of_render.size(), Vec3(0.0, 0.0, 1.0));
  hard.render.normals.back() = Vec3(1.0, 0.0, 0.0);
  for (std::uint32_t r = 0; r < hard.render.topology_of_render.size(); ++r) hard.render.uvs.emplace_back(r / 64.0, 0.5);
  const auto faces = static_cast<std::uint32_t>(hard.render.faces.faceCount());
  hard.render.primitives = {{faces / 2, 0}, {faces, -1}};
  if (Status s = saveAsset(folder / "odsk" / "arm-hard-edges.odsk", hard); !s.ok()) return fail(s.toString());
  // The same layout as an OBJ input's (ROBJ): OBJ frames keep the topology vertices.
  DeformAsset obj_layout = hard;
  obj_layout.render.primitives.clear();
  obj_layout.render.obj_order = true;
  if (Status s = saveAsset(folder / "odsk" / "arm-obj-texcoords.odsk", obj_layout); !s.ok()) return fail(s.toString());

  GltfExportOptions compact;
  const fs::path glb = folder / "gltf" / "arm-compact.glb";
  if (Result<GltfExportReport> r = exportGltf(*asset, glb, compact); !r.ok()) return fail(r.status().toString());
  if (Result<GltfExportReport> r = exportGltf(hard, folder / "gltf" / "arm-textured.glb", compact); !r.ok()) {
    return fail(r.status().toString());
  }
  GltfExportOptions baked;
  baked.bake = true;
  baked.bake_fps = 4.0;
  if (Result<GltfExportReport> r = exportGltf(*asset, folder / "gltf" / "arm-baked.glb", baked); !r.ok()) {
    return fail(r.status().toString());
  }
  // KHR_mesh_quantization: the grid in a skin (the reader's shared-scale path) and on an unskinned
  // mesh node.
  for (GltfExportOptions* options : {&compact, &baked}) {
    options->quantize = true;
    const fs::path quantized = folder / "gltf" / (options->bake ? "arm-baked-quantized.glb" : "arm-quantized.glb");
    if (Result<GltfExportReport> r = exportGltf(*asset, quantized, *options); !r.ok()) return fail(r.status().toString());
  }

  tinygltf::TinyGLTF gltf;
  tinygltf::Model model;
  std::string err;
  std::string warn;
  if (!gltf.LoadBinaryFromFile(&model, &err, &warn, glb.string())) return fail(glb.string() + ": " + err);
  const fs::path json = folder / "gltf" / "arm-compact.gltf";
  if (!gltf.WriteGltfSceneToFile(&model, json.string(), true, true, false, false)) return fail(json.string() + ": write failed");
  return 0;
}

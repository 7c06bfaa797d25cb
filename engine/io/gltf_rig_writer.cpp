// SPDX-License-Identifier: MIT
#include "gltf_rig_writer.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <tiny_gltf.h>

#include "../core/render_layout_check.hpp"
#include "gltf_baked_writer.hpp"
#include "gltf_buffer_builder.hpp"

namespace odeskin {
namespace {

constexpr std::size_t kSlots = 4;

std::vector<double> toDoubles(const Vec3& v) { return {v.x, v.y, v.z}; }

}  // namespace

Status writeRigGlb(const std::filesystem::path& path, std::span<const Vec3> positions, const FaceList& faces, const Rig& rig,
                   const RigGlbLook& look, const std::string& generator) {
  const std::size_t v_count = positions.size();
  const std::size_t bones = rig.skeleton.boneCount();
  const RenderLayout none;
  const RenderLayout& render = look.render != nullptr ? *look.render : none;
  ODESKIN_TRY(validateRig(Rig{rig.skeleton, rig.influences, {}}, v_count, 0));
  if (bones == 0 || bones > 65536) return invalidArgument(path.string() + ": a glTF skin needs 1 to 65536 bones, got " + std::to_string(bones));
  if (rig.influences.vertexCount() != v_count) return invalidArgument(path.string() + ": the rig has no weights for the mesh");
  ODESKIN_TRY(checkFaceList(faces, v_count, path.string(), "face"));
  ODESKIN_TRY(checkRenderLayout(render, v_count, faces.faceCount(), path.string()));
  for (std::size_t i = 0; i < v_count; ++i) {
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(positions[i][k])) return invalidArgument(path.string() + ": vertex " + std::to_string(i) + " is not finite");
    }
  }
  ODESKIN_TRY(gltf::checkFloat32Positions(positions, path.string()));

  tinygltf::Model m = gltf::newModel(generator);
  ODESKIN_ASSIGN_OR_RETURN(const std::vector<gltf::PrimitiveIndices> written,
                           gltf::appendPrimitiveIndices(m, render.empty() ? faces : render.faces, render.primitives,
                                                        look.materials));

  // Output vertex o is topology vertex topology[o]: its position and its largest weights.
  const std::size_t out_count = render.empty() ? v_count : render.topology_of_render.size();
  auto topology = [&](std::size_t o) { return render.empty() ? o : std::size_t{render.topology_of_render[o]}; };
  std::vector<float> xyz;
  std::vector<float> normals;
  std::vector<float> weights(kSlots * out_count, 0.0f);
  std::vector<std::uint16_t> joints(kSlots * out_count, 0);
  std::vector<std::pair<double, std::uint32_t>> row;
  for (std::size_t o = 0; o < out_count; ++o) {
    const std::size_t i = topology(o);
    for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<float>(positions[i][k]));
    if (!render.normals.empty()) {
      const Vec3 n = glm::normalize(render.normals[o]);
      normals.insert(normals.end(), {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)});
    }
    row.clear();
    for (std::uint32_t k = rig.influences.offsets[i]; k < rig.influences.offsets[i + 1]; ++k) {
      row.push_back({rig.influences.weights[k], rig.influences.bones[k]});
    }
    std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    row.resize(std::min(row.size(), kSlots));
    float sum = 0.0f;
    for (const auto& [w, b] : row) sum += static_cast<float>(w);
    for (std::size_t k = 0; k < row.size(); ++k) {
      weights[kSlots * o + k] = static_cast<float>(row[k].first) / sum;
      joints[kSlots * o + k] = static_cast<std::uint16_t>(row[k].second);
    }
  }

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] =
      gltf::appendFloatAccessor(m, xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  if (!normals.empty()) {
    primitive.attributes["NORMAL"] =
        gltf::appendFloatAccessor(m, normals, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  if (!render.uvs.empty()) primitive.attributes["TEXCOORD_0"] = gltf::appendTexcoordAccessor(m, render.uvs);
  primitive.attributes["WEIGHTS_0"] = gltf::appendAccessor(m, gltf::appendView(m, weights, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, out_count);
  primitive.attributes["JOINTS_0"] = gltf::appendAccessor(m, gltf::appendView(m, joints, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, out_count);
  tinygltf::Mesh mesh;
  mesh.name = "mesh";
  gltf::addSharedPrimitives(mesh, primitive, written);
  m.meshes.push_back(mesh);

  // Node 0: the skinned mesh; nodes 1..B: the bones at their heads; then the end nodes.
  tinygltf::Node mesh_node;
  mesh_node.name = "mesh";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  m.nodes.push_back(mesh_node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  std::vector<float> inverse_binds;
  std::vector<char> has_child(bones, 0);
  for (std::size_t b = 0; b < bones; ++b) {
    if (rig.skeleton.parents[b] >= 0) has_child[static_cast<std::size_t>(rig.skeleton.parents[b])] = 1;
  }
  for (std::size_t b = 0; b < bones; ++b) {
    const std::int32_t p = rig.skeleton.parents[b];
    tinygltf::Node node;
    node.name = rig.skeleton.names.size() == bones && !rig.skeleton.names[b].empty() ? rig.skeleton.names[b] : "bone" + std::to_string(b);
    const Vec3 offset = rig.skeleton.heads[b] - (p >= 0 ? rig.skeleton.heads[static_cast<std::size_t>(p)] : Vec3(0.0));
    node.translation = toDoubles(offset);
    m.nodes.push_back(node);
    // Column-major 4 x 4: translate(-head).
    const Vec3& h = rig.skeleton.heads[b];
    inverse_binds.insert(inverse_binds.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, static_cast<float>(-h.x),
                                               static_cast<float>(-h.y), static_cast<float>(-h.z), 1});
  }
  // glTF wants a skin's joints under one node (the validator's SKIN_NO_COMMON_ROOT): a skeleton of
  // several root bones (the cylinder's two arms from one joint) hangs them under a "skeleton" node.
  std::vector<int> roots;
  for (std::size_t b = 0; b < bones; ++b) {
    if (rig.skeleton.parents[b] < 0) roots.push_back(static_cast<int>(b + 1));
  }
  int skeleton_root = -1;
  if (roots.size() > 1) {
    tinygltf::Node root;
    root.name = "skeleton";
    root.children = roots;
    m.nodes.push_back(root);
    skeleton_root = static_cast<int>(m.nodes.size() - 1);
    scene.nodes.push_back(skeleton_root);
  } else {
    scene.nodes.insert(scene.nodes.end(), roots.begin(), roots.end());
  }
  for (std::size_t b = 0; b < bones; ++b) {
    const std::int32_t p = rig.skeleton.parents[b];
    if (p >= 0) m.nodes[static_cast<std::size_t>(p) + 1].children.push_back(static_cast<int>(b + 1));
    if (!has_child[b]) {
      tinygltf::Node end;
      end.name = m.nodes[b + 1].name + "_end";
      end.translation = toDoubles(rig.skeleton.tails[b] - rig.skeleton.heads[b]);
      m.nodes.push_back(end);
      m.nodes[b + 1].children.push_back(static_cast<int>(m.nodes.size() - 1));
    }
  }
  tinygltf::Skin skin;
  skin.name = "skin";
  skin.skeleton = skeleton_root;
  for (std::size_t b = 0; b < bones; ++b) skin.joints.push_back(static_cast<int>(b + 1));
  skin.inverseBindMatrices = gltf::appendAccessor(m, gltf::appendView(m, inverse_binds, 0), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, bones);
  m.skins.push_back(skin);
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  if (look.materials != nullptr) gltf::addMaterialLibrary(m, *look.materials);
  m.buffers[0].data.resize((m.buffers[0].data.size() + 3) / 4 * 4, 0);
  return writeGlbAtomically(path, m);
}

}  // namespace odeskin

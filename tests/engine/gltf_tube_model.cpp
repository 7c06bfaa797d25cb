// SPDX-License-Identifier: MIT
#include "engine/gltf_tube_model.hpp"

#include <algorithm>
#include <cstring>

#include <gtest/gtest.h>

#include "engine/io/text_tokens.hpp"
#include "engine/one_pixel_png.hpp"  // tests/engine
#include "scratch_dir.hpp"          // tests/

namespace odeskin::testing {
namespace fs = std::filesystem;

std::vector<unsigned char> pack(const std::vector<double>& values, int component_type) {
  std::vector<unsigned char> out;
  auto put = [&out](auto v) {
    unsigned char bytes[sizeof v];
    std::memcpy(bytes, &v, sizeof v);
    out.insert(out.end(), bytes, bytes + sizeof v);
  };
  for (double x : values) {
    switch (component_type) {
      case kByteType: put(static_cast<std::int8_t>(x)); break;
      case kUByteType: put(static_cast<std::uint8_t>(x)); break;
      case kShortType: put(static_cast<std::int16_t>(x)); break;
      case kUShortType: put(static_cast<std::uint16_t>(x)); break;
      case kUIntType: put(static_cast<std::uint32_t>(x)); break;
      default: put(static_cast<float>(x)); break;
    }
  }
  return out;
}

int appendBufferView(tinygltf::Model& model, const std::vector<unsigned char>& bytes) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = data.size();
  v.byteLength = bytes.size();
  data.insert(data.end(), bytes.begin(), bytes.end());
  model.bufferViews.push_back(v);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

std::size_t componentsOf(int type) {
  return type == TINYGLTF_TYPE_MAT4 ? 16 : static_cast<std::size_t>(tinygltf::GetNumComponentsInType(type));
}

fs::path tempDir() {
  // Not emptied: a test writes several files here, and the folder is its own (scratch_dir.hpp).
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = processScratchRoot() / (std::string("gltf_") + info->test_suite_name() + "." + info->name());
  fs::create_directories(dir);
  return dir;
}

std::string fileBytes(const fs::path& path) {
  Result<std::string> bytes = readTextFile(path);
  EXPECT_TRUE(bytes.ok()) << bytes.status().toString();
  return bytes.ok() ? std::move(bytes).value() : std::string();
}

fs::path write(const tinygltf::Model& model, const std::string& name, bool binary) {
  fs::path path = tempDir() / name;
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&model, path.string(), true, true, true, binary)) << path;
  return path;
}

namespace {

double fullWeight(int type) { return type == kUByteType ? 255.0 : type == kUShortType ? 65535.0 : 1.0; }

void addVertex(Prim& p, int ring, int column, const TubeOptions& o) {
  p.positions.emplace_back(kSquare[static_cast<std::size_t>(column)][0], ring, kSquare[static_cast<std::size_t>(column)][1]);
  p.ring.push_back(ring);
  p.column.push_back(column);
  const double full = fullWeight(o.weight_type);
  const std::array<double, 2> w = ring == 0 ? std::array<double, 2>{full, 0.0}
                                  : ring == 2 ? std::array<double, 2>{0.0, full}
                                              : o.ring1_weights;
  if (o.two_sets) {
    p.joints0.push_back({0, 0, 0, 0});
    p.weights0.push_back({w[0], 0, 0, 0});
    p.joints1.push_back({1, 0, 0, 0});
    p.weights1.push_back({w[1], 0, 0, 0});
  } else {
    p.joints0.push_back({0, 1, 0, 0});
    p.weights0.push_back({w[0], w[1], 0, 0});
  }
}

// Two triangles per quad between rings r, r + 1 and columns c, c + 1 (ring-major vertex numbering
// from `first_ring`).
std::vector<std::array<int, 2>> quadCorners(int first_ring) {
  std::vector<std::array<int, 2>> corners;  // (ring, column)
  for (int c = 0; c < kColumns - 1; ++c) {
    const std::array<std::array<int, 2>, 6> tri{{{first_ring, c},
                                                 {first_ring, c + 1},
                                                 {first_ring + 1, c + 1},
                                                 {first_ring, c},
                                                 {first_ring + 1, c + 1},
                                                 {first_ring + 1, c}}};
    corners.insert(corners.end(), tri.begin(), tri.end());
  }
  return corners;
}

Prim indexedRings(int first, int last, const TubeOptions& o) {
  Prim p;
  for (int r = first; r <= last; ++r) {
    for (int c = 0; c < kColumns; ++c) addVertex(p, r, c, o);
  }
  for (int r = first; r < last; ++r) {
    for (const auto& [ring, column] : quadCorners(r)) {
      p.indices.push_back(static_cast<std::uint32_t>((ring - first) * kColumns + column));
    }
  }
  return p;
}

Prim unindexedRings(int first, const TubeOptions& o) {
  Prim p;
  for (const auto& [ring, column] : quadCorners(first)) addVertex(p, ring, column, o);
  return p;
}

std::vector<double> flat(const std::vector<std::array<double, 4>>& v) {
  std::vector<double> out;
  for (const auto& a : v) out.insert(out.end(), a.begin(), a.end());
  return out;
}

tinygltf::Primitive emit(Builder& b, const Prim& p, const TubeOptions& o, bool sparse_target, bool first_primitive) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  std::vector<double> positions;
  std::vector<double> uvs;
  for (std::size_t i = 0; i < p.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double stored = (p.positions[i][k] - o.position_offset[k]) * o.position_scale;
      positions.push_back(o.position_type == kFloatType ? stored : std::round(stored));
    }
    const Vec2 uv = o.uv(p.ring[i], p.column[i]);
    uvs.push_back(uv.x * o.uv_scale);
    uvs.push_back(uv.y * o.uv_scale);
  }
  prim.attributes["POSITION"] = b.accessor(positions, o.position_type, TINYGLTF_TYPE_VEC3, o.position_normalized);
  if (!o.uv_in_first_primitive_only || first_primitive) {
    prim.attributes["TEXCOORD_0"] = b.accessor(uvs, o.uv_type, TINYGLTF_TYPE_VEC2, o.uv_normalized);
  }
  if (o.normal) {
    std::vector<double> normals;
    const double scale = o.normal_type == kByteType ? 127.0 : 1.0;
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
      const Vec3 n = o.normal(p.ring[i], p.column[i]);
      for (int k = 0; k < 3; ++k) normals.push_back(std::round(n[k] * scale * 1e6) / 1e6);
    }
    prim.attributes["NORMAL"] = b.accessor(normals, o.normal_type, TINYGLTF_TYPE_VEC3, o.normal_type != kFloatType);
  }
  const bool normalized = o.weight_type != kFloatType;
  prim.attributes["JOINTS_0"] = b.accessor(flat(p.joints0), o.joint_type, TINYGLTF_TYPE_VEC4);
  prim.attributes["WEIGHTS_0"] = b.accessor(flat(p.weights0), o.weight_type, TINYGLTF_TYPE_VEC4, normalized);
  if (o.two_sets) {
    prim.attributes["JOINTS_1"] = b.accessor(flat(p.joints1), o.joint_type, TINYGLTF_TYPE_VEC4);
    prim.attributes["WEIGHTS_1"] = b.accessor(flat(p.weights1), o.weight_type, TINYGLTF_TYPE_VEC4, normalized);
  }
  if (!p.indices.empty()) {
    prim.indices = b.accessor(std::vector<double>(p.indices.begin(), p.indices.end()), kUShortType, TINYGLTF_TYPE_SCALAR);
  }
  // The morph target moves ring 2, stored sparse; a primitive without ring 2 gets a zero accessor.
  std::vector<std::uint32_t> moved;
  std::vector<double> values;
  std::vector<double> base(3 * p.positions.size(), 0.0);
  const Vec3 delta = kDelta * (o.fold_into_skin ? o.position_scale : 1.0);
  for (std::size_t i = 0; i < p.positions.size(); ++i) {
    if (p.ring[i] == 2) {
      moved.push_back(static_cast<std::uint32_t>(i));
      values.insert(values.end(), {delta.x, delta.y, delta.z});
      base[3 * i] = base[3 * i + 1] = base[3 * i + 2] = 9.0;  // must be overridden
    } else if (p.ring[i] == 1) {
      base[3 * i] = kBaseDelta.x * (o.fold_into_skin ? o.position_scale : 1.0);
    }
  }
  int target = -1;
  if (!sparse_target) {
    tinygltf::Accessor zeros;
    zeros.componentType = kFloatType;
    zeros.type = TINYGLTF_TYPE_VEC3;
    zeros.count = p.positions.size();
    b.model.accessors.push_back(zeros);
    target = static_cast<int>(b.model.accessors.size()) - 1;
  } else {
    target = b.sparseVec3(p.positions.size(), o.sparse_over_base ? &base : nullptr, moved, values, o.sparse_index_type);
  }
  prim.targets.push_back({{"POSITION", target}});
  return prim;
}

void addNode(tinygltf::Model& m, const std::string& name, std::vector<double> translation, std::vector<int> children) {
  tinygltf::Node n;
  n.name = name;
  n.translation = std::move(translation);
  n.children = std::move(children);
  m.nodes.push_back(n);
}
// Rotation keys of "bend" (joint tip, times 0 and 2 s): identity to a quarter turn about z. For
// CUBICSPLINE each keyframe is in-tangent, value, out-tangent (glTF quaternions x y z w).
std::vector<double> rotationKeys(const std::string& interpolation) {
  const double s = kHalfTurnZ;
  if (interpolation == "CUBICSPLINE") {
    return {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0.375, 0, 0, 0, 0.25, -0.125, 0, 0, s, s, 0, 0, 0, 0};
  }
  return {0, 0, 0, 1, 0, 0, s, s};
}

// glTF quaternions restricted to the z axis: (z, w).
struct ZQuat {
  double z = 0.0;
  double w = 1.0;
};

}  // namespace

void addChannel(Builder& b, tinygltf::Animation& a, int node, const std::string& path, const std::string& interpolation,
                const std::vector<double>& times, const std::vector<double>& values, int type) {
  tinygltf::AnimationSampler s;
  s.input = b.accessor(times, kFloatType, TINYGLTF_TYPE_SCALAR);
  s.output = b.accessor(values, kFloatType, type);
  s.interpolation = interpolation;
  a.samplers.push_back(s);
  tinygltf::AnimationChannel c;
  c.sampler = static_cast<int>(a.samplers.size()) - 1;
  c.target_node = node;
  c.target_path = path;
  a.channels.push_back(c);
}

Tube makeTube(const TubeOptions& o) {
  Builder b;
  std::vector<Prim> prims;
  if (o.two_primitives) {
    prims.push_back(indexedRings(0, 1, o));
    prims.push_back(unindexedRings(1, o));
  } else {
    prims.push_back(indexedRings(0, 2, o));
  }
  Tube tube;
  tinygltf::Mesh mesh;
  mesh.name = "tube";
  for (std::size_t i = 0; i < prims.size(); ++i) {
    if (o.tweak) o.tweak(prims[i]);
    const bool has_ring2 = std::find(prims[i].ring.begin(), prims[i].ring.end(), 2) != prims[i].ring.end();
    mesh.primitives.push_back(emit(b, prims[i], o, has_ring2, i == 0));
    tube.render_positions.insert(tube.render_positions.end(), prims[i].positions.begin(), prims[i].positions.end());
  }
  tube.position_accessor = mesh.primitives[0].attributes["POSITION"];
  b.model.meshes.push_back(mesh);

  // Node 0: the skinned mesh, translated (which glTF says must be ignored); nodes 1, 2: joints.
  tinygltf::Node mesh_node;
  mesh_node.name = "tube";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  mesh_node.translation = {5.0, 0.0, 0.0};
  b.model.nodes.push_back(mesh_node);
  addNode(b.model, "root", {}, {2});
  addNode(b.model, "tip", {0.0, 1.0, 0.0}, {});
  tinygltf::Skin skin;
  skin.joints = {1, 2};
  std::vector<double> ibm(32, 0.0);
  for (std::size_t k = 0; k < 4; ++k) ibm[5 * k] = ibm[16 + 5 * k] = 1.0;
  ibm[16 + 13] = -1.0;  // column 3, row 1 of joint 1's matrix: translate (0, -1, 0)
  if (o.fold_into_skin) {  // IBM_j D: the scale multiplies the 3x3, the offset goes through IBM_j
    for (std::size_t j = 0; j < 2; ++j) {
      double* m = &ibm[16 * j];
      for (int k = 0; k < 3; ++k) {
        m[12 + k] += m[k] * o.position_offset.x + m[4 + k] * o.position_offset.y + m[8 + k] * o.position_offset.z;
      }
      for (int k = 0; k < 12; ++k) m[k] /= o.position_scale;
    }
  }
  skin.inverseBindMatrices = b.accessor(ibm, kFloatType, TINYGLTF_TYPE_MAT4);
  b.model.skins.push_back(skin);
  tinygltf::Scene scene;
  scene.nodes = {0, 1};
  b.model.scenes.push_back(scene);
  b.model.defaultScene = 0;

  tinygltf::Animation bend;
  bend.name = "bend";
  addChannel(b, bend, 2, "rotation", o.interpolation, {0.0, 2.0}, rotationKeys(o.interpolation), TINYGLTF_TYPE_VEC4);
  addChannel(b, bend, 1, "translation", "LINEAR", {0.0, 1.0}, {0, 0, 0, 0.5, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.model.animations.push_back(bend);
  tinygltf::Animation wiggle;
  wiggle.name = "wiggle";
  addChannel(b, wiggle, 0, "weights", "LINEAR", {0.0, 2.0}, {0.0, 1.0}, TINYGLTF_TYPE_SCALAR);
  addChannel(b, wiggle, 2, "rotation", "LINEAR", {0.0, 2.0}, rotationKeys("LINEAR"), TINYGLTF_TYPE_VEC4);
  b.model.animations.push_back(wiggle);
  tinygltf::Animation squash;
  squash.name = "squash";
  addChannel(b, squash, 2, "scale", "LINEAR", {0.0, 1.0}, {1, 1, 1, 2, 2, 2}, TINYGLTF_TYPE_VEC3);
  b.model.animations.push_back(squash);
  if (o.position_type != kFloatType) b.model.extensionsRequired = b.model.extensionsUsed = {"KHR_mesh_quantization"};
  tube.model = std::move(b.model);
  return tube;
}

Vec3 cornerNormal(int column, bool hard_seam) {
  if (column == 4 && hard_seam) return Vec3(0.6, 0.0, 0.8);
  const auto& c = kSquare[static_cast<std::size_t>(column)];
  return Vec3(c[0], 0.0, c[1]);
}

tinygltf::Model dressedTube(bool external_image) {
  TubeOptions o;
  o.two_primitives = true;
  tinygltf::Model model = makeTube(o).model;
  tinygltf::Image image;
  image.name = "skin-colour";
  if (external_image) {
    image.uri = "skin-colour.png";
  } else {
    image.bufferView = appendBufferView(model, std::vector<unsigned char>(kOnePixelPng.begin(), kOnePixelPng.end()));
    image.mimeType = "image/png";
  }
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model.textures.push_back(texture);
  tinygltf::Material skin;
  skin.name = "skin";
  skin.pbrMetallicRoughness.baseColorTexture.index = 0;
  tinygltf::Value::Object transform;
  transform["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(2.0), tinygltf::Value(2.0)});
  skin.pbrMetallicRoughness.baseColorTexture.extensions["KHR_texture_transform"] = tinygltf::Value(transform);
  tinygltf::Material cloth;
  cloth.name = "cloth";
  cloth.emissiveFactor = {1.0, 0.5, 0.0};
  tinygltf::Value::Object strength;
  strength["emissiveStrength"] = tinygltf::Value(4.0);
  cloth.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
  model.materials = {skin, cloth};
  model.extensionsUsed = {"KHR_texture_transform", "KHR_materials_emissive_strength"};
  for (std::size_t p = 0; p < model.meshes[0].primitives.size(); ++p) model.meshes[0].primitives[p].material = static_cast<int>(p);
  return model;
}

// The tip joint's rotation angle about z at time t under "bend"'s rotation channel (spec Appendix C).
double bendAngle(const std::string& interpolation, double t) {
  const ZQuat v0{0.0, 1.0};
  const ZQuat v1{kHalfTurnZ, kHalfTurnZ};
  ZQuat q = t <= 0.0 ? v0 : v1;
  if (t > 0.0 && t < 2.0) {
    const double td = 2.0;
    const double u = t / td;
    if (interpolation == "STEP") {
      q = v0;
    } else if (interpolation == "LINEAR") {
      const double theta = std::acos(v0.z * v1.z + v0.w * v1.w);
      const double a = std::sin((1.0 - u) * theta) / std::sin(theta);
      const double c = std::sin(u * theta) / std::sin(theta);
      q = {a * v0.z + c * v1.z, a * v0.w + c * v1.w};
    } else {
      const ZQuat b0{0.375, 0.0};  // tangents exact in float
      const ZQuat a1{0.25, -0.125};
      const double h00 = 2 * u * u * u - 3 * u * u + 1;
      const double h10 = u * u * u - 2 * u * u + u;
      const double h01 = -2 * u * u * u + 3 * u * u;
      const double h11 = u * u * u - u * u;
      q = {h00 * v0.z + td * h10 * b0.z + h01 * v1.z + td * h11 * a1.z,
           h00 * v0.w + td * h10 * b0.w + h01 * v1.w + td * h11 * a1.w};
    }
  }
  return 2.0 * std::atan2(q.z, q.w);  // atan2 normalises the quaternion for us
}

// Tip joint's skin matrix S_1 = G_tip IBM_tip applied to x: turn about the joint, then the root's shift.
Vec3 tipSkin(const Vec3& x, const PoseParams& p) {
  const Vec3 d = x - kTipJoint;
  const Vec3 turned(std::cos(p.angle) * d.x - std::sin(p.angle) * d.y, std::sin(p.angle) * d.x + std::cos(p.angle) * d.y, d.z);
  return kTipJoint + turned + Vec3(p.root_dx, 0.0, 0.0);
}

Vec3 expectedVertex(const Vec3& rest, double tip_weight, const Vec3& delta, const PoseParams& p) {
  const Vec3 x = rest + p.morph * delta;
  return (1.0 - tip_weight) * (x + Vec3(p.root_dx, 0.0, 0.0)) + tip_weight * tipSkin(x, p);
}

int ringOf(const Vec3& p) { return static_cast<int>(std::lround(p.y)); }

double tipWeight(int ring, const TubeOptions& o) {
  if (ring == 0) return 0.0;
  if (ring == 2) return 1.0;
  return o.ring1_weights[1] / (o.ring1_weights[0] + o.ring1_weights[1]);
}

Vec3 deltaOf(int ring, const TubeOptions& o) {
  if (ring == 2) return kDelta;
  if (ring == 1 && o.sparse_over_base) return kBaseDelta;
  return Vec3(0.0);
}

void expectNear(const Vec3& actual, const Vec3& expected, double tolerance, const std::string& what) {
  EXPECT_LT(glm::length(actual - expected), tolerance)
      << what << ": (" << actual.x << ", " << actual.y << ", " << actual.z << ") vs (" << expected.x << ", "
      << expected.y << ", " << expected.z << ")";
}

Result<ExampleSet> read(const fs::path& path, std::vector<double> times, std::vector<int> targets,
                        std::string animation) {
  GltfPoseRequest request;
  request.animation = std::move(animation);
  request.times = std::move(times);
  request.morph_targets = std::move(targets);
  return readGltfExamples(path, request);
}

void expectError(const Result<ExampleSet>& r, StatusCode code, const std::vector<std::string>& words) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), code) << r.status().toString();
  for (const std::string& w : words) {
    EXPECT_NE(r.status().message().find(w), std::string::npos) << "'" << w << "' not in: " << r.status().message();
  }
}

}  // namespace odeskin::testing

// SPDX-License-Identifier: MIT
// The glTF reader against small models written here through tinygltf (.gltf with base64 buffers
// and .glb): a two-joint tube with a UV seam, bent by an animation, with a morph target.
#include "engine/io/gltf_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "engine/export/gltf_export.hpp"
#include "engine/io/asset_file.hpp"
#include "engine/io/text_tokens.hpp"
#include "engine/one_pixel_png.hpp"  // tests/engine
#include "engine/offline/deform_player.hpp"
#include "engine/pipeline/fit_pipeline.hpp"
#include "engine/runtime/runtime_asset.hpp"
#include <tiny_gltf.h>

namespace odeskin {
namespace {

namespace fs = std::filesystem;

constexpr int kByteType = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByteType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShortType = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShortType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUIntType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kFloatType = TINYGLTF_COMPONENT_TYPE_FLOAT;

// ---------------------------------------------------------------------------------------------
// Writing models

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

// A 4-byte aligned bufferView over `bytes` appended to buffer 0.
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

// One buffer; every call appends a 4-byte aligned bufferView (and an accessor over it).
struct Builder {
  tinygltf::Model model;

  Builder() {
    model.buffers.emplace_back();
    model.asset.version = "2.0";
    model.asset.generator = "odeskin gltf_reader_test";
  }

  int view(const std::vector<unsigned char>& bytes) { return appendBufferView(model, bytes); }

  // An accessor over a new bufferView holding `values` (all components, element after element).
  int accessor(const std::vector<double>& values, int component_type, int type, bool normalized = false) {
    tinygltf::Accessor a;
    a.bufferView = view(pack(values, component_type));
    a.componentType = component_type;
    a.type = type;
    a.normalized = normalized;
    a.count = values.size() / componentsOf(type);
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
  }

  // A float VEC3 accessor of `count` zeros (no bufferView, or `base` as its bufferView data)
  // with `values` substituted at `indices` through a sparse accessor.
  int sparseVec3(std::size_t count, const std::vector<double>* base, const std::vector<std::uint32_t>& indices,
                 const std::vector<double>& values, int index_type) {
    tinygltf::Accessor a;
    a.bufferView = base ? view(pack(*base, kFloatType)) : -1;
    a.componentType = kFloatType;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = count;
    a.sparse.isSparse = true;
    a.sparse.count = static_cast<int>(indices.size());
    a.sparse.indices.bufferView = view(pack(std::vector<double>(indices.begin(), indices.end()), index_type));
    a.sparse.indices.byteOffset = 0;
    a.sparse.indices.componentType = index_type;
    a.sparse.values.bufferView = view(pack(values, kFloatType));
    a.sparse.values.byteOffset = 0;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
  }
};

fs::path tempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::temp_directory_path() / "odeskin_gltf_reader_test" / (std::string(info->test_suite_name()) + "." + info->name());
  fs::create_directories(dir);
  return dir;
}

// A file's bytes, as the readers see them.
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

// ---------------------------------------------------------------------------------------------
// The tube: rings y = 0, 1, 2 of a square (x, z) = (1, 0), (0, 1), (-1, 0), (0, -1), plus a fifth
// column that repeats column 0 with u = 1 (the UV seam). Joint "root" (node 1) at the origin,
// joint "tip" (node 2) at y = 1; ring 0 follows root, ring 2 tip, ring 1 both.

constexpr std::array<std::array<double, 2>, 5> kSquare{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 0}}};
constexpr int kColumns = 5;
const Vec3 kTipJoint(0.0, 1.0, 0.0);
const Vec3 kDelta(0.25, 0.0, 0.125);      // the morph target's displacement of ring 2
const Vec3 kBaseDelta(0.5, 0.0, 0.0);     // under the sparse values: ring 1 (ring 2 is overridden)
const double kHalfTurnZ = static_cast<float>(std::sqrt(0.5));  // quarter turn about z, as stored

struct Prim {
  std::vector<Vec3> positions;
  std::vector<int> ring;
  std::vector<int> column;
  std::vector<std::array<double, 4>> joints0, weights0, joints1, weights1;  // as stored
  std::vector<std::uint32_t> indices;                                        // empty: unindexed
};

// Fields ordered by size (clang-tidy's padding check).
struct TubeOptions {
  double position_scale = 1.0;    // stored = (position - offset) x scale, rounded for integers
  double uv_scale = 1.0;          // TEXCOORD_0 as integers: stored = uv x uv_scale
  std::array<double, 2> ring1_weights{1.0, 3.0};  // stored weights of joints 0 and 1 on ring 1
  Vec3 position_offset{0.0};
  std::string interpolation = "LINEAR";
  std::function<Vec3(int ring, int column)> normal;  // NORMAL of each vertex; none when empty
  std::function<Vec2(int ring, int column)> uv = [](int ring, int column) { return Vec2(column / 4.0, ring / 2.0); };
  std::function<void(Prim&)> tweak;
  int joint_type = kUByteType;
  int weight_type = kFloatType;   // float, or unsigned byte / short stored normalized
  int sparse_index_type = kUShortType;
  int position_type = kFloatType;
  int normal_type = kFloatType;   // float, or byte stored normalized (x 127)
  int uv_type = kFloatType;       // TEXCOORD_0: float, or an integer type (x uv_scale)
  bool two_sets = false;          // joint 1's weight in JOINTS_1/WEIGHTS_1
  bool two_primitives = false;    // rings 0-1 indexed, rings 1-2 unindexed
  bool sparse_over_base = false;  // the morph target's sparse values lie over a bufferView
  bool position_normalized = false;
  // KHR_mesh_quantization's skinned layout (gltfpack, glTF-Transform): morph deltas stored x scale
  // too, and every inverse bind matrix times the dequantization D = translate(offset) scale(1/scale).
  bool fold_into_skin = false;
  bool uv_normalized = false;
  bool uv_in_first_primitive_only = false;
};

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

// Rotation keys of "bend" (joint tip, times 0 and 2 s): identity to a quarter turn about z. For
// CUBICSPLINE each keyframe is in-tangent, value, out-tangent (glTF quaternions x y z w).
std::vector<double> rotationKeys(const std::string& interpolation) {
  const double s = kHalfTurnZ;
  if (interpolation == "CUBICSPLINE") {
    return {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0.375, 0, 0, 0, 0.25, -0.125, 0, 0, s, s, 0, 0, 0, 0};
  }
  return {0, 0, 0, 1, 0, 0, s, s};
}

struct Tube {
  tinygltf::Model model;
  std::vector<Vec3> render_positions;  // as written, primitives concatenated
  int position_accessor = -1;          // POSITION of primitive 0
};

Tube makeTube(const TubeOptions& o = {}) {
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

// ---------------------------------------------------------------------------------------------
// The expected poses, computed independently of the reader

// glTF quaternions restricted to the z axis: (z, w).
struct ZQuat {
  double z = 0.0;
  double w = 1.0;
};

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

struct PoseParams {
  double root_dx = 0.0;  // the root joint's x translation
  double angle = 0.0;    // the tip joint's rotation about z, through its joint at y = 1
  double morph = 0.0;    // the morph target's weight
};

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

Result<ExampleSet> read(const fs::path& path, std::vector<double> times, std::vector<int> targets = {},
                        std::string animation = "bend") {
  GltfPoseRequest request;
  request.animation = std::move(animation);
  request.times = std::move(times);
  request.morph_targets = std::move(targets);
  return readGltfExamples(path, request);
}

// ---------------------------------------------------------------------------------------------
// Tests

class GltfFormats : public ::testing::TestWithParam<bool> {};  // parameter: write GLB

TEST_P(GltfFormats, SeamIsWeldedAndRenderLayoutKept) {
  const Tube tube = makeTube();
  const auto examples = read(write(tube.model, GetParam() ? "tube.glb" : "tube.gltf", GetParam()), {0.5});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.render.topology_of_render.size(), 15u);
  ASSERT_EQ(e.rest_positions.size(), 12u);  // 3 rings x 4 corners; the seam column is welded
  for (std::uint32_t r = 0; r < 15; ++r) {
    const std::uint32_t t = e.render.topology_of_render[r];
    EXPECT_EQ(e.rest_positions[t], tube.render_positions[r]) << "render vertex " << r;
    if (r % kColumns == 4) {
      EXPECT_EQ(t, e.render.topology_of_render[r - 4]) << "seam vertex " << r;
    }
  }
  ASSERT_EQ(e.faces.faceCount(), 16u);
  ASSERT_EQ(e.render.faces.faceCount(), 16u);
  for (std::size_t k = 0; k < e.faces.indices.size(); ++k) {
    EXPECT_EQ(e.faces.indices[k], e.render.topology_of_render[e.render.faces.indices[k]]);
  }
  EXPECT_EQ(e.pose_labels, (std::vector<std::string>{std::string(GetParam() ? "tube.glb" : "tube.gltf") + " bind",
                                                     std::string(GetParam() ? "tube.glb" : "tube.gltf") + " bend at 0.5 s"}));
}

TEST_P(GltfFormats, TwoPrimitivesIndexedAndNotWeldIntoOneTopology) {
  TubeOptions o;
  o.two_primitives = true;
  const Tube tube = makeTube(o);
  const auto examples = read(write(tube.model, GetParam() ? "two.glb" : "two.gltf", GetParam()), {1.0}, {0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.render.topology_of_render.size(), 10u + 24u);
  ASSERT_EQ(e.rest_positions.size(), 12u);
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    EXPECT_EQ(e.rest_positions[e.render.topology_of_render[r]], tube.render_positions[r]) << "render vertex " << r;
  }
  EXPECT_EQ(e.faces.faceCount(), 16u);
  EXPECT_EQ(e.render.faces.faceCount(), 16u);
  // The morph target: zeros in primitive 0 (no bufferView), sparse in primitive 1.
  ASSERT_EQ(e.poses.size(), 3u);
  for (std::size_t v = 0; v < 12; ++v) {
    expectNear(e.poses[2][v], e.rest_positions[v] + deltaOf(ringOf(e.rest_positions[v]), o), 1e-12, "target pose");
  }
}

INSTANTIATE_TEST_SUITE_P(GltfAndGlb, GltfFormats, ::testing::Bool());

TEST(GltfReader, TriangleCollapsedByWeldingStaysOnlyInRenderFaces) {
  TubeOptions o;
  o.tweak = [](Prim& p) { p.indices.insert(p.indices.end(), {0, 4, 5}); };  // 0 and 4 are the seam pair
  const auto examples = read(write(makeTube(o).model, "sliver.gltf", false), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_EQ(examples->render.faces.faceCount(), 17u);
  EXPECT_EQ(examples->faces.faceCount(), 16u);
}

// The tube's square corners, outward; the seam column's copy (column 4) of column 0 either the same
// (a UV seam) or turned 53 degrees (a hard edge).
Vec3 cornerNormal(int column, bool hard_seam) {
  if (column == 4 && hard_seam) return Vec3(0.6, 0.0, 0.8);
  const auto& c = kSquare[static_cast<std::size_t>(column)];
  return Vec3(c[0], 0.0, c[1]);
}

TEST(GltfReader, NormalsAreKeptPerRenderVertex) {
  TubeOptions o;
  o.normal = [](int, int column) { return cornerNormal(column, true); };
  auto examples = read(write(makeTube(o).model, "normals.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.normals.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) {
    const Vec3 n = cornerNormal(static_cast<int>(r % kColumns), true);  // as float32 stores it
    EXPECT_EQ(examples->render.normals[r], Vec3(static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)))
        << "render vertex " << r;
  }
  EXPECT_TRUE(examples->warnings.empty());

  // KHR_mesh_quantization's normalized bytes decode to within 1/127.
  o.normal_type = kByteType;
  o.position_type = kFloatType;
  tinygltf::Model quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "normals-q.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.normals.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) {
    EXPECT_LT(glm::length(examples->render.normals[r] - cornerNormal(static_cast<int>(r % kColumns), true)), 1.0 / 127.0);
  }

  // A zero normal drops them all, with a warning naming the file and the vertex.
  o.normal_type = kFloatType;
  o.normal = [](int ring, int column) { return ring == 1 && column == 2 ? Vec3(0.0) : cornerNormal(column, true); };
  examples = read(write(makeTube(o).model, "zero-normal.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.normals.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("zero-normal.glb: NORMAL of vertex 7 is zero or not finite"), std::string::npos)
      << examples->warnings[0];
}

// TEXCOORD_0 per render vertex: float as stored, normalized integers decoded; what cannot be kept
// (unnormalized quantized integers, a primitive without it) is dropped with a warning.
TEST(GltfReader, TexcoordsAreKeptPerRenderVertex) {
  auto expected = [](std::size_t r) {
    const std::size_t ring = r / kColumns;  // the tube's vertices go ring by ring
    return Vec2(static_cast<double>(r % kColumns) / 4.0, static_cast<double>(ring) / 2.0);
  };
  TubeOptions o;
  auto examples = read(write(makeTube(o).model, "uv.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_EQ(examples->render.uvs[r], expected(r)) << "render vertex " << r;  // exact in float32
  EXPECT_TRUE(examples->warnings.empty());

  o.uv_type = kUShortType;  // core glTF: normalized unsigned short
  o.uv_normalized = true;
  o.uv_scale = 65535.0;
  examples = read(write(makeTube(o).model, "uv-ushort.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_LT(glm::length(examples->render.uvs[r] - expected(r)), 1.0 / 65535.0);

  o.uv_type = kShortType;  // KHR_mesh_quantization: normalized short, then unnormalized
  o.uv_scale = 32767.0;
  tinygltf::Model quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "uv-short.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->render.uvs.size(), 15u);
  for (std::size_t r = 0; r < 15; ++r) EXPECT_LT(glm::length(examples->render.uvs[r] - expected(r)), 1.0 / 32767.0);
  o.uv_normalized = false;
  quantized = makeTube(o).model;
  quantized.extensionsRequired = quantized.extensionsUsed = {"KHR_mesh_quantization"};
  examples = read(write(quantized, "uv-raw.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.uvs.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("uv-raw.glb: TEXCOORD_0 is not kept: primitive 0 stores TEXCOORD_0 as unnormalized "
                                       "integers"),
            std::string::npos)
      << examples->warnings[0];

  o = TubeOptions{};
  o.two_primitives = true;
  o.uv_in_first_primitive_only = true;
  examples = read(write(makeTube(o).model, "uv-partial.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_TRUE(examples->render.uvs.empty());
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find("TEXCOORD_0 is not kept: some primitives have no TEXCOORD_0"), std::string::npos)
      << examples->warnings[0];

  // A NaN is refused like in any accessor, naming it.
  o = TubeOptions{};
  o.uv = [](int ring, int column) { return ring == 2 && column == 1 ? Vec2(std::nan(""), 0.0) : Vec2(0.5); };
  examples = read(write(makeTube(o).model, "uv-nan.glb", true), {1.0});
  ASSERT_FALSE(examples.ok());
  EXPECT_NE(examples.status().message().find("uv-nan.glb: accessor 1 (mesh 0 primitive 0 TEXCOORD_0): element 11 is not a "
                                             "finite number"),
            std::string::npos)
      << examples.status().message();
}

TEST(GltfReader, SkeletonFromSkin) {
  const auto examples = read(write(makeTube().model, "tube.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_TRUE(examples->rig.has_value());
  const Skeleton& s = examples->rig->skeleton;
  EXPECT_EQ(s.names, (std::vector<std::string>{"root", "tip"}));
  EXPECT_EQ(s.parents, (std::vector<std::int32_t>{-1, 0}));
  ASSERT_EQ(s.heads.size(), 2u);
  EXPECT_EQ(s.heads[0], Vec3(0.0));
  EXPECT_EQ(s.heads[1], kTipJoint);
  EXPECT_EQ(s.tails[0], kTipJoint);  // the first child joint's head
  EXPECT_EQ(s.tails[1], kTipJoint);  // no child: its own head
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
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  Result<std::string> bytes = encodeAsset(fit->asset);
  ASSERT_TRUE(bytes.ok());
  Result<DeformAsset> loaded = decodeAsset(*bytes, "textured.odsk");
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

using testing::kOnePixelPng;

// The two-primitive tube dressed in two materials: "skin" with a PNG base colour texture placed by
// KHR_texture_transform, and "cloth" with KHR_materials_emissive_strength; primitive p uses
// material p. `external_image`: the PNG is a file beside the glTF rather than in its buffer.
tinygltf::Model dressedTube(bool external_image = false) {
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
  Result<PipelineResult> fit = runFitPipeline(*examples, PipelineOptions{});
  ASSERT_TRUE(fit.ok()) << fit.status().toString();
  Result<std::string> bytes = encodeAsset(fit->asset);
  ASSERT_TRUE(bytes.ok());
  Result<DeformAsset> loaded = decodeAsset(*bytes, "dressed.odsk");
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
}

TEST(GltfReaderErrors, MaterialThatDoesNotExist) {
  tinygltf::Model model = dressedTube();
  model.meshes[0].primitives[1].material = 9;
  const auto examples = read(write(model, "bad-material.glb", true), {1.0});
  ASSERT_FALSE(examples.ok());
  EXPECT_NE(examples.status().message().find("bad-material.glb: mesh 0 primitive 1 uses material 9 of 2"), std::string::npos)
      << examples.status().message();
}

struct WeightCase {
  int joint_type;
  int weight_type;
  std::array<double, 2> ring1;
  bool two_sets;
};

void PrintTo(const WeightCase& c, std::ostream* os) {
  *os << "joints " << c.joint_type << " weights " << c.weight_type << " ring 1 (" << c.ring1[0] << ", " << c.ring1[1]
      << ")" << (c.two_sets ? " in two sets" : "");
}

class GltfWeights : public ::testing::TestWithParam<WeightCase> {};

TEST_P(GltfWeights, NormalisedPerVertexForEveryComponentType) {
  TubeOptions o;
  o.joint_type = GetParam().joint_type;
  o.weight_type = GetParam().weight_type;
  o.ring1_weights = GetParam().ring1;
  o.two_sets = GetParam().two_sets;
  const auto examples = read(write(makeTube(o).model, "weights.gltf", false), {0.5});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  const Influences& in = e.rig->influences;
  ASSERT_EQ(in.vertexCount(), 12u);
  for (std::size_t v = 0; v < 12; ++v) {
    const int ring = ringOf(e.rest_positions[v]);
    std::map<std::uint32_t, double> w;
    double sum = 0.0;
    for (std::uint32_t k = in.offsets[v]; k < in.offsets[v + 1]; ++k) {
      w[in.bones[k]] += in.weights[k];
      sum += in.weights[k];
      EXPECT_GT(in.weights[k], 0.0) << "zero weights are dropped";
    }
    EXPECT_NEAR(sum, 1.0, 1e-15) << "vertex " << v;
    EXPECT_NEAR(w[1], tipWeight(ring, o), 1e-12) << "vertex " << v;
    EXPECT_EQ(in.offsets[v + 1] - in.offsets[v], ring == 1 ? 2u : 1u) << "vertex " << v;
  }
}

INSTANTIATE_TEST_SUITE_P(
    ComponentTypes, GltfWeights,
    ::testing::Values(WeightCase{kUByteType, kFloatType, {1.0, 3.0}, false},        // sums to 4: normalised
                      WeightCase{kUShortType, kFloatType, {0.25, 0.75}, false},
                      WeightCase{kUByteType, kUByteType, {64.0, 191.0}, false},     // 64/255, 191/255
                      WeightCase{kUShortType, kUByteType, {100.0, 100.0}, false},   // sums to 200/255
                      WeightCase{kUByteType, kUShortType, {16384.0, 49151.0}, false},
                      WeightCase{kUShortType, kUShortType, {1000.0, 3000.0}, true}, // JOINTS_1/WEIGHTS_1
                      WeightCase{kUByteType, kFloatType, {0.5, 0.5}, true}));

struct PoseCase {
  std::string interpolation;
  bool binary;
};

void PrintTo(const PoseCase& c, std::ostream* os) { *os << c.interpolation << (c.binary ? " glb" : " gltf"); }

class GltfPoses : public ::testing::TestWithParam<PoseCase> {};

TEST_P(GltfPoses, EqualIndependentLinearBlendSkinning) {
  TubeOptions o;
  o.interpolation = GetParam().interpolation;
  const std::vector<double> times{-0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0};
  const auto examples = read(write(makeTube(o).model, GetParam().binary ? "bend.glb" : "bend.gltf", GetParam().binary), times);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  ASSERT_EQ(e.poses.size(), times.size() + 1);
  ASSERT_EQ(e.rig->key_poses.size(), times.size() + 1);
  for (std::size_t v = 0; v < 12; ++v) EXPECT_EQ(e.poses[0][v], e.rest_positions[v]);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const PoseParams p{0.5 * std::clamp(t, 0.0, 1.0), bendAngle(o.interpolation, t), 0.0};
    const std::vector<Vec3>& pose = e.poses[k + 1];
    for (std::size_t v = 0; v < 12; ++v) {
      const Vec3& x = e.rest_positions[v];
      expectNear(pose[v], expectedVertex(x, tipWeight(ringOf(x), o), Vec3(0.0), p), 1e-9,
                 "t " + std::to_string(t) + " vertex " + std::to_string(v));
    }
    // Key poses are the joints' skin matrices (rigid here).
    const std::vector<RigidTransform>& key = e.rig->key_poses[k + 1];
    for (const Vec3& x : {Vec3(0.0), Vec3(1.0, 2.0, 3.0), Vec3(-1.0, 0.5, 0.0)}) {
      expectNear(key[0].apply(x), x + Vec3(p.root_dx, 0.0, 0.0), 1e-9, "root key pose");
      expectNear(key[1].apply(x), tipSkin(x, p), 1e-9, "tip key pose");
    }
  }
  // A quarter turn at the end (float data aside), and none at the start.
  EXPECT_NEAR(bendAngle(o.interpolation, 2.0), std::numbers::pi / 2, 1e-7);
  for (const RigidTransform& identity : e.rig->key_poses[0]) {
    EXPECT_EQ(identity.rotation, glm::dquat(1.0, 0.0, 0.0, 0.0));
    EXPECT_EQ(identity.translation, Vec3(0.0));
  }
}

INSTANTIATE_TEST_SUITE_P(Interpolations, GltfPoses,
                         ::testing::Values(PoseCase{"LINEAR", false}, PoseCase{"LINEAR", true}, PoseCase{"STEP", false},
                                           PoseCase{"CUBICSPLINE", false}, PoseCase{"CUBICSPLINE", true}),
                         [](const auto& case_info) { return case_info.param.interpolation + (case_info.param.binary ? "_glb" : "_gltf"); });

TEST(GltfReader, AnimatedMorphWeightsApplyBeforeSkinning) {
  const TubeOptions o;
  const auto examples = read(write(makeTube(o).model, "wiggle.gltf", false), {1.0, 2.0}, {}, "wiggle");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  const ExampleSet& e = *examples;
  for (std::size_t k = 0; k < 2; ++k) {
    const double t = k == 0 ? 1.0 : 2.0;
    const PoseParams p{0.0, bendAngle("LINEAR", t), t / 2.0};
    for (std::size_t v = 0; v < 12; ++v) {
      const Vec3& x = e.rest_positions[v];
      expectNear(e.poses[k + 1][v], expectedVertex(x, tipWeight(ringOf(x), o), deltaOf(ringOf(x), o), p), 1e-9,
                 "wiggle t " + std::to_string(t) + " vertex " + std::to_string(v));
    }
  }
  EXPECT_EQ(e.pose_labels[1], "wiggle.gltf wiggle at 1 s");
}

TEST(GltfReader, AnimationByIndex) {
  const auto examples = read(write(makeTube().model, "tube.gltf", false), {2.0}, {}, "1");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_EQ(examples->pose_labels[1], "tube.gltf wiggle at 2 s");
}

TEST(GltfReader, TimesOutsideTheKeyframesAreReadWithAWarning) {
  const fs::path path = write(makeTube().model, "tube.gltf", false);
  const auto inside = read(path, {0.0, 0.5, 2.0});
  ASSERT_TRUE(inside.ok()) << inside.status().toString();
  EXPECT_TRUE(inside->warnings.empty());

  // "bend" keys its rotation at 0 and 2 s and its translation at 0 and 1 s.
  const auto outside = read(path, {-0.5, 1.0, 3.0});
  ASSERT_TRUE(outside.ok()) << outside.status().toString();
  ASSERT_EQ(outside->warnings.size(), 2u);
  for (const std::string& piece :
       std::vector<std::string>{path.string() + ": -0.5 s is outside bend's keyframes (0 to 2 s)", "at 0 s"}) {
    EXPECT_NE(outside->warnings[0].find(piece), std::string::npos) << outside->warnings[0];
  }
  for (const std::string& piece : std::vector<std::string>{path.string() + ": 3 s is outside", "at 2 s"}) {
    EXPECT_NE(outside->warnings[1].find(piece), std::string::npos) << outside->warnings[1];
  }
  // The warning says what happened: the pose at 3 s is the one at 2 s.
  const auto end = read(path, {2.0});
  ASSERT_TRUE(end.ok());
  EXPECT_EQ(outside->poses[3], end->poses[1]);
}

TEST(GltfReader, AnAnimationThatMovesNothingIsReadWithAWarning) {
  Builder b;
  b.model = makeTube().model;
  // Its one channel targets no node (as one of an extension's may), so odeskin skips it.
  tinygltf::Animation still;
  still.name = "still";
  addChannel(b, still, -1, "translation", "LINEAR", {0.0, 1.0}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.model.animations.push_back(still);
  const fs::path path = write(b.model, "still.gltf", false);
  const auto examples = read(path, {0.5, 1.0}, {}, "still");
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->warnings.size(), 1u);
  EXPECT_NE(examples->warnings[0].find(path.string() + ": still animates no node"), std::string::npos)
      << examples->warnings[0];
}

TEST(GltfReader, SparseMorphTargetIsApplied) {
  for (int index_type : {kUByteType, kUShortType, kUIntType}) {
    for (bool over_base : {false, true}) {
      TubeOptions o;
      o.sparse_index_type = index_type;
      o.sparse_over_base = over_base;
      GltfPoseRequest request;
      request.morph_targets = {0};
      const auto examples = readGltfExamples(write(makeTube(o).model, "sparse.glb", true), request);
      ASSERT_TRUE(examples.ok()) << examples.status().toString();
      const ExampleSet& e = *examples;
      ASSERT_EQ(e.poses.size(), 2u);
      EXPECT_EQ(e.pose_labels[1], "sparse.glb target 0");
      for (std::size_t v = 0; v < 12; ++v) {
        const Vec3& x = e.rest_positions[v];
        EXPECT_EQ(e.poses[1][v], x + deltaOf(ringOf(x), o)) << "vertex " << v << " index type " << index_type;
      }
      for (const RigidTransform& key : e.rig->key_poses[1]) EXPECT_EQ(key.translation, Vec3(0.0));
    }
  }
}

TEST(GltfReader, QuantizedPositions) {
  TubeOptions o;
  o.position_type = kShortType;
  o.position_normalized = true;
  o.position_scale = 16000.0;
  GltfPoseRequest request;
  request.morph_targets = {0};
  const Tube tube = makeTube(o);
  const auto examples = readGltfExamples(write(tube.model, "quantized.gltf", false), request);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  ASSERT_EQ(examples->rest_positions.size(), 12u);
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    const Vec3 stored = tube.render_positions[r] * 16000.0;
    EXPECT_EQ(examples->rest_positions[examples->render.topology_of_render[r]], stored / 32767.0);
  }
  // Without the extension those formats are not glTF.
  tinygltf::Model plain = tube.model;
  plain.extensionsRequired.clear();
  plain.extensionsUsed.clear();
  const auto refused = readGltfExamples(write(plain, "plain.gltf", false), request);
  EXPECT_EQ(refused.status().code(), StatusCode::kParseError);
  EXPECT_NE(refused.status().message().find("accessor " + std::to_string(tube.position_accessor)), std::string::npos)
      << refused.status().message();
}

// gltfpack's layout: 16-bit unsigned grid coordinates, the dequantization folded into the IBMs.
TubeOptions gltfpackLayout() {
  TubeOptions o;
  o.position_type = kUShortType;
  o.position_scale = 65535.0 / 2.0;  // the tube spans 2 along every axis
  o.position_offset = Vec3(-1.0, 0.0, -1.0);
  o.fold_into_skin = true;
  return o;
}

TEST(GltfReader, QuantizedSkinGivesTheFloatFilesPoses) {
  const TubeOptions o = gltfpackLayout();
  const double step = 1.0 / o.position_scale;
  const auto exact = read(write(makeTube().model, "float.glb", true), {0.5, 1.0}, {0});
  const auto quantized = read(write(makeTube(o).model, "quantized.glb", true), {0.5, 1.0}, {0});
  ASSERT_TRUE(exact.ok()) << exact.status().toString();
  ASSERT_TRUE(quantized.ok()) << quantized.status().toString();
  // The rest pose is the bind pose, so the grid goes back to the tube's own coordinates.
  ASSERT_EQ(quantized->rest_positions.size(), exact->rest_positions.size());
  for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
    expectNear(quantized->rest_positions[v], exact->rest_positions[v], step, "rest vertex " + std::to_string(v));
  }
  ASSERT_EQ(quantized->poses.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
      expectNear(quantized->poses[k][v], exact->poses[k][v], 2.0 * step,
                 quantized->pose_labels[k] + " vertex " + std::to_string(v));
    }
    for (std::size_t j = 0; j < 2; ++j) {
      const RigidTransform& a = quantized->rig->key_poses[k][j];
      const RigidTransform& b = exact->rig->key_poses[k][j];
      expectNear(a.translation, b.translation, 1e-6, "key translation");
      EXPECT_GT(std::abs(glm::dot(a.rotation, b.rotation)), 1.0 - 1e-9);
    }
  }
  for (std::size_t j = 0; j < 2; ++j) {
    expectNear(quantized->rig->skeleton.heads[j], exact->rig->skeleton.heads[j], 1e-6, "joint head");
  }
}

TEST(GltfReader, QuantizedSkinAwayFromItsBindPoseKeepsThePoses) {
  // The root rests 2 to the side of where it was bound: the bind space may move, the poses may not.
  auto shifted = [](const TubeOptions& o) {
    tinygltf::Model m = makeTube(o).model;
    m.nodes[1].translation = {2.0, 0.0, 0.0};
    return m;
  };
  const TubeOptions o = gltfpackLayout();
  const auto exact = read(write(shifted(TubeOptions{}), "float.glb", true), {0.5, 1.0}, {0});
  const auto quantized = read(write(shifted(o), "quantized.glb", true), {0.5, 1.0}, {0});
  ASSERT_TRUE(exact.ok()) << exact.status().toString();
  ASSERT_TRUE(quantized.ok()) << quantized.status().toString();
  for (std::size_t k = 1; k < 3; ++k) {  // the poses at times; the bind pose and target are bind space
    for (std::size_t v = 0; v < exact->rest_positions.size(); ++v) {
      expectNear(quantized->poses[k][v], exact->poses[k][v], 2.0 / o.position_scale,
                 quantized->pose_labels[k] + " vertex " + std::to_string(v));
    }
  }
}

TEST(GltfReader, QuantizedSkinWhoseJointsScaleDifferentlyIsRefused) {
  tinygltf::Model m = makeTube(gltfpackLayout()).model;
  // Joint 1's inverse bind matrix scaled once more: no one grid explains both joints.
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(m.skins[0].inverseBindMatrices)];
  const tinygltf::BufferView& view = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
  auto* floats = reinterpret_cast<float*>(m.buffers[0].data.data() + view.byteOffset + a.byteOffset);
  for (int k = 0; k < 12; ++k) floats[16 + k] *= 1.5f;
  const fs::path path = write(m, "two-scales.glb", true);
  const auto r = read(path, {1.0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  for (const std::string& w : std::vector<std::string>{path.string(), "skin 0", "joint 1 'tip'", "joint 0 'root'",
                                                       "KHR_mesh_quantization"}) {
    EXPECT_NE(r.status().message().find(w), std::string::npos) << w << " not in: " << r.status().message();
  }
}

TEST(GltfReader, QuantizedUnskinnedMeshTakesItsNodesTransform) {
  TubeOptions o = gltfpackLayout();
  o.fold_into_skin = false;
  Tube tube = makeTube(o);
  tinygltf::Node& node = tube.model.nodes[0];
  node.skin = -1;  // the node's transform now counts: it holds the dequantization
  node.translation = {o.position_offset.x, o.position_offset.y, o.position_offset.z};
  node.scale = std::vector<double>(3, 1.0 / o.position_scale);
  GltfPoseRequest request;
  request.morph_targets = {0};
  const auto examples = readGltfExamples(write(tube.model, "unskinned.glb", true), request);
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    expectNear(examples->rest_positions[examples->render.topology_of_render[r]], tube.render_positions[r],
               1.0 / o.position_scale, "render vertex " + std::to_string(r));
  }
}

// An unskinned mesh is read where its node's world transform puts it, as viewers show it: Blender's
// exporter leaves such a transform on every mesh it turns (a character imported from a y-up OBJ
// gets a quarter turn about x). A mirroring transform reverses the triangles' corners so they keep
// facing out; one that collapses the mesh is refused.
TEST(GltfReader, UnskinnedMeshIsReadWhereItsNodePutsIt) {
  tinygltf::Model model = makeTube().model;
  model.nodes[0].skin = -1;
  model.nodes[0].translation.clear();  // the tube's skinned node is translated: here its mesh space is wanted
  const auto local = read(write(model, "local.gltf", false), {}, {0});
  ASSERT_TRUE(local.ok()) << local.status().toString();
  // The mesh node under a parent: world = parent (translate) x node (turn, scale).
  tinygltf::Node parent;
  parent.translation = {1.0, 2.0, 3.0};
  parent.children = {0};
  model.nodes.push_back(parent);
  model.scenes[0].nodes = {static_cast<int>(model.nodes.size() - 1)};
  model.nodes[0].rotation = {std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};  // x, y, z, w: 90 degrees about x
  model.nodes[0].scale = {2.0, 2.0, 2.0};
  const auto placed = read(write(model, "placed.gltf", false), {}, {0});
  ASSERT_TRUE(placed.ok()) << placed.status().toString();
  auto world = [](const Vec3& p) { return Vec3(1.0, 2.0, 3.0) + 2.0 * Vec3(p.x, -p.z, p.y); };
  ASSERT_EQ(placed->poses.size(), local->poses.size());
  for (std::size_t k = 0; k < placed->poses.size(); ++k) {
    for (std::size_t v = 0; v < placed->poses[k].size(); ++v) {
      expectNear(placed->poses[k][v], world(local->poses[k][v]), 1e-12, "pose " + std::to_string(k));
    }
  }
  EXPECT_EQ(placed->faces.indices, local->faces.indices);
  for (std::size_t r = 0; r < placed->render.normals.size(); ++r) {
    const Vec3& n = local->render.normals[r];
    expectNear(placed->render.normals[r], Vec3(n.x, -n.z, n.y), 1e-12, "normal");
  }
  model.nodes[0].scale = {-2.0, 2.0, 2.0};
  const auto mirrored = read(write(model, "mirrored.gltf", false), {}, {0});
  ASSERT_TRUE(mirrored.ok()) << mirrored.status().toString();
  ASSERT_EQ(mirrored->faces.indices.size(), local->faces.indices.size());
  for (std::size_t t = 0; t < local->faces.indices.size(); t += 3) {
    EXPECT_EQ(mirrored->faces.indices[t], local->faces.indices[t]);
    EXPECT_EQ(mirrored->faces.indices[t + 1], local->faces.indices[t + 2]);
    EXPECT_EQ(mirrored->faces.indices[t + 2], local->faces.indices[t + 1]);
  }
  model.nodes[0].scale = {2.0, 0.0, 2.0};
  const auto collapsed = read(write(model, "collapsed.gltf", false), {}, {0});
  ASSERT_FALSE(collapsed.ok());
  EXPECT_NE(collapsed.status().message().find("collapsed.gltf: node 0 'tube': its world transform collapses the mesh (determinant 0)"), std::string::npos)
      << collapsed.status().message();
  // A node matrix must be affine: a projective last row is refused, not dropped.
  model.nodes[0].scale.clear();
  model.nodes[0].rotation.clear();
  model.nodes[0].matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0};
  const auto projective = read(write(model, "projective.gltf", false), {}, {0});
  ASSERT_FALSE(projective.ok());
  EXPECT_NE(projective.status().message().find("projective.gltf: node 0: matrix's last row must be 0, 0, 0, 1"),
            std::string::npos)
      << projective.status().message();
  model.nodes[0].matrix.clear();
  model.nodes[0].scale = {1e300, 1e300, 1e300};
  const auto overflowing = read(write(model, "overflowing.gltf", false), {}, {0});
  ASSERT_FALSE(overflowing.ok());
  EXPECT_NE(overflowing.status().message().find("node 0 'tube': its world transform scales the mesh beyond double precision"),
            std::string::npos)
      << overflowing.status().message();
}

// ---------------------------------------------------------------------------------------------
// Errors

void expectError(const Result<ExampleSet>& r, StatusCode code, const std::vector<std::string>& words) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), code) << r.status().toString();
  for (const std::string& w : words) {
    EXPECT_NE(r.status().message().find(w), std::string::npos) << "'" << w << "' not in: " << r.status().message();
  }
}

TEST(GltfReader, InterleavedPositionsHonourByteStride) {
  Tube tube = makeTube();
  // POSITION moved into an interleaved view: x y z and one float of something else per vertex.
  std::vector<double> interleaved;
  for (const Vec3& p : tube.render_positions) interleaved.insert(interleaved.end(), {p.x, p.y, p.z, 99.0});
  std::vector<unsigned char>& data = tube.model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteStride = 16;
  const std::vector<unsigned char> bytes = pack(interleaved, kFloatType);
  view.byteLength = bytes.size() - 4;  // the last vertex's extra float is not needed
  data.insert(data.end(), bytes.begin(), bytes.end());
  tube.model.bufferViews.push_back(view);
  tinygltf::Accessor& a = tube.model.accessors[static_cast<std::size_t>(tube.position_accessor)];
  a.bufferView = static_cast<int>(tube.model.bufferViews.size()) - 1;
  const auto examples = read(write(tube.model, "stride.glb", true), {1.0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  for (std::size_t r = 0; r < tube.render_positions.size(); ++r) {
    EXPECT_EQ(examples->rest_positions[examples->render.topology_of_render[r]], tube.render_positions[r]);
  }
  tube.model.bufferViews.back().byteStride = 8;  // smaller than a VEC3 of floats
  expectError(read(write(tube.model, "short_stride.glb", true), {1.0}), StatusCode::kParseError, {"byteStride 8"});
}

// parseGltfExamples reads bytes in memory as readGltfExamples reads the file, GLB or JSON with
// embedded buffers, and refuses a buffer in an external file (there is no folder to look in).
TEST_P(GltfFormats, BytesInMemoryReadAsTheFile) {
  const bool binary = GetParam();
  const fs::path path = write(makeTube().model, binary ? "tube.glb" : "tube.gltf", binary);
  const std::string bytes = fileBytes(path);
  GltfPoseRequest request;
  request.times = {0.5, 1.0};
  request.morph_targets = {0};
  const Result<ExampleSet> from_file = readGltfExamples(path, request);
  const Result<ExampleSet> from_bytes = parseGltfExamples(bytes, path.string(), request);
  ASSERT_TRUE(from_file.ok()) << from_file.status().toString();
  ASSERT_TRUE(from_bytes.ok()) << from_bytes.status().toString();
  EXPECT_EQ(from_bytes->poses, from_file->poses);
  EXPECT_EQ(from_bytes->pose_labels, from_file->pose_labels);
  EXPECT_EQ(from_bytes->faces.indices, from_file->faces.indices);
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

TEST(GltfReaderErrors, TimesNeedASkin) {
  tinygltf::Model model = makeTube().model;
  model.nodes[0].skin = -1;
  expectError(read(write(model, "unskinned.gltf", false), {1.0}), StatusCode::kInvalidArgument, {"no skin"});
  // Morph targets alone still read, without a rig.
  const auto examples = read(write(model, "unskinned.gltf", false), {}, {0});
  ASSERT_TRUE(examples.ok()) << examples.status().toString();
  EXPECT_FALSE(examples->rig.has_value());
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

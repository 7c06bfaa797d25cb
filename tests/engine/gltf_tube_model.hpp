// SPDX-License-Identifier: MIT
// The glTF models the reader's tests write through tinygltf (.gltf with base64 buffers and .glb):
// a two-joint tube with a UV seam, bent by an animation, with a morph target, which options turn
// into every layout the reader must take; and the poses it must give, computed independently of
// the reader.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "engine/io/gltf_reader.hpp"

namespace odeskin::testing {

constexpr int kByteType = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByteType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShortType = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShortType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUIntType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kFloatType = TINYGLTF_COMPONENT_TYPE_FLOAT;

// ---------------------------------------------------------------------------------------------
// Writing models

// `values` stored as `component_type` (integers truncated), one after the other.
std::vector<unsigned char> pack(const std::vector<double>& values, int component_type);
// A 4-byte aligned bufferView over `bytes` appended to buffer 0.
int appendBufferView(tinygltf::Model& model, const std::vector<unsigned char>& bytes);
std::size_t componentsOf(int type);

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

// A folder of its own for the running test.
std::filesystem::path tempDir();
// A file's bytes, as the readers see them.
std::string fileBytes(const std::filesystem::path& path);
// `model` written to tempDir() / name, as .glb when `binary`.
std::filesystem::path write(const tinygltf::Model& model, const std::string& name, bool binary);

// ---------------------------------------------------------------------------------------------
// The tube: rings y = 0, 1, 2 of a square (x, z) = (1, 0), (0, 1), (-1, 0), (0, -1), plus a fifth
// column that repeats column 0 with u = 1 (the UV seam). Joint "root" (node 1) at the origin,
// joint "tip" (node 2) at y = 1; ring 0 follows root, ring 2 tip, ring 1 both.

constexpr std::array<std::array<double, 2>, 5> kSquare{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 0}}};
constexpr int kColumns = 5;
inline const Vec3 kTipJoint(0.0, 1.0, 0.0);
inline const Vec3 kDelta(0.25, 0.0, 0.125);      // the morph target's displacement of ring 2
inline const Vec3 kBaseDelta(0.5, 0.0, 0.0);     // under the sparse values: ring 1 (ring 2 is overridden)
inline const double kHalfTurnZ = static_cast<float>(std::sqrt(0.5));  // quarter turn about z, as stored

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
  std::array<double, 2> ring1_weights{0.25, 0.75};  // stored weights of joints 0 and 1 on ring 1
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

struct Tube {
  tinygltf::Model model;
  std::vector<Vec3> render_positions;  // as written, primitives concatenated
  int position_accessor = -1;          // POSITION of primitive 0
};

// The tube as `o` lays it out: nodes 0 (the mesh), 1 "root", 2 "tip"; animations "bend" (the tip
// turns a quarter about z over 2 s while the root moves 0.5 along x over 1 s), "wiggle" (the morph
// weight 0 to 1 and the same turn) and "squash" (the tip scales, which no rigid pose can follow).
Tube makeTube(const TubeOptions& o = {});

// A sampler of `times` and `values` (accessor type `type`) and a channel driving `path` of `node`.
void addChannel(Builder& b, tinygltf::Animation& a, int node, const std::string& path, const std::string& interpolation,
                const std::vector<double>& times, const std::vector<double>& values, int type);

// The tube's square corners, outward; the seam column's copy (column 4) of column 0 either the same
// (a UV seam) or turned 53 degrees (a hard edge).
Vec3 cornerNormal(int column, bool hard_seam);

// The two-primitive tube dressed in two materials: "skin" with a PNG base colour texture placed by
// KHR_texture_transform, and "cloth" with KHR_materials_emissive_strength; primitive p uses
// material p. `external_image`: the PNG is a file beside the glTF rather than in its buffer.
tinygltf::Model dressedTube(bool external_image = false);

// ---------------------------------------------------------------------------------------------
// The expected poses, computed independently of the reader

// The tip joint's rotation angle about z at time t under "bend"'s rotation channel (spec Appendix C).
double bendAngle(const std::string& interpolation, double t);

struct PoseParams {
  double root_dx = 0.0;  // the root joint's x translation
  double angle = 0.0;    // the tip joint's rotation about z, through its joint at y = 1
  double morph = 0.0;    // the morph target's weight
};

// Tip joint's skin matrix S_1 = G_tip IBM_tip applied to x: turn about the joint, then the root's shift.
Vec3 tipSkin(const Vec3& x, const PoseParams& p);
Vec3 expectedVertex(const Vec3& rest, double tip_weight, const Vec3& delta, const PoseParams& p);
// The ring a rest vertex lies on (its y).
int ringOf(const Vec3& p);
double tipWeight(int ring, const TubeOptions& o);
// The morph target's displacement of a vertex of `ring`.
Vec3 deltaOf(int ring, const TubeOptions& o);
void expectNear(const Vec3& actual, const Vec3& expected, double tolerance, const std::string& what);

// The file's rest pose and the poses of `animation` at `times`, then of the morph `targets`.
Result<ExampleSet> read(const std::filesystem::path& path, std::vector<double> times, std::vector<int> targets = {},
                        std::string animation = "bend");
// A refusal with `code` whose message holds every one of `words`.
void expectError(const Result<ExampleSet>& r, StatusCode code, const std::vector<std::string>& words);

}  // namespace odeskin::testing

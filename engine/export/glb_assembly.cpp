// SPDX-License-Identifier: MIT
#include "glb_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include <tiny_gltf.h>

#include "../core/number_text.hpp"
#include "../io/gltf_baked_writer.hpp"
#include "../io/gltf_buffer_builder.hpp"
#include "../io/gltf_quantized.hpp"

namespace odeskin {
namespace {

constexpr std::size_t kMaxBufferBytes = std::size_t{1} << 31;

// One model with one buffer (gltf_buffer_builder.hpp aligns every view to 4 bytes).
class ModelBuilder {
 public:
  tinygltf::Model model;

  ModelBuilder() { model.buffers.emplace_back(); }

  template <class T>
  int view(const std::vector<T>& values, int target) {
    return gltf::appendView(model, values, target);
  }

  int accessor(int view, int component_type, int type, std::size_t count) {
    return gltf::appendAccessor(model, view, component_type, type, count);
  }

  // Float accessor over new data, with min/max per component when asked (POSITION, times).
  int floats(const std::vector<float>& values, int type, int components, int target, bool bounds) {
    return gltf::appendFloatAccessor(model, values, type, components, target, bounds);
  }
};

bool allFinite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

// Finite once written as float32 (a double beyond float's range would become an infinity).
bool allFinite(const std::vector<Vec3>& values) {
  return std::all_of(values.begin(), values.end(), [](const Vec3& v) {
    return std::isfinite(static_cast<float>(v.x)) && std::isfinite(static_cast<float>(v.y)) &&
           std::isfinite(static_cast<float>(v.z));
  });
}

void putVec3(std::vector<float>& out, const Vec3& v) {
  out.insert(out.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
}

void putQuat(std::vector<float>& out, const glm::dquat& q) {  // glTF order x, y, z, w
  out.insert(out.end(), {static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z), static_cast<float>(q.w)});
}

// Times in seconds as float32, strictly increasing (the validator's rule), with min/max.
Result<int> timeAccessor(ModelBuilder& b, const std::vector<double>& t, double segment_seconds, const char* what) {
  std::vector<float> seconds;
  for (double x : t) {
    seconds.push_back(static_cast<float>(x * segment_seconds));
    if (seconds.size() > 1 && !(seconds.back() > seconds[seconds.size() - 2])) {
      return invalidArgument(std::string("export: two ") + what + " keys fall on one float32 time near " +
                             messageNumber(seconds.back()) + " s");
    }
  }
  return b.floats(seconds, TINYGLTF_TYPE_SCALAR, 1, 0, true);
}

// Values as computed and as written (decoded, in the same units) at the listed output vertices.
struct WrittenField {
  std::vector<std::uint32_t> vertices;
  std::vector<Vec3> exact;
  std::vector<Vec3> written;
};

// Where the compact export's numbers go: float32 in mesh space, or KHR_mesh_quantization's
// integers in grid steps (gltf_quantized.hpp), with what was written, to measure it.
struct Quantization {
  std::optional<PositionGrid> grid;
  WrittenField positions;  // in mesh space
  WrittenField normals;
  std::vector<WrittenField> position_targets;  // in split-target order
  std::vector<WrittenField> normal_targets;    // the same, when the targets carry normals
  std::size_t float_deltas = 0;
};

// base + sum_t w_t target_t, exact and as written, with the weights of one key (none: the base).
void morphBoth(const WrittenField& base, const std::vector<WrittenField>& targets, std::span<const double> weights,
               std::vector<Vec3>& exact, std::vector<Vec3>& written) {
  exact = base.exact;
  written = base.written;
  for (std::size_t t = 0; t < weights.size() && t < targets.size(); ++t) {
    const double w = weights[t];
    if (w == 0.0) continue;
    const WrittenField& f = targets[t];
    for (std::size_t i = 0; i < f.vertices.size(); ++i) {
      exact[f.vertices[i]] += w * f.exact[i];
      written[f.vertices[i]] += w * f.written[i];
    }
  }
}

// What the rounding costs at the base shape and at every weight key.
QuantizationCost measureQuantization(const Quantization& q, const WeightKeys& weights) {
  QuantizationCost cost;
  cost.step = q.grid->step;
  cost.float_deltas = q.float_deltas;
  const std::size_t targets = weights.weightCount();
  std::vector<Vec3> exact, written;
  NormalAngles angles;
  for (std::size_t k = 0; k <= weights.times.size(); ++k) {  // k == times: the base alone
    const std::span<const double> w =
        k < weights.times.size() && targets > 0 ? std::span<const double>(weights.values).subspan(k * targets, targets)
                                                : std::span<const double>();
    morphBoth(q.positions, q.position_targets, w, exact, written);
    for (std::size_t i = 0; i < exact.size(); ++i) {
      cost.position_error = std::max(cost.position_error, glm::length(written[i] - exact[i]));
    }
    morphBoth(q.normals, q.normal_targets, w, exact, written);
    for (std::size_t i = 0; i < exact.size(); ++i) angles.add(exact[i], written[i]);
  }
  cost.normal_p99_degrees = angles.p99();
  cost.normal_max_degrees = angles.largest();
  return cost;
}

// The index accessor of every primitive with triangles (-1 for one without), then the vertex
// attributes all primitives share, into `primitive`.
std::vector<int> writeMesh(ModelBuilder& b, const ExportMesh& mesh, tinygltf::Primitive& primitive, std::size_t joint_count,
                           Quantization& q) {
  const std::size_t count = mesh.positions.size();
  std::vector<int> index_accessors;
  std::uint32_t begin = 0;
  for (const std::uint32_t end : mesh.primitive_ends) {
    const auto first = mesh.triangles.begin() + 3 * static_cast<std::ptrdiff_t>(begin);
    const auto last = mesh.triangles.begin() + 3 * static_cast<std::ptrdiff_t>(end);
    begin = end;
    if (first == last) {
      index_accessors.push_back(-1);
    } else if (count < 65535) {
      std::vector<std::uint16_t> indices(first, last);
      index_accessors.push_back(b.accessor(b.view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, indices.size()));
    } else {
      std::vector<std::uint32_t> indices(first, last);
      index_accessors.push_back(b.accessor(b.view(indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                           TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size()));
    }
  }
  if (q.grid) {
    std::vector<Vec3> grid(count);
    for (std::size_t i = 0; i < count; ++i) grid[i] = q.grid->toGrid(mesh.positions[i]);
    bool sparse = false;
    q.positions = {allVertexIndices(count), mesh.positions, {}};
    primitive.attributes["POSITION"] = appendVec3Accessor(b.model, Vec3Encoding::kShort, count, q.positions.vertices,
                                                          grid, true, sparse, &q.positions.written);
    for (Vec3& p : q.positions.written) p = q.grid->origin + q.grid->step * p;
    q.normals = {allVertexIndices(count), mesh.normals, {}};
    primitive.attributes["NORMAL"] = appendVec3Accessor(b.model, Vec3Encoding::kByteNormalized, count, q.normals.vertices,
                                                        mesh.normals, false, sparse, &q.normals.written);
  } else {
    std::vector<float> xyz;
    for (const Vec3& p : mesh.positions) putVec3(xyz, p);
    primitive.attributes["POSITION"] = b.floats(xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    xyz.clear();
    for (const Vec3& n : mesh.normals) putVec3(xyz, n);
    primitive.attributes["NORMAL"] = b.floats(xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  if (!mesh.uvs.empty()) primitive.attributes["TEXCOORD_0"] = gltf::appendTexcoordAccessor(b.model, mesh.uvs);
  std::vector<float> weights;
  for (const auto& w : mesh.weights) weights.insert(weights.end(), w.begin(), w.end());
  primitive.attributes["WEIGHTS_0"] = b.floats(weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  if (joint_count <= 256) {
    std::vector<std::uint8_t> joints;
    for (const auto& j : mesh.joints) {
      for (std::uint32_t x : j) joints.push_back(static_cast<std::uint8_t>(x));
    }
    primitive.attributes["JOINTS_0"] = b.accessor(b.view(joints, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, count);
  } else {
    std::vector<std::uint16_t> joints;
    for (const auto& j : mesh.joints) {
      for (std::uint32_t x : j) joints.push_back(static_cast<std::uint16_t>(x));
    }
    primitive.attributes["JOINTS_0"] = b.accessor(b.view(joints, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, count);
  }
  return index_accessors;
}

// A target's POSITION deltas: its field (topology vertices) gathered to the output vertices.
Result<int> positionAccessor(ModelBuilder& b, const ExportMesh& mesh, const SparseField& field, double factor,
                             const std::string& name, std::vector<std::int32_t>& slot_of_vertex, bool& sparse,
                             Quantization& q) {
  for (std::size_t k = 0; k < field.vertices.size(); ++k) slot_of_vertex[field.vertices[k]] = static_cast<std::int32_t>(k);
  std::vector<std::uint32_t> indices;
  std::vector<Vec3> values;
  for (std::size_t i = 0; i < mesh.source_vertex.size(); ++i) {
    const std::int32_t slot = slot_of_vertex[mesh.source_vertex[i]];
    if (slot < 0) continue;
    indices.push_back(static_cast<std::uint32_t>(i));
    values.push_back(factor * field.values[static_cast<std::size_t>(slot)]);
  }
  for (std::uint32_t v : field.vertices) slot_of_vertex[v] = -1;
  if (!allFinite(values)) return invalidArgument("export: morph target " + name + " has a non-finite displacement");
  const std::size_t count = mesh.positions.size();
  if (!q.grid) {
    return appendVec3Accessor(b.model, Vec3Encoding::kFloat, count, std::move(indices), std::move(values), true, sparse);
  }
  const double step = q.grid->step;
  std::vector<Vec3> steps(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) steps[k] = values[k] / step;
  const Vec3Encoding encoding = fitsEncoding(Vec3Encoding::kShort, steps) ? Vec3Encoding::kShort : Vec3Encoding::kFloat;
  q.float_deltas += encoding == Vec3Encoding::kFloat ? 1 : 0;
  WrittenField& field_written = q.position_targets.emplace_back(WrittenField{indices, std::move(values), {}});
  const int accessor =
      appendVec3Accessor(b.model, encoding, count, std::move(indices), steps, true, sparse, &field_written.written);
  for (Vec3& d : field_written.written) d *= step;
  return accessor;
}

// A target's NORMAL deltas, already indexed by output vertex.
Result<int> normalAccessor(ModelBuilder& b, const ExportMesh& mesh, const SparseField& delta, double factor,
                           const std::string& name, Quantization& q) {
  std::vector<Vec3> values;
  for (const Vec3& d : delta.values) values.push_back(factor * d);
  if (!allFinite(values)) return invalidArgument("export: morph target " + name + " has a non-finite normal delta");
  bool sparse = false;
  const std::size_t count = mesh.positions.size();
  if (!q.grid) {
    return appendVec3Accessor(b.model, Vec3Encoding::kFloat, count, delta.vertices, std::move(values), false, sparse);
  }
  const Vec3Encoding encoding =
      fitsEncoding(Vec3Encoding::kShortNormalized, values) ? Vec3Encoding::kShortNormalized : Vec3Encoding::kFloat;
  q.float_deltas += encoding == Vec3Encoding::kFloat ? 1 : 0;
  WrittenField& written = q.normal_targets.emplace_back(WrittenField{delta.vertices, values, {}});
  return appendVec3Accessor(b.model, encoding, count, delta.vertices, std::move(values), false, sparse, &written.written);
}

int sampler(tinygltf::Animation& animation, int input, int output, KeyInterpolation interpolation) {
  tinygltf::AnimationSampler s;
  s.input = input;
  s.output = output;
  s.interpolation = std::string(gltfInterpolationName(interpolation));
  animation.samplers.push_back(s);
  return static_cast<int>(animation.samplers.size() - 1);
}

void channel(tinygltf::Animation& animation, int sampler_index, int node, const char* path) {
  tinygltf::AnimationChannel c;
  c.sampler = sampler_index;
  c.target_node = node;
  c.target_path = path;
  animation.channels.push_back(c);
}

Status writeWeightsAnimation(ModelBuilder& b, const GlbContents& in, tinygltf::Animation& animation) {
  const WeightKeys& w = *in.weights;
  const std::size_t targets = w.weightCount();
  if (targets == 0) return okStatus();
  const double per_second = 1.0 / in.asset->segment_seconds;
  ODESKIN_ASSIGN_OR_RETURN(const int input, timeAccessor(b, w.times, in.asset->segment_seconds, "weight"));
  const bool cubic = w.interpolation == KeyInterpolation::kCubicSpline;
  std::vector<float> output;
  output.reserve(w.times.size() * targets * (cubic ? 3 : 1));
  for (std::size_t k = 0; k < w.times.size(); ++k) {
    const std::size_t row = k * targets;
    if (cubic) {
      for (std::size_t j = 0; j < targets; ++j) output.push_back(static_cast<float>(w.in_tangents[row + j] * per_second));
    }
    for (std::size_t j = 0; j < targets; ++j) output.push_back(static_cast<float>(w.values[row + j]));
    if (cubic) {
      for (std::size_t j = 0; j < targets; ++j) output.push_back(static_cast<float>(w.out_tangents[row + j] * per_second));
    }
  }
  if (!allFinite(output)) return invalidArgument("export: a morph weight key is not finite");
  const int out = b.floats(output, TINYGLTF_TYPE_SCALAR, 1, 0, false);
  channel(animation, sampler(animation, input, out, w.interpolation), 0, "weights");
  return okStatus();
}

// `unit`: grid steps per mesh unit (1 unless quantized), for the joints' translations.
Status writeSkeletonAnimation(ModelBuilder& b, const GlbContents& in, int first_joint, double unit,
                              tinygltf::Animation& animation) {
  const SkeletonKeys& s = *in.skeleton;
  const std::size_t bones = in.asset->bone_count;
  const double per_second = 1.0 / in.asset->segment_seconds;
  ODESKIN_ASSIGN_OR_RETURN(const int input, timeAccessor(b, s.times, in.asset->segment_seconds, "skeleton"));
  const bool cubic = s.interpolation == KeyInterpolation::kCubicSpline;
  for (std::size_t bone = 0; bone < bones; ++bone) {
    std::vector<float> translation, rotation;
    for (std::size_t k = 0; k < s.times.size(); ++k) {
      const std::size_t at = k * bones + bone;
      if (!cubic) {
        putVec3(translation, unit * s.translations[at]);
        putQuat(rotation, s.rotations[at]);
        continue;
      }
      putVec3(translation, unit * s.translation_in[at] * per_second);
      putVec3(translation, unit * s.translations[at]);
      putVec3(translation, unit * s.translation_out[at] * per_second);
      putQuat(rotation, s.rotation_in[at] * per_second);
      putQuat(rotation, s.rotations[at]);
      putQuat(rotation, s.rotation_out[at] * per_second);
    }
    if (!allFinite(translation) || !allFinite(rotation)) {
      return invalidArgument("export: the animation of bone " + std::to_string(bone) + " is not finite");
    }
    const int node = first_joint + static_cast<int>(bone);
    const int translations = b.floats(translation, TINYGLTF_TYPE_VEC3, 3, 0, false);
    const int rotations = b.floats(rotation, TINYGLTF_TYPE_VEC4, 4, 0, false);
    channel(animation, sampler(animation, input, translations, s.interpolation), node, "translation");
    channel(animation, sampler(animation, input, rotations, s.interpolation), node, "rotation");
  }
  return okStatus();
}

std::string boneName(const DeformAsset& asset, std::size_t bone) {
  if (bone < asset.bone_names.size() && !asset.bone_names[bone].empty()) return asset.bone_names[bone];
  return "bone_" + std::to_string(bone);
}

}  // namespace

Result<GlbSummary> writeExportGlb(const std::filesystem::path& path, const GlbContents& contents) {
  const DeformAsset& asset = *contents.asset;
  const ExportMesh& mesh = *contents.mesh;
  const std::size_t bones = asset.bone_count;
  if (bones == 0 || bones > 65536) return invalidArgument("export: " + std::to_string(bones) + " bones (glTF skins take 1 to 65536 joints)");
  GlbSummary summary;
  ModelBuilder b;
  b.model.asset.version = "2.0";
  b.model.asset.generator = contents.generator;

  tinygltf::Primitive primitive;  // what every primitive shares: attributes and targets
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  Quantization quantization;
  if (contents.quantize) quantization.grid = positionGrid(mesh.positions);
  const std::vector<int> index_accessors = writeMesh(b, mesh, primitive, bones, quantization);
  tinygltf::Value::Array names;
  std::vector<std::int32_t> slot_of_vertex(asset.vertexCount(), -1);
  for (const SplitTarget& t : contents.weights->targets) {
    const ModeTarget& source = contents.targets->targets[t.source];
    const std::string name = source.name + (t.sign > 0 ? "+" : "-");
    bool sparse = false;
    ODESKIN_ASSIGN_OR_RETURN(const int position, positionAccessor(b, mesh, source.field, t.sign * t.scale, name,
                                                                  slot_of_vertex, sparse, quantization));
    std::map<std::string, int>& target = primitive.targets.emplace_back();
    target["POSITION"] = position;
    if (contents.normals != nullptr) {
      ODESKIN_ASSIGN_OR_RETURN(target["NORMAL"], normalAccessor(b, mesh, contents.normals->deltas[t.source],
                                                                t.sign * t.scale, name, quantization));
    }
    names.emplace_back(name);
    summary.sparse_targets += sparse ? 1 : 0;
  }
  summary.morph_targets = primitive.targets.size();
  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = "odeskin";
  std::vector<int> materials(index_accessors.size(), -1);
  if (contents.materials != nullptr) {
    ODESKIN_ASSIGN_OR_RETURN(materials, gltf::primitiveMaterials(*contents.materials, asset.render.primitives,
                                                                 index_accessors.size()));
  }
  for (std::size_t p = 0; p < index_accessors.size(); ++p) {
    if (index_accessors[p] < 0) continue;  // a primitive without triangles: glTF has no empty one
    tinygltf::Primitive& written = gltf_mesh.primitives.emplace_back(primitive);
    written.indices = index_accessors[p];
    written.material = materials[p];
  }
  if (!names.empty()) {
    gltf_mesh.weights.assign(names.size(), 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(names);
    gltf_mesh.extras = tinygltf::Value(extras);
  }
  b.model.meshes.push_back(gltf_mesh);

  // Nodes: 0 the skinned mesh (scene root, identity), 1 the skeleton root, 2 + b the joints.
  constexpr int kFirstJoint = 2;
  tinygltf::Node mesh_node;
  mesh_node.name = "odeskin";
  mesh_node.mesh = 0;
  mesh_node.skin = 0;
  b.model.nodes.push_back(mesh_node);
  // Quantized, the skeleton root scales grid steps to mesh units, and everything below it is in
  // grid steps: Blender 3.4's importer drops a scale in the inverse bind matrices (where gltfpack
  // puts it), but keeps a node's. Then S_b = scale(step) G'_b IBM'_b with G'_b = G_b in grid steps
  // and IBM'_b = translate((origin - pivot_b) / step), which maps q to G_b (origin + step q - pivot_b).
  tinygltf::Node skeleton_root;
  skeleton_root.name = "skeleton";
  const double unit = quantization.grid ? 1.0 / quantization.grid->step : 1.0;
  const Vec3 origin = quantization.grid ? quantization.grid->origin : Vec3(0.0);
  if (quantization.grid) skeleton_root.scale.assign(3, quantization.grid->step);
  b.model.nodes.push_back(skeleton_root);
  const SkeletonKeys& keys = *contents.skeleton;
  std::vector<float> inverse_binds;
  for (std::size_t bone = 0; bone < bones; ++bone) {
    tinygltf::Node node;
    node.name = boneName(asset, bone);
    const Vec3& t = keys.translations[bone];  // the pose at t = 0, for viewers that show no animation
    const glm::dquat& q = keys.rotations[bone];
    node.translation = {unit * t.x, unit * t.y, unit * t.z};
    node.rotation = {q.x, q.y, q.z, q.w};
    b.model.nodes.push_back(node);
    // J_b^-1 = translation by -pivot (by (origin - pivot) / step when quantized), column-major.
    const Vec3& pivot = asset.bone_pivots[bone];
    const Vec3 p = quantization.grid ? unit * (origin - pivot) : -pivot;
    inverse_binds.insert(inverse_binds.end(), {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, static_cast<float>(p.x),
                                               static_cast<float>(p.y), static_cast<float>(p.z), 1});
  }
  for (std::size_t bone = 0; bone < bones; ++bone) {  // parents may come after their children
    const std::int32_t parent = keys.parents[bone];
    const std::size_t parent_node = parent < 0 ? 1 : static_cast<std::size_t>(kFirstJoint + parent);
    b.model.nodes[parent_node].children.push_back(kFirstJoint + static_cast<int>(bone));
  }
  if (!allFinite(inverse_binds)) return invalidArgument("export: a bone pivot is not finite");
  tinygltf::Skin skin;
  skin.name = "odeskin";
  skin.skeleton = 1;
  for (std::size_t bone = 0; bone < bones; ++bone) skin.joints.push_back(kFirstJoint + static_cast<int>(bone));
  skin.inverseBindMatrices = b.floats(inverse_binds, TINYGLTF_TYPE_MAT4, 16, 0, false);
  b.model.skins.push_back(skin);

  tinygltf::Animation animation;
  animation.name = "odeskin";
  ODESKIN_TRY(writeWeightsAnimation(b, contents, animation));
  ODESKIN_TRY(writeSkeletonAnimation(b, contents, kFirstJoint, unit, animation));
  b.model.animations.push_back(animation);

  tinygltf::Scene scene;
  scene.name = "odeskin";
  scene.nodes = {0, 1};
  b.model.scenes.push_back(scene);
  b.model.defaultScene = 0;
  if (quantization.grid) {
    b.model.extensionsUsed.push_back("KHR_mesh_quantization");
    b.model.extensionsRequired.push_back("KHR_mesh_quantization");
    summary.quantization = measureQuantization(quantization, *contents.weights);
  }
  if (contents.materials != nullptr) gltf::addMaterialLibrary(b.model, *contents.materials);
  std::vector<unsigned char>& data = b.model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  if (data.size() >= kMaxBufferBytes) {
    return invalidArgument("export: " + std::to_string(data.size()) + " bytes of buffer data; most glTF tools fail at 2 GiB; export fewer segments");
  }
  summary.buffer_bytes = data.size();
  ODESKIN_TRY(writeGlbAtomically(path, b.model));
  return summary;
}

}  // namespace odeskin

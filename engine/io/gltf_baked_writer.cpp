// SPDX-License-Identifier: MIT
#include "gltf_baked_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include <tiny_gltf.h>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/render_primitives.hpp"
#include "gltf_buffer_builder.hpp"
#include "gltf_quantized.hpp"
#include "obj_io.hpp"

namespace odeskin {
namespace {

Status checkInput(const FaceList& faces, const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds,
                  const BakedVertexData& data) {
  const std::span<const std::vector<Vec3>> normals = data.normals;
  const std::span<const Vec2> uvs = data.uvs;
  if (frames.empty()) return invalidArgument("baked glTF: no frames");
  if (seconds.size() != frames.size()) return invalidArgument("baked glTF: one time per frame is needed");
  if (!normals.empty() && normals.size() != frames.size()) return invalidArgument("baked glTF: normals for some frames only");
  for (std::size_t f = 0; f < normals.size(); ++f) {
    if (normals[f].size() != frames[f].size()) {
      return invalidArgument("baked glTF: frame " + std::to_string(f) + " has another normal count");
    }
    for (const Vec3& n : normals[f]) {
      if (!isFinite(n)) {
        return invalidArgument("baked glTF: frame " + std::to_string(f) + " has a non-finite normal");
      }
    }
  }
  const std::size_t v_count = frames[0].size();
  if (!uvs.empty() && uvs.size() != v_count) {
    return invalidArgument("baked glTF: " + std::to_string(uvs.size()) + " texture coordinates for " + std::to_string(v_count) +
                           " vertices");
  }
  for (std::size_t i = 0; i < uvs.size(); ++i) {
    if (!isFinite(uvs[i])) {
      return invalidArgument("baked glTF: texture coordinate " + std::to_string(i) + " is not finite");
    }
  }
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != v_count) return invalidArgument("baked glTF: frame " + std::to_string(f) + " has another vertex count");
    for (const Vec3& p : frames[f]) {
      if (!isFinite(p)) {
        return invalidArgument("baked glTF: frame " + std::to_string(f) + " has a non-finite position");
      }
    }
    ODESKIN_TRY(gltf::checkFloat32Positions(frames[f], "baked glTF: frame " + std::to_string(f)));
    if (!std::isfinite(seconds[f]) || seconds[f] < 0.0 || (f > 0 && !(seconds[f] > seconds[f - 1]))) {
      return invalidArgument("baked glTF: frame times must be non-negative and increasing");
    }
  }
  for (std::uint32_t index : faces.indices) {
    if (index >= v_count) return invalidArgument("baked glTF: a face uses vertex " + std::to_string(index));
  }
  if (const std::string problem = primitiveRunProblem(data.primitives, faces.faceCount()); !problem.empty()) {
    return invalidArgument("baked glTF: " + problem);
  }
  return okStatus();
}

// Every vertex of frame `f` (frame 0 as it is, later frames less frame 0), in grid steps when
// `step` is not 1.
std::vector<Vec3> frameValues(std::span<const std::vector<Vec3>> values, std::size_t f, double step) {
  std::vector<Vec3> out(values[f].size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (f == 0 ? values[0][i] : values[f][i] - values[0][i]) / step;
  return out;
}

// The quantized frames: frame 0 on the grid (normals 8-bit), one target per later frame (deltas in
// grid steps, normal deltas 16-bit), and what the rounding cost at each frame into `cost`.
void writeQuantizedFrames(tinygltf::Model& m, const PositionGrid& grid, const std::vector<std::vector<Vec3>>& frames,
                          std::span<const std::vector<Vec3>> normals, tinygltf::Primitive& primitive,
                          QuantizationCost* cost) {
  const std::size_t count = frames[0].size();
  const std::vector<std::uint32_t> all = allVertexIndices(count);
  std::vector<Vec3> base, base_normals, written;
  bool sparse = false;
  std::vector<Vec3> grid_frame = frameValues(frames, 0, grid.step);
  for (Vec3& p : grid_frame) p -= grid.origin / grid.step;
  primitive.attributes["POSITION"] =
      appendVec3Accessor(m, Vec3Encoding::kShort, count, all, grid_frame, true, sparse, &base);
  for (Vec3& p : base) p = grid.origin + grid.step * p;
  if (!normals.empty()) {
    primitive.attributes["NORMAL"] =
        appendVec3Accessor(m, Vec3Encoding::kByteNormalized, count, all, normals[0], false, sparse, &base_normals);
  }
  QuantizationCost measured;
  measured.step = grid.step;
  NormalAngles angles;
  for (std::size_t i = 0; i < count; ++i) {
    measured.position_error = std::max(measured.position_error, glm::length(base[i] - frames[0][i]));
    if (!normals.empty()) angles.add(normals[0][i], base_normals[i]);
  }
  for (std::size_t f = 1; f < frames.size(); ++f) {
    std::map<std::string, int>& target = primitive.targets.emplace_back();
    const std::vector<Vec3> steps = frameValues(frames, f, grid.step);
    const bool fits = fitsEncoding(Vec3Encoding::kShort, steps);
    measured.float_deltas += fits ? 0 : 1;
    target["POSITION"] = appendVec3Accessor(m, fits ? Vec3Encoding::kShort : Vec3Encoding::kFloat, count, all, steps,
                                            true, sparse, &written);
    for (std::size_t i = 0; i < count; ++i) {
      const double error = glm::length(base[i] + grid.step * written[i] - frames[f][i]);
      measured.position_error = std::max(measured.position_error, error);
    }
    if (normals.empty()) continue;
    const std::vector<Vec3> deltas = frameValues(normals, f, 1.0);
    const Vec3Encoding encoding =
        fitsEncoding(Vec3Encoding::kShortNormalized, deltas) ? Vec3Encoding::kShortNormalized : Vec3Encoding::kFloat;
    measured.float_deltas += encoding == Vec3Encoding::kFloat ? 1 : 0;
    target["NORMAL"] = appendVec3Accessor(m, encoding, count, all, deltas, false, sparse, &written);
    for (std::size_t i = 0; i < count; ++i) angles.add(normals[f][i], base_normals[i] + written[i]);
  }
  measured.normal_p99_degrees = angles.p99();
  measured.normal_max_degrees = angles.largest();
  if (cost != nullptr) *cost = measured;
}

}  // namespace

Status writeBakedGlb(const std::filesystem::path& path, const FaceList& faces,
                     const std::vector<std::vector<Vec3>>& frames, std::span<const double> seconds,
                     const BakedGlbOptions& options, const BakedVertexData& data, QuantizationCost* quantization) {
  if (Status s = checkInput(faces, frames, seconds, data); !s.ok()) return Status(s.code(), path.string() + ": " + s.message());
  const std::span<const std::vector<Vec3>> normals = data.normals;
  tinygltf::Model m = gltf::newModel(options.generator);

  ODESKIN_ASSIGN_OR_RETURN(const std::vector<gltf::PrimitiveIndices> written,
                           gltf::appendPrimitiveIndices(m, faces, data.primitives, options.materials));
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  std::vector<float> xyz;
  // Frame 0 as it is, every later frame as its difference from frame 0 (a morph target's delta).
  auto flatten = [&](std::span<const std::vector<Vec3>> values, std::size_t frame, bool bounds) {
    xyz.clear();
    for (std::size_t i = 0; i < values[frame].size(); ++i) {
      const Vec3 d = frame == 0 ? values[0][i] : values[frame][i] - values[0][i];
      xyz.insert(xyz.end(), {static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z)});
    }
    return gltf::appendFloatAccessor(m, xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, bounds);
  };
  std::optional<PositionGrid> grid;
  if (options.quantize) {
    grid = positionGrid(frames[0]);
    writeQuantizedFrames(m, *grid, frames, normals, primitive, quantization);
  } else {
    primitive.attributes["POSITION"] = flatten(frames, 0, true);
    if (!normals.empty()) primitive.attributes["NORMAL"] = flatten(normals, 0, false);
  }
  if (!data.uvs.empty()) primitive.attributes["TEXCOORD_0"] = gltf::appendTexcoordAccessor(m, data.uvs);
  for (std::size_t f = 1; f < frames.size() && !options.quantize; ++f) {
    std::map<std::string, int> target{{"POSITION", flatten(frames, f, true)}};
    if (!normals.empty()) target["NORMAL"] = flatten(normals, f, false);
    primitive.targets.push_back(target);
  }
  tinygltf::Mesh mesh;
  mesh.name = "odeskin";
  gltf::addSharedPrimitives(mesh, primitive, written);
  mesh.weights.assign(frames.size() - 1, 0.0);
  m.meshes.push_back(mesh);
  gltf::addSingleMeshScene(m, "odeskin");
  if (grid) {  // the mesh node undoes the grid: an unskinned mesh's node transform applies
    m.nodes[0].translation = {grid->origin.x, grid->origin.y, grid->origin.z};
    m.nodes[0].scale.assign(3, grid->step);
    m.extensionsUsed.push_back("KHR_mesh_quantization");
    m.extensionsRequired.push_back("KHR_mesh_quantization");
  }

  if (frames.size() > 1) {
    // Key f weights target f-1 by 1 (frame 0: none); STEP holds it, LINEAR fades into the next.
    const std::size_t targets = frames.size() - 1;
    std::vector<float> times(seconds.begin(), seconds.end());
    std::vector<float> weights(frames.size() * targets, 0.0f);
    for (std::size_t f = 1; f < frames.size(); ++f) weights[f * targets + (f - 1)] = 1.0f;
    tinygltf::AnimationSampler sampler;
    sampler.input = gltf::appendFloatAccessor(m, times, TINYGLTF_TYPE_SCALAR, 1, 0, true);
    sampler.output = gltf::appendFloatAccessor(m, weights, TINYGLTF_TYPE_SCALAR, 1, 0, false);
    sampler.interpolation = options.linear ? "LINEAR" : "STEP";
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    tinygltf::Animation animation;
    animation.name = options.animation;
    animation.samplers.push_back(sampler);
    animation.channels.push_back(channel);
    m.animations.push_back(animation);
  }
  if (options.materials != nullptr) gltf::addMaterialLibrary(m, *options.materials);
  m.buffers[0].data.resize((m.buffers[0].data.size() + 3) / 4 * 4, 0);

  return writeGlbAtomically(path, m);
}

Status checkBakedSize(std::size_t frames, std::size_t vertices) {
  const double bytes = static_cast<double>(frames) * static_cast<double>(vertices) * 24.0;
  if (bytes < 2147483648.0) return okStatus();
  return invalidArgument("baking " + std::to_string(frames) + " frames of " + std::to_string(vertices) +
                         " vertices needs 2 GiB or more");
}

Status checkBakedSize(double frames, std::size_t vertices) {
  // Below 2^53 the count is exact in double and prints as the integer the other overload prints.
  if (frames < 9007199254740992.0) return checkBakedSize(static_cast<std::size_t>(std::max(frames, 0.0)), vertices);
  const std::string count = std::isfinite(frames) ? numberText(frames) : "more than " + numberText(std::numeric_limits<double>::max());
  return invalidArgument("baking " + count + " frames of " + std::to_string(vertices) + " vertices needs 2 GiB or more");
}

Status writeGlbAtomically(const std::filesystem::path& path, const tinygltf::Model& model) {
  // Serialised in memory, then written by the one temp-file-and-rename path: tinygltf's own file
  // writer does not report a failed write (a full disk), so it could leave half a .glb.
  std::ostringstream glb(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, glb, false, true) || !glb) {
    return ioError(path.string() + ": cannot serialise the glTF model");
  }
  return writeFileAtomically(path, std::move(glb).str());
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "gltf_mesh.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <string>

#include "gltf_accessor.hpp"

namespace odeskin::gltf {
namespace {

constexpr std::array kFloatOnly{kFloat};
// KHR_mesh_quantization: POSITION in every 8-bit and 16-bit variant, deltas in the signed ones.
constexpr std::array kQuantizedPositions{kFloat, kByte, kByteNorm, kUByte, kUByteNorm,
                                         kShort, kShortNorm, kUShort, kUShortNorm};
constexpr std::array kQuantizedDeltas{kFloat, kByte, kByteNorm, kShort, kShortNorm};
constexpr std::array kQuantizedNormals{kFloat, kByteNorm, kShortNorm};
// TEXCOORD_0 as the core specification stores it, and KHR_mesh_quantization's normalized signed
// forms. Its unnormalized integers need the material's KHR_texture_transform to mean anything.
constexpr std::array kTexcoords{kFloat, kUByteNorm, kUShortNorm};
constexpr std::array kQuantizedTexcoords{kFloat, kUByteNorm, kUShortNorm, kByteNorm, kShortNorm};

constexpr std::array kIndexFormats{kUByte, kUShort, kUInt};
constexpr std::array kJointFormats{kUByte, kUShort};
constexpr std::array kWeightFormats{kFloat, kUByteNorm, kUShortNorm};

// Why the mesh's TEXCOORD_0 cannot be kept, or empty when every primitive has it in one of `formats`.
std::string texcoordProblem(const tinygltf::Model& model, const tinygltf::Mesh& mesh,
                            std::span<const AccessorFormat> formats) {
  bool any = false, all = true;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const auto uv = mesh.primitives[p].attributes.find("TEXCOORD_0");
    if (uv == mesh.primitives[p].attributes.end()) {
      all = false;
      continue;
    }
    any = true;
    if (uv->second < 0 || static_cast<std::size_t>(uv->second) >= model.accessors.size()) continue;  // readAccessor names it
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(uv->second)];
    const bool known = std::any_of(formats.begin(), formats.end(), [&](const AccessorFormat& f) {
      return f.component_type == a.componentType && f.normalized == a.normalized;
    });
    if (!known) {
      return "primitive " + std::to_string(p) + " stores TEXCOORD_0 as unnormalized integers, whose meaning is in a texture "
             "transform odeskin does not carry";
    }
  }
  if (any && !all) return "some primitives have no TEXCOORD_0";
  return {};
}

bool has(const std::map<std::string, int>& attributes, const std::string& name) {
  return attributes.find(name) != attributes.end();
}

// Appends one primitive's triangles, offset by `first` render vertices.
Status readTriangles(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                     std::size_t vertex_count, std::uint32_t first, std::vector<std::uint32_t>& triangles,
                     DecodeBudget& budget) {
  if (prim.indices < 0) {
    if (vertex_count % 3 != 0) {
      return parseError(where + ": " + std::to_string(vertex_count) + " unindexed vertices are not whole triangles");
    }
    ODESKIN_TRY(budget.charge(vertex_count, where + " unindexed triangles"));
    for (std::size_t i = 0; i < vertex_count; ++i) triangles.push_back(first + static_cast<std::uint32_t>(i));
    return okStatus();
  }
  ODESKIN_ASSIGN_OR_RETURN(AccessorData indices,
                           readAccessor(model, prim.indices, {where + " indices", TINYGLTF_TYPE_SCALAR, kIndexFormats}, budget));
  if (indices.count % 3 != 0) {
    return parseError(where + ": " + std::to_string(indices.count) + " indices are not whole triangles");
  }
  for (std::size_t k = 0; k < indices.count; ++k) {
    const double i = indices.values[k];
    if (i >= static_cast<double>(vertex_count)) {
      return parseError(where + ": index " + std::to_string(static_cast<std::uint64_t>(i)) + " (entry " +
                        std::to_string(k) + ") >= vertex count " + std::to_string(vertex_count));
    }
    triangles.push_back(first + static_cast<std::uint32_t>(i));
  }
  return okStatus();
}

std::size_t influenceSets(const tinygltf::Primitive& prim, const std::string& where, Status& status) {
  std::size_t n = 0;
  while (has(prim.attributes, "JOINTS_" + std::to_string(n)) || has(prim.attributes, "WEIGHTS_" + std::to_string(n))) {
    if (!has(prim.attributes, "JOINTS_" + std::to_string(n)) || !has(prim.attributes, "WEIGHTS_" + std::to_string(n))) {
      status = parseError(where + ": JOINTS_" + std::to_string(n) + " and WEIGHTS_" + std::to_string(n) +
                          " must come together");
    }
    ++n;
  }
  return n;
}

// Appends JOINTS_s / WEIGHTS_s, s < sets, of one primitive's `n` vertices.
Status readInfluences(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                      std::size_t n, std::size_t sets, MeshData& out, DecodeBudget& budget) {
  std::vector<AccessorData> joints(sets);
  std::vector<AccessorData> weights(sets);
  for (std::size_t s = 0; s < sets; ++s) {
    const std::string j = "JOINTS_" + std::to_string(s);
    const std::string w = "WEIGHTS_" + std::to_string(s);
    ODESKIN_ASSIGN_OR_RETURN(joints[s], readAccessor(model, prim.attributes.at(j),
                                                     {where + " " + j, TINYGLTF_TYPE_VEC4, kJointFormats, n}, budget));
    ODESKIN_ASSIGN_OR_RETURN(weights[s], readAccessor(model, prim.attributes.at(w),
                                                      {where + " " + w, TINYGLTF_TYPE_VEC4, kWeightFormats, n}, budget));
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t s = 0; s < sets; ++s) {
      for (std::size_t c = 0; c < 4; ++c) {
        out.joints.push_back(static_cast<std::uint32_t>(joints[s].at(i, c)));
        out.weights.push_back(weights[s].at(i, c));
      }
    }
  }
  return okStatus();
}

// Appends every morph target's POSITION deltas of one primitive's `n` vertices.
Status readTargets(const tinygltf::Model& model, const tinygltf::Primitive& prim, const std::string& where,
                   std::size_t n, bool quantized, MeshData& out, DecodeBudget& budget) {
  const std::span<const AccessorFormat> delta_formats =
      quantized ? std::span<const AccessorFormat>(kQuantizedDeltas) : std::span<const AccessorFormat>(kFloatOnly);
  for (std::size_t t = 0; t < out.target_deltas.size(); ++t) {
    std::vector<Vec3>& deltas = out.target_deltas[t];
    const auto position = prim.targets[t].find("POSITION");
    if (position == prim.targets[t].end()) {
      ODESKIN_TRY(budget.charge(3 * n, where + " target " + std::to_string(t) + " (zeros: no POSITION)"));
      deltas.resize(deltas.size() + n, Vec3(0.0));
      continue;
    }
    ODESKIN_ASSIGN_OR_RETURN(AccessorData d, readAccessor(model, position->second,
                                                          {where + " target " + std::to_string(t) + " POSITION",
                                                           TINYGLTF_TYPE_VEC3, delta_formats, n},
                                                          budget));
    for (std::size_t i = 0; i < n; ++i) deltas.emplace_back(d.at(i, 0), d.at(i, 1), d.at(i, 2));
  }
  return okStatus();
}

}  // namespace

Result<MeshData> readMesh(const tinygltf::Model& model, int mesh_index, bool quantized, DecodeBudget& budget) {
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(mesh_index)];
  const std::string mesh_name = "mesh " + std::to_string(mesh_index);
  if (mesh.primitives.empty()) return parseError(mesh_name + " has no primitives");
  MeshData out;
  // NORMAL only tells hard edges from UV seams (RenderLayout::normals): kept when every primitive
  // has it, since a primitive without it has no normals to compare.
  bool normals = true;
  for (const tinygltf::Primitive& prim : mesh.primitives) normals = normals && has(prim.attributes, "NORMAL");
  const std::span<const AccessorFormat> uv_formats =
      quantized ? std::span<const AccessorFormat>(kQuantizedTexcoords) : std::span<const AccessorFormat>(kTexcoords);
  out.uv_warning = texcoordProblem(model, mesh, uv_formats);
  const bool uvs = out.uv_warning.empty() && has(mesh.primitives.front().attributes, "TEXCOORD_0");
  const std::size_t target_count = mesh.primitives.front().targets.size();
  out.target_deltas.resize(target_count);
  // Each primitive's first render vertex and count. Primitives over the same vertex accessors (the
  // usual split of one mesh by material) share their render vertices: read once, not copied.
  std::vector<std::pair<std::uint32_t, std::size_t>> ranges;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where = mesh_name + " primitive " + std::to_string(p);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
      return parseError(where + " has mode " + std::to_string(prim.mode) + "; only TRIANGLES (4) is read");
    }
    if (prim.material < -1 || prim.material >= static_cast<int>(model.materials.size())) {
      return parseError(where + " uses material " + std::to_string(prim.material) + " of " +
                        std::to_string(model.materials.size()));
    }
    const auto shared = std::find_if(mesh.primitives.begin(), mesh.primitives.begin() + static_cast<std::ptrdiff_t>(p),
                                     [&](const tinygltf::Primitive& q) {
                                       return q.attributes == prim.attributes && q.targets == prim.targets;
                                     });
    if (shared != mesh.primitives.begin() + static_cast<std::ptrdiff_t>(p)) {
      const auto [first, n] = ranges[static_cast<std::size_t>(shared - mesh.primitives.begin())];
      ranges.emplace_back(first, n);
      ODESKIN_TRY(readTriangles(model, prim, where, n, first, out.triangles, budget));
      out.primitives.push_back({static_cast<std::uint32_t>(out.triangles.size() / 3), prim.material});
      continue;
    }
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) return parseError(where + " has no POSITION");
    const std::span<const AccessorFormat> position_formats =
        quantized ? std::span<const AccessorFormat>(kQuantizedPositions) : std::span<const AccessorFormat>(kFloatOnly);
    ODESKIN_ASSIGN_OR_RETURN(AccessorData positions, readAccessor(model, position->second,
                                                                  {where + " POSITION", TINYGLTF_TYPE_VEC3, position_formats},
                                                                  budget));
    const std::size_t n = positions.count;
    if (out.positions.size() + n > std::numeric_limits<std::uint32_t>::max()) {
      return parseError(mesh_name + " has more than 2^32 - 1 vertices");
    }
    const auto first = static_cast<std::uint32_t>(out.positions.size());
    ranges.emplace_back(first, n);
    for (std::size_t i = 0; i < n; ++i) out.positions.emplace_back(positions.at(i, 0), positions.at(i, 1), positions.at(i, 2));
    ODESKIN_TRY(readTriangles(model, prim, where, n, first, out.triangles, budget));
    out.primitives.push_back({static_cast<std::uint32_t>(out.triangles.size() / 3), prim.material});
    if (normals) {
      const std::span<const AccessorFormat> normal_formats =
          quantized ? std::span<const AccessorFormat>(kQuantizedNormals) : std::span<const AccessorFormat>(kFloatOnly);
      ODESKIN_ASSIGN_OR_RETURN(AccessorData read, readAccessor(model, prim.attributes.at("NORMAL"),
                                                               {where + " NORMAL", TINYGLTF_TYPE_VEC3, normal_formats},
                                                               budget));
      if (read.count != n) {
        return parseError(where + ": NORMAL has " + std::to_string(read.count) + " entries, POSITION " + std::to_string(n));
      }
      for (std::size_t i = 0; i < n; ++i) out.normals.emplace_back(read.at(i, 0), read.at(i, 1), read.at(i, 2));
    }
    if (uvs) {
      ODESKIN_ASSIGN_OR_RETURN(AccessorData read, readAccessor(model, prim.attributes.at("TEXCOORD_0"),
                                                               {where + " TEXCOORD_0", TINYGLTF_TYPE_VEC2, uv_formats, n},
                                                               budget));
      for (std::size_t i = 0; i < n; ++i) out.uvs.emplace_back(read.at(i, 0), read.at(i, 1));
    }

    Status status;
    const std::size_t sets = influenceSets(prim, where, status);
    ODESKIN_TRY(status);
    if (p == 0) out.influence_sets = sets;
    if (sets != out.influence_sets) {
      return parseError(where + " has " + std::to_string(sets) + " JOINTS_n/WEIGHTS_n sets, primitive 0 has " +
                        std::to_string(out.influence_sets));
    }
    ODESKIN_TRY(readInfluences(model, prim, where, n, sets, out, budget));
    if (prim.targets.size() != target_count) {
      return parseError(where + " has " + std::to_string(prim.targets.size()) + " morph targets, primitive 0 has " +
                        std::to_string(target_count));
    }
    ODESKIN_TRY(readTargets(model, prim, where, n, quantized, out, budget));
  }
  return out;
}

}  // namespace odeskin::gltf

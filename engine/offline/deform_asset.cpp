// SPDX-License-Identifier: MIT
#include "deform_asset.hpp"

#include <cmath>
#include <span>
#include <string>

#include <glm/geometric.hpp>

#include "../core/float32_range.hpp"
#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/render_layout_check.hpp"
#include "../core/smoothing_groups.hpp"
#include "../kernels/fourier_deform_job.hpp"

namespace odeskin {
namespace {

Status fieldSize(const std::string& field, std::size_t got, std::size_t expected) {
  if (got == expected) return okStatus();
  return invalidArgument("deform asset: " + field + " has " + std::to_string(got) + " entries, expected " +
                         std::to_string(expected));
}

// The packed layout is float32: a value beyond its range would deform to infinities on the fast
// CPU path and the GPU.
Status checkFloat32(std::span<const Vec3> values, const std::string& field) {
  const std::size_t i = firstBeyondFloat32(values);
  if (i == values.size()) return okStatus();
  return invalidArgument("deform asset: " + field + " " + std::to_string(i) +
                         " is outside float32's range (|coordinate| up to 1e+38): the packed layout cannot hold it");
}

Status checkFloat32(const DeformAsset& a) {
  ODESKIN_TRY(checkFloat32(a.rest_positions, "rest position"));
  for (std::size_t s = 0; s < a.segments.size(); ++s) {
    const DeformSegment& seg = a.segments[s];
    const std::string in = "segment " + std::to_string(s) + " ";
    ODESKIN_TRY(checkFloat32(seg.base_residuals, in + "base residual"));
    ODESKIN_TRY(checkFloat32(seg.remainders, in + "remainder"));
    ODESKIN_TRY(checkFloat32(seg.coefficients, in + "coefficient"));
    ODESKIN_TRY(checkFloat32(seg.rates, in + "rate"));
  }
  return okStatus();
}

}  // namespace

std::vector<Vec3> outputPositions(const DeformAsset& asset, std::span<const Vec3> topology_positions) {
  if (asset.render.empty()) return {topology_positions.begin(), topology_positions.end()};
  std::vector<Vec3> out;
  out.reserve(asset.render.topology_of_render.size());
  for (std::uint32_t t : asset.render.topology_of_render) out.push_back(topology_positions[t]);
  return out;
}

const FaceList& outputFaces(const DeformAsset& asset) { return asset.render.empty() ? asset.faces : asset.render.faces; }

std::size_t outputVertexCount(const DeformAsset& asset) {
  return asset.render.empty() ? asset.vertexCount() : asset.render.topology_of_render.size();
}

std::vector<Vec3> objPositions(const DeformAsset& asset, std::span<const Vec3> topology_positions) {
  if (asset.render.obj_order) return {topology_positions.begin(), topology_positions.end()};
  return outputPositions(asset, topology_positions);
}

std::size_t objVertexCount(const DeformAsset& asset) {
  return asset.render.obj_order ? asset.vertexCount() : outputVertexCount(asset);
}

std::vector<Vec3> outputNormals(const DeformAsset& asset, std::span<const Vec3> topology_positions) {
  // Twice each polygon's vector area (its fan's cross products), added to each of its corners.
  auto faceNormal = [&](const FaceList& faces, std::size_t f, auto position) {
    const std::uint32_t begin = faces.face_offsets[f];
    Vec3 normal(0.0);
    for (std::uint32_t k = begin + 1; k + 1 < faces.face_offsets[f + 1]; ++k) {
      const Vec3& a = position(faces.indices[begin]);
      normal += glm::cross(position(faces.indices[k]) - a, position(faces.indices[k + 1]) - a);
    }
    return normal;
  };
  const auto topology_position = [&](std::uint32_t i) -> const Vec3& { return topology_positions[i]; };
  std::vector<Vec3> topology_normals(asset.vertexCount(), Vec3(0.0));
  for (std::size_t f = 0; f < asset.faces.faceCount(); ++f) {
    const Vec3 normal = faceNormal(asset.faces, f, topology_position);
    for (std::uint32_t k = asset.faces.face_offsets[f]; k < asset.faces.face_offsets[f + 1]; ++k) {
      topology_normals[asset.faces.indices[k]] += normal;
    }
  }
  const std::span<const std::uint32_t> topology = asset.render.topology_of_render;
  SmoothingGroups groups;
  std::vector<Vec3> group_normals;
  if (!asset.render.normals.empty()) {
    groups = smoothingGroups(topology, asset.vertexCount(), asset.render.normals);
    group_normals.assign(groups.group_count, Vec3(0.0));
    const FaceList& faces = asset.render.faces;
    const auto render_position = [&](std::uint32_t r) -> const Vec3& { return topology_positions[topology[r]]; };
    for (std::size_t f = 0; f < faces.faceCount() && groups.hard_vertices > 0; ++f) {
      const Vec3 normal = faceNormal(faces, f, render_position);
      for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
        const std::uint32_t r = faces.indices[k];
        if (groups.hard[topology[r]]) group_normals[groups.group_of_render[r]] += normal;
      }
    }
  }
  const std::size_t count = outputVertexCount(asset);
  std::vector<Vec3> out(count);
  for (std::size_t o = 0; o < count; ++o) {
    const std::uint32_t i = asset.render.empty() ? static_cast<std::uint32_t>(o) : topology[o];
    const Vec3& sum = groups.hard_vertices > 0 && groups.hard[i] ? group_normals[groups.group_of_render[o]] : topology_normals[i];
    const double length = glm::length(sum);
    out[o] = length > 0.0 ? sum / length : Vec3(0.0, 0.0, 1.0);
  }
  return out;
}

Status validateDeformAsset(const DeformAsset& a) {
  if (a.modes < 1 || a.modes > 64) return outOfRange("deform asset: modes N = " + std::to_string(a.modes));
  const std::size_t v_count = a.vertexCount();
  const std::size_t c_count = a.curveCount();
  const std::size_t m_count = coefficientsPerCurve(a.modes);
  ODESKIN_TRY(fieldSize("bindings", a.bindings.size(), v_count));
  ODESKIN_TRY(fieldSize("bone_pivots", a.bone_pivots.size(), a.bone_count));
  if (a.materials.empty()) return invalidArgument("deform asset: no material");
  if (a.key_poses.size() < 2) return invalidArgument("deform asset: needs at least 2 key poses");
  ODESKIN_TRY(fieldSize("segments", a.segments.size(), a.key_poses.size() - 1));
  for (std::size_t k = 0; k < a.key_poses.size(); ++k) {
    ODESKIN_TRY(fieldSize("key pose " + std::to_string(k), a.key_poses[k].size(), a.bone_count));
    for (std::size_t b = 0; b < a.bone_count; ++b) {
      if (!isUnitRigid(a.key_poses[k][b])) {
        return invalidArgument("deform asset: key pose " + std::to_string(k) + " moves bone " + std::to_string(b) +
                               " by a non-finite transform or a rotation that is not unit");
      }
      // The float32 paths (the runtime, the GPU, glTF) carry the translation: 1e300 was inf there.
      const Vec3 translation = a.key_poses[k][b].translation;
      if (firstBeyondFloat32(std::span<const Vec3>(&translation, 1)) == 0) {
        return invalidArgument("deform asset: key pose " + std::to_string(k) + " moves bone " + std::to_string(b) +
                               " by a translation beyond float32's range");
      }
    }
  }
  if (const std::size_t b = firstBeyondFloat32(a.bone_pivots); b < a.bone_pivots.size()) {
    return invalidArgument("deform asset: the pivot of bone " + std::to_string(b) +
                           " is not finite or beyond float32's range");
  }
  for (std::size_t c = 0; c < c_count; ++c) {
    if (a.curve_materials[c] >= a.materials.size()) {
      return invalidArgument("deform asset: curve " + std::to_string(c) + " uses material " +
                             std::to_string(a.curve_materials[c]) + " of " + std::to_string(a.materials.size()));
    }
  }
  for (std::size_t i = 0; i < v_count; ++i) {
    const CurveBinding& b = a.bindings[i];
    // v is a curve parameter in [0, 1): one of 1e300 passed and became inf, and NaN on the GPU.
    if (b.curve_a >= c_count || b.curve_b >= c_count || !(b.w >= 0.0 && b.w <= 1.0) || !(b.v >= 0.0 && b.v <= 1.0)) {
      return invalidArgument("deform asset: vertex " + std::to_string(i) + " has an invalid curve binding");
    }
  }
  for (std::size_t s = 0; s < a.segments.size(); ++s) {
    const DeformSegment& seg = a.segments[s];
    const std::string name = "segment " + std::to_string(s) + " ";
    ODESKIN_TRY(fieldSize(name + "base_residuals", seg.base_residuals.size(), v_count));
    ODESKIN_TRY(fieldSize(name + "coefficients", seg.coefficients.size(), c_count * m_count));
    ODESKIN_TRY(fieldSize(name + "rates", seg.rates.size(), c_count * m_count));
    ODESKIN_TRY(fieldSize(name + "remainder_indices", seg.remainder_indices.size(), v_count));
    for (std::uint32_t r : seg.remainder_indices) {
      if (r != kNoRemainder && r >= seg.remainders.size()) {
        return invalidArgument("deform asset: " + name + "references remainder " + std::to_string(r) + " of " +
                               std::to_string(seg.remainders.size()));
      }
    }
  }
  if (!(a.segment_seconds > 0.0) || !std::isfinite(a.segment_seconds)) {
    return invalidArgument("deform asset: segment length " + messageNumber(a.segment_seconds) + " s is not positive");
  }
  if (a.skinning != SkinningMode::kLinear && a.skinning != SkinningMode::kDualQuaternion) {
    return invalidArgument("deform asset: unknown skinning mode");
  }
  if (!a.curves.empty()) ODESKIN_TRY(fieldSize("curves", a.curves.size(), c_count));
  for (std::size_t c = 0; c < a.curves.size(); ++c) {
    const IsoCurve& curve = a.curves[c];
    if (curve.v.size() != curve.points.size()) {
      return invalidArgument("deform asset: curve " + std::to_string(c) + " has a v per point missing");
    }
    for (const CurvePoint& p : curve.points) {
      if (p.a >= v_count || p.b >= v_count || !(p.t >= 0.0 && p.t <= 1.0)) {
        return invalidArgument("deform asset: curve " + std::to_string(c) + " has a point off the mesh");
      }
    }
  }
  if (!a.bone_parents.empty()) {
    ODESKIN_TRY(fieldSize("bone_parents", a.bone_parents.size(), a.bone_count));
    for (std::int32_t parent : a.bone_parents) {
      if (parent < -1 || parent >= static_cast<std::int32_t>(a.bone_count)) {
        return invalidArgument("deform asset: bone parent " + std::to_string(parent) + " out of range");
      }
    }
  }
  if (!a.bone_names.empty()) ODESKIN_TRY(fieldSize("bone_names", a.bone_names.size(), a.bone_count));
  ODESKIN_TRY(checkFaceList(a.faces, v_count, "deform asset", "face"));
  // A .odsk file's rows are read as stored, and the runtime and the export walk them.
  ODESKIN_TRY(checkRenderLayout(a.render, v_count, a.faces.faceCount(), "deform asset"));
  return validateInfluences(a.influences, v_count, a.bone_count);
}

Result<PackedDeformData> packDeformAsset(const DeformAsset& a, std::uint32_t influence_layout) {
  ODESKIN_TRY(validateDeformAsset(a));
  ODESKIN_TRY(checkFloat32(a));
  PackedDeformData p;
  p.vertex_count = static_cast<std::uint32_t>(a.vertexCount());
  p.modes = static_cast<std::uint32_t>(a.modes);
  p.curve_count = static_cast<std::uint32_t>(a.curveCount());
  p.material_count = static_cast<std::uint32_t>(a.materials.size());
  p.bone_count = a.bone_count;
  p.segment_count = static_cast<std::uint32_t>(a.segments.size());
  p.residual_space = a.residual_space;
  p.skinning = a.skinning;
  p.rest_positions.reserve(p.vertex_count);
  for (const Vec3& x : a.rest_positions) p.rest_positions.push_back(toGpuFloat4(x, 1.0f));
  for (const CurveBinding& b : a.bindings) {
    p.bindings.push_back(gpu::VertexBinding{b.curve_a, b.curve_b, static_cast<float>(b.w), static_cast<float>(b.v)});
  }
  p.curve_materials = a.curve_materials;
  bool any_rate = false;
  for (const DeformSegment& seg : a.segments) {
    p.remainder_base.push_back(static_cast<std::uint32_t>(p.remainders.size()));
    for (std::size_t i = 0; i < a.vertexCount(); ++i) {
      const Vec3& r = seg.base_residuals[i];
      p.segment_vertices.push_back(gpu::SegmentVertex{static_cast<float>(r.x), static_cast<float>(r.y),
                                                      static_cast<float>(r.z), seg.remainder_indices[i]});
    }
    for (const Vec3& e : seg.remainders) p.remainders.push_back(toGpuFloat4(e));
    for (const Vec3& d : seg.coefficients) p.coefficients.push_back(toGpuFloat4(d));
    for (const Vec3& r : seg.rates) {
      p.rates.push_back(toGpuFloat4(r));
      any_rate = any_rate || r != Vec3(0.0);
    }
  }
  // An all-zero rate buffer would cost a second series per vertex for nothing.
  if (!any_rate) p.rates.clear();
  p.influence_layout = influence_layout;
  if (influence_layout == ODESKIN_INFLUENCES_SPARSE) {
    p.influence_offsets = a.influences.offsets;
    for (std::size_t k = 0; k < a.influences.bones.size(); ++k) {
      p.influences.push_back(gpu::Influence{a.influences.bones[k], static_cast<float>(a.influences.weights[k])});
    }
  } else {
    ODESKIN_ASSIGN_OR_RETURN(FixedSlotInfluences fixed, toFixedSlots(a.influences, influence_layout));
    for (std::size_t k = 0; k < fixed.bones.size(); ++k) {
      p.influences.push_back(gpu::Influence{fixed.bones[k], fixed.weights[k]});
    }
  }
  return p;
}

}  // namespace odeskin

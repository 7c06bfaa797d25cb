// SPDX-License-Identifier: MIT
#include "target_normals.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../offline/deform_player.hpp"
#include "../offline/residual_fit.hpp"

namespace odeskin {
namespace {

// Points per segment where the linear blend of the deltas is checked against the exact normals.
constexpr int kCheckedPoints = 32;
// Central-difference step, as the largest displacement over the box: its truncation error is
// second order in the step (~1e-12 here), its rounding about 1e-16 / 1e-6.
constexpr double kStep = 1e-6;

// `values` indexed as the field is: topology vertices for displacements, output vertices for normals.
void addScaled(std::vector<Vec3>& values, const SparseField& field, double weight) {
  for (std::size_t k = 0; k < field.vertices.size(); ++k) values[field.vertices[k]] += weight * field.values[k];
}

SparseField sparse(const std::vector<Vec3>& dense) {
  SparseField out;
  for (std::size_t o = 0; o < dense.size(); ++o) {
    if (dense[o] == Vec3(0.0)) continue;
    out.vertices.push_back(static_cast<std::uint32_t>(o));
    out.values.push_back(dense[o]);
  }
  return out;
}

// d/dh outputNormals(shape + h field) at h = 0. Vertices whose faces the field does not touch get
// the same normal twice and so an exact zero. `shape` comes back bit-for-bit as it was.
SparseField normalDerivative(const DeformAsset& asset, std::vector<Vec3>& shape, const SparseField& field, double box) {
  const double length = field.maxLength();
  if (length == 0.0) return {};
  const double h = kStep * box / length;
  std::vector<Vec3> saved;
  saved.reserve(field.vertices.size());
  for (std::uint32_t i : field.vertices) saved.push_back(shape[i]);
  addScaled(shape, field, h);
  const std::vector<Vec3> plus = outputNormals(asset, shape);
  for (std::size_t k = 0; k < field.vertices.size(); ++k) shape[field.vertices[k]] = saved[k] - h * field.values[k];
  const std::vector<Vec3> minus = outputNormals(asset, shape);
  for (std::size_t k = 0; k < field.vertices.size(); ++k) shape[field.vertices[k]] = saved[k];
  SparseField out;
  for (std::size_t o = 0; o < plus.size(); ++o) {
    if (plus[o] == minus[o]) continue;
    out.vertices.push_back(static_cast<std::uint32_t>(o));
    out.values.push_back((plus[o] - minus[o]) / (2.0 * h));
  }
  return out;
}

// The angle between the normal a viewer makes of `blend` (normalised) and the unit `exact`. A blend
// that cancels to nothing leaves the viewer no direction: the worst case.
double blendAngle(const Vec3& blend, const Vec3& exact) {
  if (blend == Vec3(0.0)) return std::numbers::pi;
  return std::atan2(glm::length(glm::cross(blend, exact)), glm::dot(blend, exact));
}

void dropVertices(SparseField& field, const std::vector<bool>& drop) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < field.vertices.size(); ++k) {
    if (drop[field.vertices[k]]) continue;
    field.vertices[kept] = field.vertices[k];
    field.values[kept++] = field.values[k];
  }
  field.vertices.resize(kept);
  field.values.resize(kept);
}

}  // namespace

Result<TargetNormals> buildTargetNormals(const DeformAsset& asset, std::span<const Vec3> base, const ModeTargetSet& set) {
  if (base.size() != asset.vertexCount()) {
    return invalidArgument("export: " + std::to_string(base.size()) + " base positions for " +
                           std::to_string(asset.vertexCount()) + " vertices");
  }
  const double box = std::max(longestBoxSide(base), 1e-300);
  TargetNormals out;
  out.deltas.resize(set.targets.size());
  std::vector<Vec3> shape(base.begin(), base.end());
  std::vector<Vec3> start = outputNormals(asset, shape);  // what every earlier target adds up to
  std::vector<double> vertex_worst(start.size(), 0.0);
  double angle_sum = 0.0;

  for (std::uint32_t s = 0; s < asset.segments.size(); ++s) {
    std::vector<std::size_t> members;
    std::size_t correction = set.targets.size();
    for (std::size_t k = 0; k < set.targets.size(); ++k) {
      if (set.targets[k].segment != s) continue;
      members.push_back(k);
      if (set.targets[k].curve.kind == WeightCurveKind::kRemainder) correction = k;
    }
    if (correction == set.targets.size()) {
      return invalidArgument("export: segment " + std::to_string(s) + " has no key correction target to carry its normals");
    }
    std::vector<Vec3> end_shape = shape;
    std::vector<Vec3> linear_end = start;
    for (std::size_t k : members) {
      const ModeTarget& t = set.targets[k];
      addScaled(end_shape, t.field, t.curve.at(1.0).value);
      if (k == correction) continue;
      out.deltas[k] = normalDerivative(asset, shape, t.field, box);
      addScaled(linear_end, out.deltas[k], t.curve.at(1.0).value);
    }
    const std::vector<Vec3> end = outputNormals(asset, end_shape);
    const std::size_t count = end.size();

    // Two ways to reach the key: the modes' derivatives plus what they miss, or only the blend of
    // the two keys' normals by the correction's weight. Both are exact at the keys; each vertex
    // keeps the one that strays less on the way.
    std::vector<double> modes_error(count, 0.0), keys_error(count, 0.0), modes_sum(count, 0.0), keys_sum(count, 0.0);
    for (int j = 1; j < kCheckedPoints; ++j) {
      const double tau = static_cast<double>(j) / kCheckedPoints;
      std::vector<Vec3> played_shape = shape;
      std::vector<Vec3> modes = start;
      for (std::size_t k : members) {
        const double w = set.targets[k].curve.at(tau).value;
        addScaled(played_shape, set.targets[k].field, w);
        addScaled(modes, out.deltas[k], w);  // the correction's delta is still empty here
      }
      const double w_r = remainderWeight(tau);
      const std::vector<Vec3> exact = outputNormals(asset, played_shape);
      for (std::size_t o = 0; o < count; ++o) {
        const double by_modes = blendAngle(modes[o] + w_r * (end[o] - linear_end[o]), exact[o]);
        const double by_keys = blendAngle(start[o] + w_r * (end[o] - start[o]), exact[o]);
        modes_error[o] = std::max(modes_error[o], by_modes);
        keys_error[o] = std::max(keys_error[o], by_keys);
        modes_sum[o] += by_modes;
        keys_sum[o] += by_keys;
      }
    }
    std::vector<bool> by_keys(count, false);
    std::vector<Vec3> rest(count);
    for (std::size_t o = 0; o < count; ++o) {
      by_keys[o] = keys_error[o] < modes_error[o];
      rest[o] = end[o] - (by_keys[o] ? start[o] : linear_end[o]);
      vertex_worst[o] = std::max(vertex_worst[o], std::min(keys_error[o], modes_error[o]));
      angle_sum += by_keys[o] ? keys_sum[o] : modes_sum[o];
      out.key_blended += by_keys[o] ? 1 : 0;
    }
    for (std::size_t k : members) dropVertices(out.deltas[k], by_keys);
    out.deltas[correction] = sparse(rest);
    shape = std::move(end_shape);
    start = end;
  }
  if (!vertex_worst.empty()) {
    const double checked = static_cast<double>(asset.segments.size()) * (kCheckedPoints - 1) * static_cast<double>(vertex_worst.size());
    out.mean_angle = angle_sum / checked;
    out.max_angle = *std::max_element(vertex_worst.begin(), vertex_worst.end());
    const auto p99 = vertex_worst.begin() + static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(vertex_worst.size() - 1));
    std::nth_element(vertex_worst.begin(), p99, vertex_worst.end());
    out.vertex_p99_angle = *p99;
  }
  return out;
}

}  // namespace odeskin

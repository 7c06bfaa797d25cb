// SPDX-License-Identifier: MIT
#include "procedural_arm.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "../kernels/lbs_job.hpp"

namespace odeskin {
namespace {

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Status checkOptions(const ArmOptions& o) {
  if (o.rings < 3) return invalidArgument("arm: rings must be at least 3, got " + std::to_string(o.rings));
  if (o.ring_vertices < 3) return invalidArgument("arm: ring_vertices must be at least 3");
  if (o.curve_stride < 1 || o.curve_stride >= o.rings) return invalidArgument("arm: curve_stride must be in [1, rings)");
  if (!(o.length > 0.0) || !(o.radius > 0.0) || !(o.blend_width > 0.0) || !(o.blend_width < 0.5)) {
    return invalidArgument("arm: length, radius and blend_width must be positive (blend_width < 0.5)");
  }
  if (!std::isfinite(o.bend_degrees) || !std::isfinite(o.bulge) || std::abs(o.bulge) >= 1.0) {
    return invalidArgument("arm: bend_degrees must be finite and |bulge| < 1");
  }
  if (static_cast<double>(o.rings) * o.ring_vertices > 64e6) return invalidArgument("arm: more than 64M vertices");
  return okStatus();
}

}  // namespace

Result<ProceduralArm> makeProceduralArm(const ArmOptions& o) {
  ODESKIN_TRY(checkOptions(o));
  ProceduralArm arm;
  FitInput& in = arm.fit_input;
  const std::uint32_t rings = o.rings;
  const std::uint32_t per_ring = o.ring_vertices;
  const double elbow_x = 0.5 * o.length;
  const Vec3 elbow(elbow_x, 0.0, 0.0);

  // Curves: every curve_stride-th ring and always the last one; rings between bind to both
  // neighbours with w = their relative position (PIPELINE.md 3's blend of two series).
  std::vector<std::uint32_t> curve_rings;
  for (std::uint32_t r = 0; r < rings; r += o.curve_stride) curve_rings.push_back(r);
  if (curve_rings.back() != rings - 1) curve_rings.push_back(rings - 1);
  in.curves.resize(curve_rings.size());

  const std::size_t v_count = armVertexCount(o);
  in.rest_positions.resize(v_count);
  in.bindings.resize(v_count);
  std::vector<Vec3> bulge(v_count);
  in.influences.offsets.assign(1, 0);
  std::size_t curve = 0;
  for (std::uint32_t r = 0; r < rings; ++r) {
    while (curve + 1 < curve_rings.size() && curve_rings[curve + 1] <= r) ++curve;
    const bool on_curve = curve_rings[curve] == r;
    const double x = o.length * r / (rings - 1);
    const double s = x / o.length;
    const double ring_radius = o.radius * (1.0 - 0.25 * s);  // taper towards the wrist
    // Biceps: a Gaussian along the upper arm, on the +y (inner) side.
    const double along = std::exp(-std::pow((s - 0.28) / 0.1, 2.0));
    const double forearm_weight = smoothstep(0.5 - o.blend_width, 0.5 + o.blend_width, s);
    for (std::uint32_t j = 0; j < per_ring; ++j) {
      const std::size_t i = static_cast<std::size_t>(r) * per_ring + j;
      const double v = static_cast<double>(j) / per_ring;
      const double theta = 2.0 * std::numbers::pi * v;
      const Vec3 normal(0.0, std::cos(theta), std::sin(theta));
      in.rest_positions[i] = Vec3(x, 0.0, 0.0) + ring_radius * normal;
      const double around = std::pow(std::max(0.0, std::cos(theta - 0.5 * std::numbers::pi)), 2.0);
      bulge[i] = o.bulge * ring_radius * along * around * normal;
      if (on_curve) {
        in.bindings[i] = CurveBinding{static_cast<std::uint32_t>(curve), static_cast<std::uint32_t>(curve), 0.0, v};
        const auto vertex = static_cast<std::uint32_t>(i);
        in.curves[curve].points.push_back(CurvePoint{vertex, vertex, 0.0});
        in.curves[curve].v.push_back(v);
      } else {
        const double w = static_cast<double>(r - curve_rings[curve]) / (curve_rings[curve + 1] - curve_rings[curve]);
        in.bindings[i] = CurveBinding{static_cast<std::uint32_t>(curve), static_cast<std::uint32_t>(curve + 1), w, v};
      }
      for (std::uint32_t b = 0; b < 2; ++b) {
        const double w = b == 0 ? 1.0 - forearm_weight : forearm_weight;
        if (w <= 0.0) continue;
        in.influences.bones.push_back(b);
        in.influences.weights.push_back(w);
      }
      in.influences.offsets.push_back(static_cast<std::uint32_t>(in.influences.bones.size()));
    }
  }
  for (IsoCurve& c : in.curves) c.closed = true;

  // Quads between consecutive rings, counter-clockwise seen from outside.
  for (std::uint32_t r = 0; r + 1 < rings; ++r) {
    for (std::uint32_t j = 0; j < per_ring; ++j) {
      const std::uint32_t a = r * per_ring + j;
      const std::uint32_t b = r * per_ring + (j + 1) % per_ring;
      in.faces.indices.insert(in.faces.indices.end(), {a, a + per_ring, b + per_ring, b});
      in.faces.face_offsets.push_back(static_cast<std::uint32_t>(in.faces.indices.size()));
    }
  }

  in.bone_count = 2;
  in.bone_pivots = {Vec3(0.0), elbow};
  const RigidTransform identity;
  const RigidTransform bent = rotationAbout(elbow, Vec3(0.0, 0.0, 1.0), o.bend_degrees * std::numbers::pi / 180.0);
  in.key_poses = {{identity, identity}, {identity, bent}};

  // The end pose is the skinned bent arm with the bulge applied in bind space, so the exact
  // bind-space corrective r^1 is the bulge itself (a check the tests use).
  arm.start_positions = in.rest_positions;
  arm.end_positions.resize(v_count);
  const BoneTransform bones[2] = {identity.matrix(), bent.matrix()};
  const InfluencesView influences(in.influences);
  for (std::size_t i = 0; i < v_count; ++i) {
    arm.end_positions[i] = skinPoint(influences, bones, i, in.rest_positions[i] + bulge[i]);
  }
  in.poses = {arm.start_positions, arm.end_positions};
  return arm;
}

}  // namespace odeskin

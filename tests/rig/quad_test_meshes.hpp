// SPDX-License-Identifier: MIT
// Quad-dominant meshes with a known parameterisation for the ray-and-fan tests: tubes swept along
// a path (straight capsule, a limb bent 90 degrees), where every vertex knows its ring and its
// position round the ring, so every edge is known to be axial (same position round, next ring)
// or circumferential (same ring); and a T-shaped body from Catmull-Clark steps of a box cage.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

#include "engine/core/types.hpp"
#include "engine/mesh/poly_mesh.hpp"

namespace odeskin::testing {

struct QuadTestMesh {
  std::vector<Vec3> positions;
  FaceList faces;
  std::vector<int> ring;    // per vertex: ring index along the tube (-1: a pole or unknown)
  std::vector<int> around;  // per vertex: position round the ring (-1: a pole or unknown)
  std::vector<Vec3> axis;   // per vertex: the true axial direction (0: unknown, e.g. at a junction)

  void face(std::initializer_list<std::uint32_t> corners) {
    faces.indices.insert(faces.indices.end(), corners);
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  }
};

// A tube of radius r swept along a planar path in the xy plane (centre(s), unit tangent(s), s in
// [0, length]) with `sides` vertices per ring and rings about as far apart as the sides are long
// (square quads). caps: a hemisphere of rings closed by a pole (triangles) at each end; else open.
inline QuadTestMesh sweptTube(const std::function<Vec3(double)>& centre, const std::function<Vec3(double)>& tangent,
                              double length, double r, int sides, bool caps) {
  QuadTestMesh m;
  const double step = 2.0 * std::numbers::pi * r / sides;
  const int rings = std::max(2, static_cast<int>(std::lround(length / step)) + 1);
  const Vec3 z(0.0, 0.0, 1.0);
  auto addRing = [&](const Vec3& c, const Vec3& t, double radius, int index) {
    const Vec3 w = glm::cross(t, z);
    for (int k = 0; k < sides; ++k) {
      const double a = 2.0 * std::numbers::pi * k / sides;
      m.positions.push_back(c + radius * (std::cos(a) * z + std::sin(a) * w));
      m.ring.push_back(index);
      m.around.push_back(k);
      m.axis.push_back(t);
    }
  };
  const int cap_rings = caps ? std::max(2, sides / 4) : 0;
  int index = 0;
  // Cap at s = 0: rings at latitudes from near the pole down to the equator (excluded).
  const Vec3 c0 = centre(0.0), t0 = tangent(0.0);
  for (int k = cap_rings; k >= 1; --k) {
    const double phi = 0.5 * std::numbers::pi * k / (cap_rings + 1.0);
    addRing(c0 - r * std::sin(phi) * t0, t0, r * std::cos(phi), index++);
  }
  for (int i = 0; i < rings; ++i) {
    const double s = length * i / (rings - 1);
    addRing(centre(s), tangent(s), r, index++);
  }
  const Vec3 c1 = centre(length), t1 = tangent(length);
  for (int k = 1; k <= cap_rings; ++k) {
    const double phi = 0.5 * std::numbers::pi * k / (cap_rings + 1.0);
    addRing(c1 + r * std::sin(phi) * t1, t1, r * std::cos(phi), index++);
  }
  const int total = index;
  auto at = [&](int i, int k) { return static_cast<std::uint32_t>(i * sides + (k % sides)); };
  for (int i = 0; i + 1 < total; ++i) {
    for (int k = 0; k < sides; ++k) m.face({at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k)});
  }
  if (caps) {
    // The latitude rings of the first cap shrink towards s < 0: the pole closes ring 0.
    const auto p0 = static_cast<std::uint32_t>(m.positions.size());
    m.positions.push_back(c0 - r * t0);
    const auto p1 = p0 + 1;
    m.positions.push_back(c1 + r * t1);
    for (int pole = 0; pole < 2; ++pole) {
      m.ring.push_back(-1);
      m.around.push_back(-1);
      m.axis.push_back(Vec3(0.0));
    }
    for (int k = 0; k < sides; ++k) {
      m.face({p0, at(0, k + 1), at(0, k)});
      m.face({p1, at(total - 1, k), at(total - 1, k + 1)});
    }
  }
  return m;
}

// A straight capsule along x from 0 to `length`.
inline QuadTestMesh quadCapsule(double length, double r, int sides) {
  return sweptTube([](double s) { return Vec3(s, 0.0, 0.0); }, [](double) { return Vec3(1.0, 0.0, 0.0); }, length, r,
                   sides, true);
}

// An open tube along +x (length `arm`) up to the origin, a quarter circle of radius `bend` turning
// to +y, then straight on along +y (length `forearm`): a limb bent 90 degrees at an elbow centred
// on (bend sin 45, bend (1 - cos 45), 0).
inline QuadTestMesh bentTube(double arm, double forearm, double bend, double r, int sides) {
  const double arc = 0.5 * std::numbers::pi * bend;
  auto centre = [=](double s) {
    if (s <= arm) return Vec3(s - arm, 0.0, 0.0);
    if (s <= arm + arc) {
      const double phi = (s - arm) / bend;
      return Vec3(bend * std::sin(phi), bend * (1.0 - std::cos(phi)), 0.0);
    }
    return Vec3(bend, bend + (s - arm - arc), 0.0);
  };
  auto tangent = [=](double s) {
    if (s <= arm) return Vec3(1.0, 0.0, 0.0);
    if (s <= arm + arc) {
      const double phi = (s - arm) / bend;
      return Vec3(std::cos(phi), std::sin(phi), 0.0);
    }
    return Vec3(0.0, 1.0, 0.0);
  };
  return sweptTube(centre, tangent, arm + arc + forearm, r, sides, false);
}

// `steps` Catmull-Clark steps of a polygon mesh (all quads after the first).
inline QuadTestMesh catmullClark(const std::vector<Vec3>& positions, const FaceList& faces, int steps) {
  PolyMesh mesh;
  for (const Vec3& p : positions) mesh.add_vertex(PolyMesh::Point(p.x, p.y, p.z));
  std::vector<PolyMesh::VertexHandle> face;
  for (std::size_t f = 0; f < faces.faceCount(); ++f) {
    face.clear();
    for (std::uint32_t k = faces.face_offsets[f]; k < faces.face_offsets[f + 1]; ++k) {
      face.push_back(PolyMesh::VertexHandle(static_cast<int>(faces.indices[k])));
    }
    mesh.add_face(face);
  }
  OpenMesh::Subdivider::Uniform::CatmullClarkT<PolyMesh> subdivide;
  subdivide.attach(mesh);
  subdivide(static_cast<std::size_t>(steps));
  subdivide.detach();
  mesh.garbage_collection();
  QuadTestMesh out;
  for (auto v : mesh.vertices()) {
    const PolyMesh::Point& p = mesh.point(v);
    out.positions.push_back(Vec3(p[0], p[1], p[2]));
  }
  for (auto f : mesh.faces()) {
    for (auto v : mesh.fv_range(f)) out.faces.indices.push_back(static_cast<std::uint32_t>(v.idx()));
    out.faces.face_offsets.push_back(static_cast<std::uint32_t>(out.faces.indices.size()));
  }
  out.ring.assign(out.positions.size(), -1);
  out.around.assign(out.positions.size(), -1);
  out.axis.assign(out.positions.size(), Vec3(0.0));
  return out;
}

// A T of unit cubes: a bar along x (cubes x = -half .. half - 1 at y = 0) and a stem down from
// its middle (y = -1 .. -stem), the outer faces as quads, smoothed by `steps` Catmull-Clark steps.
// axis: x in the bar's arms from 2 to half - 1 from the middle, y in the stem from y = -2 to one
// short of its end (the junction and the rounded ends have no one axis).
inline QuadTestMesh quadT(int half, int stem, int steps) {
  std::vector<std::array<int, 2>> cubes;  // (x, y) at z = 0
  for (int x = -half; x < half; ++x) cubes.push_back({x, 0});
  for (int y = -1; y >= -stem; --y) cubes.push_back({-1, y});
  for (int y = -1; y >= -stem; --y) cubes.push_back({0, y});
  auto filled = [&](int x, int y, int z) {
    if (z != 0) return false;
    for (const auto& c : cubes) {
      if (c[0] == x && c[1] == y) return true;
    }
    return false;
  };
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> keys;
  auto vertex = [&](int x, int y, int z) {
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (keys[k] == std::array<int, 3>{x, y, z}) return static_cast<std::uint32_t>(k);
    }
    keys.push_back({x, y, z});
    positions.push_back(Vec3(x, y, z));
    return static_cast<std::uint32_t>(keys.size() - 1);
  };
  FaceList faces;
  auto quad = [&](const std::array<std::array<int, 3>, 4>& c) {
    for (const auto& p : c) faces.indices.push_back(vertex(p[0], p[1], p[2]));
    faces.face_offsets.push_back(static_cast<std::uint32_t>(faces.indices.size()));
  };
  for (const auto& c : cubes) {
    const int x = c[0], y = c[1], z = 0;
    // Outward-facing (counter-clockwise seen from outside) faces where no neighbour cube is.
    if (!filled(x - 1, y, z)) quad({{{x, y, z}, {x, y, z + 1}, {x, y + 1, z + 1}, {x, y + 1, z}}});
    if (!filled(x + 1, y, z)) quad({{{x + 1, y, z}, {x + 1, y + 1, z}, {x + 1, y + 1, z + 1}, {x + 1, y, z + 1}}});
    if (!filled(x, y - 1, z)) quad({{{x, y, z}, {x + 1, y, z}, {x + 1, y, z + 1}, {x, y, z + 1}}});
    if (!filled(x, y + 1, z)) quad({{{x, y + 1, z}, {x, y + 1, z + 1}, {x + 1, y + 1, z + 1}, {x + 1, y + 1, z}}});
    if (!filled(x, y, z - 1)) quad({{{x, y, z}, {x, y + 1, z}, {x + 1, y + 1, z}, {x + 1, y, z}}});
    if (!filled(x, y, z + 1)) quad({{{x, y, z + 1}, {x + 1, y, z + 1}, {x + 1, y + 1, z + 1}, {x, y + 1, z + 1}}});
  }
  QuadTestMesh out = catmullClark(positions, faces, steps);
  for (std::size_t i = 0; i < out.positions.size(); ++i) {
    const Vec3& p = out.positions[i];
    if (p.y > 0.0 && std::abs(p.x) > 2.0 && std::abs(p.x) < half - 1.0) out.axis[i] = Vec3(1.0, 0.0, 0.0);
    if (p.y < -2.0 && p.y > 1.0 - stem) out.axis[i] = Vec3(0.0, 1.0, 0.0);
  }
  return out;
}

}  // namespace odeskin::testing

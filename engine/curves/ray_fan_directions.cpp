// SPDX-License-Identifier: MIT
#include "ray_fan_directions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <unsupported/Eigen/BVH>

#include "../core/parallel.hpp"

namespace odeskin {
namespace {

using Halfedge = PolyMesh::HalfedgeHandle;
using VertexHandle = PolyMesh::VertexHandle;
using Box = Eigen::AlignedBox3d;
using Tree = Eigen::KdBVH<double, 3, int>;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// cos 45 degrees: the edge class where a vertex does not rank its edges (valence other than 4)
// and where the two ends of an edge disagree.
const double kDiagonal = std::sqrt(0.5);
// Edge directions within 30 degrees of each other are one line (one seed plane).
const double kSameLine = std::cos(std::numbers::pi / 6.0);

Vec3 point(const PolyMesh& mesh, VertexHandle v) {
  const PolyMesh::Point& p = mesh.point(v);
  return {p[0], p[1], p[2]};
}

// Faces fanned into triangles for the rays, each knowing its polygon.
struct Triangles {
  std::vector<std::array<Vec3, 3>> corners;
  std::vector<int> face;
  std::vector<Box> boxes;
};

Triangles fanTriangles(const PolyMesh& mesh) {
  Triangles t;
  std::vector<Vec3> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    for (auto v : mesh.fv_range(f)) corners.push_back(point(mesh, v));
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      t.corners.push_back({corners[0], corners[k], corners[k + 1]});
      t.face.push_back(f.idx());
      Box box;
      for (const Vec3& c : t.corners.back()) box.extend(Eigen::Vector3d(c.x, c.y, c.z));
      t.boxes.push_back(box);
    }
  }
  return t;
}

// Nearest triangle a ray meets (Moller-Trumbore), skipping the faces around the ray's own vertex.
struct RayQuery {
  const Triangles* triangles = nullptr;
  const std::vector<int>* skip = nullptr;
  Vec3 origin{0.0};
  Vec3 direction{0.0};
  double best = kInfinity;
  int hit = -1;

  bool intersectVolume(const Box& box) const {
    double t0 = 0.0;
    double t1 = best;
    for (int k = 0; k < 3; ++k) {
      const auto axis = static_cast<glm::length_t>(k);
      const double lo = box.min()(k) - origin[axis];
      const double hi = box.max()(k) - origin[axis];
      if (direction[axis] == 0.0) {
        if (lo > 0.0 || hi < 0.0) return false;
        continue;
      }
      double a = lo / direction[axis];
      double b = hi / direction[axis];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
      if (t0 > t1) return false;
    }
    return true;
  }

  bool intersectObject(int triangle) {
    const auto index = static_cast<std::size_t>(triangle);
    if (std::find(skip->begin(), skip->end(), triangles->face[index]) != skip->end()) return false;
    const std::array<Vec3, 3>& c = triangles->corners[index];
    const Vec3 e1 = c[1] - c[0];
    const Vec3 e2 = c[2] - c[0];
    const Vec3 pv = glm::cross(direction, e2);
    const double det = glm::dot(e1, pv);
    if (det == 0.0) return false;
    const Vec3 tv = origin - c[0];
    const double u = glm::dot(tv, pv) / det;
    if (u < 0.0 || u > 1.0) return false;
    const Vec3 qv = glm::cross(tv, e1);
    const double w = glm::dot(direction, qv) / det;
    if (w < 0.0 || u + w > 1.0) return false;
    const double t = glm::dot(e2, qv) / det;
    if (t > 0.0 && t < best) {
      best = t;
      hit = triangle;
    }
    return false;
  }
};

// Area-weighted polygon normals (Newell), unnormalised.
std::vector<Vec3> faceNormals(const PolyMesh& mesh) {
  std::vector<Vec3> normals(mesh.n_faces(), Vec3(0.0));
  for (auto f : mesh.faces()) {
    Vec3 n(0.0);
    for (auto h : mesh.fh_range(f)) n += glm::cross(point(mesh, mesh.from_vertex_handle(h)), point(mesh, mesh.to_vertex_handle(h)));
    normals[static_cast<std::size_t>(f.idx())] = n;
  }
  return normals;
}

// The plane dot(normal, x - origin) = 0, with a vertex exactly on it counted on the positive side
// (symbolic perturbation: every face then has an even number of crossed edges, consistently).
struct FanPlane {
  Vec3 origin;
  Vec3 normal;
  double side(const Vec3& x) const { return glm::dot(normal, x - origin); }
};

// Length of the section of the mesh by `plane` that passes through the ray's vertex, walked face
// to face from one of its edges; kInfinity when it is open (reaches a boundary), longer than
// `cap`, or does not wind around `centre` (a fold, not the limb). `in_plane` spans the plane with
// the ray direction, for the winding. A section that winds round the axis point crosses the ray
// beyond it, at the wall point `far` or farther (far is the first wall), so from a point x the
// walk still has at least |x - far| + |far - p| to go: a walk is dropped as soon as that bound
// passes `cap`, which stops lengthwise sections about one diameter out instead of a perimeter.
double sectionLength(const PolyMesh& mesh, VertexHandle v, const FanPlane& plane, const Vec3& centre, const Vec3& ray,
                     const Vec3& in_plane, const Vec3& far, double cap, std::vector<Vec3>& points) {
  const double back = glm::length(far - plane.origin);
  auto side = [&](VertexHandle u) { return u == v ? 0.0 : plane.side(point(mesh, u)); };
  auto crossed = [&](Halfedge h) { return (side(mesh.from_vertex_handle(h)) >= 0.0) != (side(mesh.to_vertex_handle(h)) >= 0.0); };
  auto where = [&](Halfedge h) {
    const double a = side(mesh.from_vertex_handle(h));
    const double b = side(mesh.to_vertex_handle(h));
    const double t = a / (a - b);
    return (1.0 - t) * point(mesh, mesh.from_vertex_handle(h)) + t * point(mesh, mesh.to_vertex_handle(h));
  };
  Halfedge start;
  for (auto h : mesh.voh_range(v)) {
    if (crossed(h)) {
      start = h;
      break;
    }
  }
  if (!start.is_valid()) return kInfinity;
  if (mesh.is_boundary(start)) start = mesh.opposite_halfedge_handle(start);
  const auto start_edge = mesh.edge_handle(start);
  points.clear();
  points.push_back(where(start));
  double length = 0.0;
  Halfedge h = start;
  for (std::size_t steps = 0; steps <= mesh.n_faces(); ++steps) {
    // The exit paired with the entry: crossings alternate in sign round a face, and a +- entry
    // pairs with the next crossing, a -+ entry with the previous one (symmetric, so a face with
    // four crossings is walked consistently from either side).
    // One side() per corner: the walk round the face carries the side of the vertex it left.
    const bool forward = side(mesh.from_vertex_handle(h)) >= 0.0;
    Halfedge exit = h;
    bool left_positive = forward ? side(mesh.to_vertex_handle(h)) >= 0.0 : forward;
    for (;;) {
      exit = forward ? mesh.next_halfedge_handle(exit) : mesh.prev_halfedge_handle(exit);
      if (exit == h) return kInfinity;
      const bool positive = side(forward ? mesh.to_vertex_handle(exit) : mesh.from_vertex_handle(exit)) >= 0.0;
      if (positive != left_positive) break;
      left_positive = positive;
    }
    const Vec3 x = where(exit);
    length += glm::length(x - points.back());
    if (length + glm::length(x - far) + back > cap) return kInfinity;
    h = mesh.opposite_halfedge_handle(exit);
    if (mesh.edge_handle(h) == start_edge) {
      length += glm::length(points.front() - x);
      if (length > cap) return kInfinity;
      // Winding number about the axis point, in the plane's coordinates (u along the ray, w
      // across it): signed crossings of the half-line u = 0, w > 0, which runs between p and q.
      points.push_back(x);
      int winding = 0;
      auto coords = [&](const Vec3& y) { return std::array<double, 2>{glm::dot(y - centre, ray), glm::dot(y - centre, in_plane)}; };
      std::array<double, 2> a = coords(x);
      for (const Vec3& y : points) {
        const std::array<double, 2> b = coords(y);
        if ((a[0] > 0.0) != (b[0] > 0.0) && a[1] + (b[1] - a[1]) * (-a[0] / (b[0] - a[0])) > 0.0) winding += b[0] > a[0] ? 1 : -1;
        a = b;
      }
      return winding != 0 ? length : kInfinity;
    }
    if (mesh.is_boundary(h)) return kInfinity;
    points.push_back(x);
  }
  return kInfinity;
}

// The axial direction at one vertex, or zero; `diameter` gets the ray's length (0: no wall hit).
Vec3 vertexAxis(const PolyMesh& mesh, VertexHandle v, const std::vector<Vec3>& face_normals, const Triangles& triangles,
                const Tree& tree, const RayFanOptions& options, std::vector<int>& skip, std::vector<Vec3>& points,
                double& diameter) {
  diameter = 0.0;
  Vec3 normal(0.0);
  skip.clear();
  for (auto f : mesh.vf_range(v)) {
    normal += face_normals[static_cast<std::size_t>(f.idx())];
    skip.push_back(f.idx());
  }
  if (!(glm::length(normal) > 0.0)) return Vec3(0.0);
  normal = glm::normalize(normal);
  const Vec3 p = point(mesh, v);
  RayQuery ray{&triangles, &skip, p, -normal};
  Eigen::BVIntersect(tree, ray);
  if (ray.hit < 0) return Vec3(0.0);
  // The wall must be met from inside the body (its outward normal along the ray); otherwise the
  // ray left the mesh first (a concave spot).
  const auto hit_face = static_cast<std::size_t>(triangles.face[static_cast<std::size_t>(ray.hit)]);
  if (!(glm::dot(face_normals[hit_face], ray.direction) > 0.0)) return Vec3(0.0);
  diameter = ray.best;
  const Vec3 centre = p + 0.5 * ray.best * ray.direction;
  const Vec3 far = p + ray.best * ray.direction;
  // Tangent frame at p; plane k of the fan has normal cos(k pi / K) t1 + sin(k pi / K) t2.
  const Vec3 helper = std::abs(normal.x) < 0.6 ? Vec3(1.0, 0.0, 0.0) : Vec3(0.0, 1.0, 0.0);
  const Vec3 t1 = glm::normalize(glm::cross(normal, helper));
  const Vec3 t2 = glm::cross(normal, t1);
  double best = options.max_section_diameters * diameter;
  Vec3 axis(0.0);
  auto tryPlane = [&](const Vec3& m) {
    // Bounded by the shortest so far: a longer walk is abandoned as soon as it passes it.
    const double length = sectionLength(mesh, v, {p, m}, centre, normal, glm::cross(m, normal), far, best, points);
    if (length < best) {
      best = length;
      axis = m;
    }
  };
  // The planes across the vertex's own edge lines first (one per line: opposite edges of a
  // regular vertex are one line): on a quad mesh one of them is usually across the limb, and the
  // bound it sets cuts the fan's lengthwise walks short.
  std::array<Vec3, 8> seeds;
  std::size_t seed_count = 0;
  for (auto h : mesh.voh_range(v)) {
    const Vec3 e = point(mesh, mesh.to_vertex_handle(h)) - p;
    Vec3 tangent = e - glm::dot(e, normal) * normal;
    if (!(glm::length(tangent) > 0.0) || seed_count == seeds.size()) continue;
    tangent = glm::normalize(tangent);
    bool same_line = false;
    for (std::size_t k = 0; k < seed_count; ++k) same_line = same_line || std::abs(glm::dot(seeds[k], tangent)) > kSameLine;
    if (same_line) continue;
    seeds[seed_count++] = tangent;
    tryPlane(tangent);
  }
  if (!options.full_fan && glm::length(axis) > 0.0) return axis;
  for (int k = 0; k < options.fan_planes; ++k) {
    const double angle = std::numbers::pi * static_cast<double>(k) / static_cast<double>(options.fan_planes);
    tryPlane(std::cos(angle) * t1 + std::sin(angle) * t2);
  }
  return axis;
}

}  // namespace

RayFanDirections rayFanDirections(const PolyMesh& mesh, const RayFanOptions& options_in) {
  RayFanOptions options = options_in;
  options.fan_planes = std::max(2, options.fan_planes);
  if (!(options.max_section_diameters > 0.0)) options.max_section_diameters = RayFanOptions{}.max_section_diameters;
  const std::size_t count = mesh.n_vertices();
  RayFanDirections out;
  out.axes.assign(count, Vec3(0.0));
  out.diameters.assign(count, 0.0);
  out.measured.assign(count, 0);
  out.edges.assign(mesh.n_edges(), EdgeDirection::kUnknown);
  if (count == 0 || mesh.n_faces() == 0) {
    out.unknown_edges = mesh.n_edges();
    return out;
  }
  const std::vector<Vec3> face_normals = faceNormals(mesh);
  const Triangles triangles = fanTriangles(mesh);
  std::vector<int> ids(triangles.face.size());
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = static_cast<int>(k);
  const Tree tree(ids.begin(), ids.end(), triangles.boxes.begin(), triangles.boxes.end());

  std::vector<Vec3> raw(count, Vec3(0.0));
  parallelFor(tbb::blocked_range<std::size_t>(0, count, 64), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<int> skip;
    std::vector<Vec3> points;
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const VertexHandle v(static_cast<int>(i));
      raw[i] = vertexAxis(mesh, v, face_normals, triangles, tree, options, skip, points, out.diameters[i]);
      out.measured[i] = glm::length(raw[i]) > 0.0 ? 1 : 0;
    }
  });
  for (const char m : out.measured) out.measured_vertices += m ? 1 : 0;

  // One-ring smoothing: the principal direction of sum a a^T over the vertex and its neighbours.
  parallelFor(tbb::blocked_range<std::size_t>(0, count, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
      std::size_t n = 0;
      auto add = [&](std::size_t u) {
        if (!out.measured[u]) return;
        const Eigen::Vector3d a(raw[u].x, raw[u].y, raw[u].z);
        tensor += a * a.transpose();
        ++n;
      };
      add(i);
      for (auto u : mesh.vv_range(VertexHandle(static_cast<int>(i)))) add(static_cast<std::size_t>(u.idx()));
      if (n == 0) continue;
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
      eigen.computeDirect(tensor);
      const Eigen::Vector3d a = eigen.eigenvectors().col(2);
      out.axes[i] = glm::normalize(Vec3(a.x(), a.y(), a.z()));
    }
  });

  // Votes: each end with an axis votes for every edge it holds (by rank at valence 4, else by the
  // 45-degree line); a split vote goes by the mean |cos(edge, axis)| of the two ends.
  std::vector<int> circumferential(mesh.n_edges(), 0);
  std::vector<int> axial(mesh.n_edges(), 0);
  std::vector<double> cos_sum(mesh.n_edges(), 0.0);
  std::vector<std::pair<double, std::size_t>> ranked;
  for (std::size_t i = 0; i < count; ++i) {
    const Vec3 a = out.axes[i];
    if (!(glm::length(a) > 0.0)) continue;
    const VertexHandle v(static_cast<int>(i));
    ranked.clear();
    for (auto h : mesh.voh_range(v)) {
      const Vec3 e = point(mesh, mesh.to_vertex_handle(h)) - point(mesh, v);
      const double len = glm::length(e);
      const double c = len > 0.0 ? std::abs(glm::dot(e, a)) / len : kDiagonal;
      const auto edge = static_cast<std::size_t>(mesh.edge_handle(h).idx());
      ranked.push_back({c, edge});
      cos_sum[edge] += c;
    }
    if (ranked.size() == 4) {
      std::sort(ranked.begin(), ranked.end());
      for (std::size_t k = 0; k < 4; ++k) ++(k < 2 ? circumferential : axial)[ranked[k].second];
    } else {
      for (const auto& [c, edge] : ranked) ++(c < kDiagonal ? circumferential : axial)[edge];
    }
  }
  for (std::size_t e = 0; e < mesh.n_edges(); ++e) {
    const int votes = circumferential[e] + axial[e];
    EdgeDirection d = EdgeDirection::kUnknown;
    if (circumferential[e] > axial[e]) {
      d = EdgeDirection::kCircumferential;
    } else if (axial[e] > circumferential[e]) {
      d = EdgeDirection::kAxial;
    } else if (votes > 0) {
      d = cos_sum[e] / static_cast<double>(votes) < kDiagonal ? EdgeDirection::kCircumferential : EdgeDirection::kAxial;
    }
    out.edges[e] = d;
    out.axial_edges += d == EdgeDirection::kAxial ? 1 : 0;
    out.circumferential_edges += d == EdgeDirection::kCircumferential ? 1 : 0;
    out.unknown_edges += d == EdgeDirection::kUnknown ? 1 : 0;
  }
  return out;
}

DirectedLoops directedEdgeLoops(const PolyMesh& mesh, const RayFanDirections& directions, std::size_t min_points) {
  DirectedLoops out;
  for (EdgeLoop& loop : edgeLoops(mesh)) {
    const std::size_t n = loop.vertices.size();
    const std::size_t segments = loop.closed ? n : n - 1;
    std::size_t around = 0;
    std::size_t along = 0;
    for (std::size_t j = 0; j < segments; ++j) {
      const Halfedge h = mesh.find_halfedge(VertexHandle(static_cast<int>(loop.vertices[j])),
                                            VertexHandle(static_cast<int>(loop.vertices[(j + 1) % n])));
      if (!h.is_valid()) continue;
      const EdgeDirection d = directions.edges[static_cast<std::size_t>(mesh.edge_handle(h).idx())];
      around += d == EdgeDirection::kCircumferential ? 1 : 0;
      along += d == EdgeDirection::kAxial ? 1 : 0;
    }
    if (n < min_points) continue;
    if (loop.closed && 2 * around > segments) {
      out.rings.push_back(std::move(loop));
    } else if (2 * along > segments) {
      out.axial.push_back(std::move(loop));
    }
  }
  return out;
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "ray_fan_directions.hpp"

#include <algorithm>
#include <array>
#include <bit>
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

// Faces fanned into triangles for the rays; the BVH holds the faces (half as many boxes as
// triangles on quads, so half the build).
struct Triangles {
  std::vector<std::array<Vec3, 3>> corners;  // face by face
  std::vector<std::uint32_t> first;          // F + 1: face f's triangles are first[f] .. first[f + 1] - 1
  std::vector<Box> boxes;                    // F: each face's box
};

Triangles fanTriangles(const PolyMesh& mesh) {
  Triangles t;
  t.corners.reserve(2 * mesh.n_faces());
  t.first.reserve(mesh.n_faces() + 1);
  t.boxes.reserve(mesh.n_faces());
  std::vector<Vec3> corners;
  for (auto f : mesh.faces()) {
    corners.clear();
    Box box;
    for (auto v : mesh.fv_range(f)) {
      corners.push_back(point(mesh, v));
      box.extend(Eigen::Vector3d(corners.back().x, corners.back().y, corners.back().z));
    }
    t.first.push_back(static_cast<std::uint32_t>(t.corners.size()));
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) t.corners.push_back({corners[0], corners[k], corners[k + 1]});
    t.boxes.push_back(box);
  }
  t.first.push_back(static_cast<std::uint32_t>(t.corners.size()));
  return t;
}

// Nearest face a ray meets (Moller-Trumbore on its triangles), skipping the faces around the ray's
// own vertex.
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

  bool intersectObject(int face) {
    if (std::find(skip->begin(), skip->end(), face) != skip->end()) return false;
    const auto f = static_cast<std::size_t>(face);
    for (std::uint32_t k = triangles->first[f]; k < triangles->first[f + 1]; ++k) {
      const std::array<Vec3, 3>& c = triangles->corners[k];
      const Vec3 e1 = c[1] - c[0];
      const Vec3 e2 = c[2] - c[0];
      const Vec3 pv = glm::cross(direction, e2);
      const double det = glm::dot(e1, pv);
      if (det == 0.0) continue;
      const Vec3 tv = origin - c[0];
      const double u = glm::dot(tv, pv) / det;
      if (u < 0.0 || u > 1.0) continue;
      const Vec3 qv = glm::cross(tv, e1);
      const double w = glm::dot(direction, qv) / det;
      if (w < 0.0 || u + w > 1.0) continue;
      const double t = glm::dot(e2, qv) / det;
      if (t > 0.0 && t < best) {
        best = t;
        hit = face;
      }
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
  // The crossing point on edge h, given the sides of its ends.
  auto where = [&](Halfedge h, double a, double b) {
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
  // The sides of the current edge's ends are carried from face to face: one side() per new corner.
  double from_side = side(mesh.from_vertex_handle(start));
  double to_side = side(mesh.to_vertex_handle(start));
  points.clear();
  points.push_back(where(start, from_side, to_side));
  double length = 0.0;
  Halfedge h = start;
  for (std::size_t steps = 0; steps <= mesh.n_faces(); ++steps) {
    // The exit paired with the entry: crossings alternate in sign round a face, and a +- entry
    // pairs with the next crossing, a -+ entry with the previous one (symmetric, so a face with
    // four crossings is walked consistently from either side).
    const bool forward = from_side >= 0.0;
    Halfedge exit = h;
    double left_side = forward ? to_side : from_side;  // the corner the walk round the face left
    bool left_positive = forward ? to_side >= 0.0 : false;
    double new_side = 0.0;
    for (;;) {
      exit = forward ? mesh.next_halfedge_handle(exit) : mesh.prev_halfedge_handle(exit);
      if (exit == h) return kInfinity;
      new_side = side(forward ? mesh.to_vertex_handle(exit) : mesh.from_vertex_handle(exit));
      const bool positive = new_side >= 0.0;
      if (positive != left_positive) break;
      left_positive = positive;
      left_side = new_side;
    }
    // exit runs from the corner left to the new one (forward), or from the new one to it.
    const double exit_from = forward ? left_side : new_side;
    const double exit_to = forward ? new_side : left_side;
    const Vec3 x = where(exit, exit_from, exit_to);
    length += glm::length(x - points.back());
    if (length + glm::length(x - far) + back > cap) return kInfinity;
    from_side = exit_to;  // h becomes the exit's opposite
    to_side = exit_from;
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
  const auto hit_face = static_cast<std::size_t>(ray.hit);
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

// What vertexAxis needs besides the vertex, built once per mesh.
struct AxisTest {
  const PolyMesh& mesh;
  const std::vector<Vec3>& face_normals;
  const Triangles& triangles;
  const Tree& tree;
  const RayFanOptions& options;
};

void countEdges(RayFanDirections& out) {
  for (const EdgeDirection d : out.edges) {
    out.axial_edges += d == EdgeDirection::kAxial ? 1 : 0;
    out.circumferential_edges += d == EdgeDirection::kCircumferential ? 1 : 0;
    out.unknown_edges += d == EdgeDirection::kUnknown ? 1 : 0;
  }
}

// The class an edge (or loop) gets from its votes; a split vote goes by the mean |cos(edge, axis)|.
EdgeDirection decide(int circumferential, int axial, double cos_sum) {
  if (circumferential > axial) return EdgeDirection::kCircumferential;
  if (axial > circumferential) return EdgeDirection::kAxial;
  const int votes = circumferential + axial;
  if (votes == 0) return EdgeDirection::kUnknown;
  return cos_sum / static_cast<double>(votes) < kDiagonal ? EdgeDirection::kCircumferential : EdgeDirection::kAxial;
}

// One-ring smoothing: the principal direction of sum a a^T over the vertex's and its neighbours'
// measured axes (they have no sign); 0 when none is measured.
Vec3 ringAxis(const PolyMesh& mesh, std::size_t i, const std::vector<Vec3>& raw, const std::vector<char>& measured) {
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  std::size_t n = 0;
  auto add = [&](std::size_t u) {
    if (!measured[u]) return;
    const Eigen::Vector3d a(raw[u].x, raw[u].y, raw[u].z);
    tensor += a * a.transpose();
    ++n;
  };
  add(i);
  for (auto u : mesh.vv_range(VertexHandle(static_cast<int>(i)))) add(static_cast<std::size_t>(u.idx()));
  if (n == 0) return Vec3(0.0);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(tensor);
  const Eigen::Vector3d a = eigen.eigenvectors().col(2);
  return glm::normalize(Vec3(a.x(), a.y(), a.z()));
}

// The test at every vertex: axes smoothed over the one-rings, each end votes on its edges.
void everyVertex(const AxisTest& test, RayFanDirections& out) {
  const PolyMesh& mesh = test.mesh;
  const std::size_t count = mesh.n_vertices();
  std::vector<Vec3> raw(count, Vec3(0.0));
  parallelFor(tbb::blocked_range<std::size_t>(0, count, 64), [&](const tbb::blocked_range<std::size_t>& range) {
    std::vector<int> skip;
    std::vector<Vec3> points;
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const VertexHandle v(static_cast<int>(i));
      raw[i] = vertexAxis(mesh, v, test.face_normals, test.triangles, test.tree, test.options, skip, points, out.diameters[i]);
      out.measured[i] = glm::length(raw[i]) > 0.0 ? 1 : 0;
    }
  });
  out.tested_vertices = count;
  for (const char m : out.measured) out.measured_vertices += m ? 1 : 0;

  // One-ring smoothing: the principal direction of sum a a^T over the vertex and its neighbours.
  parallelFor(tbb::blocked_range<std::size_t>(0, count, 256), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      out.axes[i] = ringAxis(mesh, i, raw, out.measured);
    }
  });

  // Votes: each end with an axis votes for every edge it holds (by rank at valence 4, else by the
  // 45-degree line).
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
  for (std::size_t e = 0; e < mesh.n_edges(); ++e) out.edges[e] = decide(circumferential[e], axial[e], cos_sum[e]);
}

// One loop's sampling: where it is in its candidate order and the votes it has.
struct LoopVotes {
  std::size_t cursor = 0;
  int circumferential = 0;
  int axial = 0;
  int pending = 0;  // vertices queued in this round that are on the loop
  double cos_sum = 0.0;
  int decided() const { return circumferential + axial; }
};

// The loops through a vertex and, given an axis, the sum of |cos(edge, axis)| over each one's edges
// there (a vertex inside a loop holds two edges of it, an end one).
struct VertexLoops {
  std::array<std::uint32_t, 8> loop{};
  std::array<double, 8> cos_sum{};
  std::array<int, 8> edges{};
  std::size_t count = 0;
};

VertexLoops loopsThrough(const PolyMesh& mesh, VertexHandle v, const std::vector<std::uint32_t>& edge_loop, const Vec3* axis) {
  VertexLoops out;
  for (auto h : mesh.voh_range(v)) {
    const std::uint32_t l = edge_loop[static_cast<std::size_t>(mesh.edge_handle(h).idx())];
    std::size_t k = 0;
    while (k < out.count && out.loop[k] != l) ++k;
    if (k == out.count) {
      if (out.count == out.loop.size()) continue;  // valence > 8, every edge on its own loop: the rest do not vote
      out.loop[out.count++] = l;
    }
    if (axis == nullptr) continue;
    const Vec3 e = point(mesh, mesh.to_vertex_handle(h)) - point(mesh, v);
    const double len = glm::length(e);
    out.cos_sum[k] += len > 0.0 ? std::abs(glm::dot(e, *axis)) / len : kDiagonal;
    ++out.edges[k];
  }
  return out;
}

// Position `cursor` of loop `l`'s candidate order: first `wanted` evenly spaced vertices, then
// every vertex in bit-reversed order (each prefix spread along the loop); false when none is left.
// The order starts at a different place on each loop (golden-ratio steps), so the loops that cross
// a tube's rings get their votes from the rings' samples instead of all meeting the same few.
bool nextCandidate(std::size_t l, std::size_t n, std::size_t wanted, std::size_t& cursor, std::size_t& index) {
  const std::size_t spread = std::min(wanted, n);
  const std::size_t span = std::bit_ceil(n);
  const int bits = std::countr_zero(span);
  const double turn = static_cast<double>(l) * 0.6180339887498949;
  const auto offset = std::min(n - 1, static_cast<std::size_t>((turn - std::floor(turn)) * static_cast<double>(n)));
  while (cursor < spread + span) {
    const std::size_t c = cursor++;
    if (c < spread) {
      index = (offset + c * n / spread) % n;
      return true;
    }
    std::size_t r = 0;
    for (int b = 0; b < bits; ++b) r |= ((c - spread) >> b & 1u) << (bits - 1 - b);
    if (r < n) {
      index = (offset + r) % n;
      return true;
    }
  }
  return false;
}

// The test at sampled vertices of each edge loop (RayFanOptions::loop_samples), in rounds: every
// loop short of `wanted` decided votes queues its next candidates (counting the votes already
// queued for it by vertices of crossing loops), the round's vertices are tested in parallel and
// vote in the order they were queued, so the result does not depend on the threads. A loop none
// of whose vertices got an axis (an open tube's rim: no section through a rim vertex closes) then
// votes as in everyVertex, with its vertices' one-ring axes: the neighbours are tested as needed.
void sampledLoops(const AxisTest& test, std::size_t wanted, RayFanDirections& out) {
  const PolyMesh& mesh = test.mesh;
  out.loops = edgeLoops(mesh);
  const std::vector<EdgeLoop>& loops = out.loops;
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> edge_loop(mesh.n_edges(), kNone);
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (const std::uint32_t e : loops[l].edges) edge_loop[e] = static_cast<std::uint32_t>(l);
  }
  std::vector<LoopVotes> votes(loops.size());
  std::vector<char> queued(mesh.n_vertices(), 0);
  std::vector<Vec3> raw(mesh.n_vertices(), Vec3(0.0));
  std::vector<std::size_t> batch;
  auto testBatch = [&] {
    parallelFor(tbb::blocked_range<std::size_t>(0, batch.size(), 16), [&](const tbb::blocked_range<std::size_t>& range) {
      std::vector<int> skip;
      std::vector<Vec3> points;
      for (std::size_t b = range.begin(); b < range.end(); ++b) {
        const std::size_t i = batch[b];
        raw[i] = vertexAxis(mesh, VertexHandle(static_cast<int>(i)), test.face_normals, test.triangles, test.tree, test.options, skip,
                            points, out.diameters[i]);
      }
    });
    for (const std::size_t i : batch) {
      ++out.tested_vertices;
      if (!(glm::length(raw[i]) > 0.0)) continue;
      out.axes[i] = raw[i];
      out.measured[i] = 1;
      ++out.measured_vertices;
    }
  };
  auto queueVertex = [&](std::size_t v, const std::vector<char>* only) {
    const VertexLoops through = loopsThrough(mesh, VertexHandle(static_cast<int>(v)), edge_loop, nullptr);
    for (std::size_t k = 0; k < through.count; ++k) {
      const std::uint32_t l = through.loop[k];
      if (l != kNone && (only == nullptr || (*only)[l])) ++votes[l].pending;
    }
  };
  // Where two loops cross (a regular vertex) the one more across the axis is circumferential and
  // the other axial, as everyVertex's rank rule; elsewhere each by the 45-degree line.
  auto vote = [&](std::size_t v, const Vec3& axis, const std::vector<char>* only) {
    const VertexLoops through = loopsThrough(mesh, VertexHandle(static_cast<int>(v)), edge_loop, &axis);
    std::array<double, 8> mean{};
    for (std::size_t k = 0; k < through.count; ++k) mean[k] = through.cos_sum[k] / static_cast<double>(std::max(1, through.edges[k]));
    for (std::size_t k = 0; k < through.count; ++k) {
      const std::uint32_t l = through.loop[k];
      if (l == kNone || (only != nullptr && !(*only)[l])) continue;
      bool across = mean[k] < kDiagonal;
      if (through.count == 2 && mean[0] != mean[1]) across = mean[k] < mean[1 - k];
      LoopVotes& lv = votes[l];
      ++(across ? lv.circumferential : lv.axial);
      lv.cos_sum += mean[k];
    }
  };
  const auto goal = static_cast<int>(wanted);
  for (;;) {
    batch.clear();
    for (std::size_t l = 0; l < loops.size(); ++l) {
      LoopVotes& lv = votes[l];
      std::size_t index = 0;
      while (lv.decided() + lv.pending < goal && nextCandidate(l, loops[l].vertices.size(), wanted, lv.cursor, index)) {
        const std::uint32_t v = loops[l].vertices[index];
        if (queued[v]) continue;
        queued[v] = 1;
        batch.push_back(v);
        queueVertex(v, nullptr);
      }
    }
    if (batch.empty()) break;
    testBatch();
    for (LoopVotes& lv : votes) lv.pending = 0;
    for (const std::size_t i : batch) {
      if (out.measured[i]) vote(i, raw[i], nullptr);
    }
  }

  // Loops left without a vote: their vertices vote with the principal direction of the axes over
  // their one-rings (everyVertex's smoothing), and only for such loops.
  std::vector<char> silent(loops.size(), 0);
  bool any = false;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    silent[l] = votes[l].decided() == 0 ? 1 : 0;
    votes[l].cursor = 0;
    any = any || silent[l];
  }
  std::vector<char> smoothed(any ? mesh.n_vertices() : 0, 0);
  std::vector<std::size_t> centres;
  while (any) {
    batch.clear();
    centres.clear();
    for (std::size_t l = 0; l < loops.size(); ++l) {
      LoopVotes& lv = votes[l];
      std::size_t index = 0;
      while (silent[l] && lv.decided() + lv.pending < goal && nextCandidate(l, loops[l].vertices.size(), wanted, lv.cursor, index)) {
        const std::uint32_t v = loops[l].vertices[index];
        if (smoothed[v]) continue;
        smoothed[v] = 1;
        centres.push_back(v);
        queueVertex(v, &silent);
        for (auto u : mesh.vv_range(VertexHandle(static_cast<int>(v)))) {
          const auto n = static_cast<std::size_t>(u.idx());
          if (queued[n]) continue;
          queued[n] = 1;
          batch.push_back(n);
        }
      }
    }
    if (centres.empty()) break;
    testBatch();
    for (LoopVotes& lv : votes) lv.pending = 0;
    for (const std::size_t c : centres) {
      out.axes[c] = ringAxis(mesh, c, raw, out.measured);
      if (glm::length(out.axes[c]) > 0.0) vote(c, out.axes[c], &silent);
    }
  }
  for (std::size_t e = 0; e < mesh.n_edges(); ++e) {
    const std::uint32_t l = edge_loop[e];
    if (l != kNone) out.edges[e] = decide(votes[l].circumferential, votes[l].axial, votes[l].cos_sum);
  }
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
  std::vector<int> ids(mesh.n_faces());
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = static_cast<int>(k);
  const Tree tree(ids.begin(), ids.end(), triangles.boxes.begin(), triangles.boxes.end());

  const AxisTest test{mesh, face_normals, triangles, tree, options};
  if (options.loop_samples > 0) {
    sampledLoops(test, static_cast<std::size_t>(options.loop_samples), out);
  } else {
    everyVertex(test, out);
  }
  countEdges(out);
  return out;
}

DirectedLoops directedEdgeLoops(const PolyMesh& mesh, const RayFanDirections& directions, std::size_t min_points) {
  DirectedLoops out;
  std::vector<EdgeLoop> loops = directions.loops.empty() ? edgeLoops(mesh) : directions.loops;
  for (EdgeLoop& loop : loops) {
    const std::size_t n = loop.vertices.size();
    const std::size_t segments = loop.edges.size();
    std::size_t around = 0;
    std::size_t along = 0;
    for (const std::uint32_t e : loop.edges) {
      const EdgeDirection d = e < directions.edges.size() ? directions.edges[e] : EdgeDirection::kUnknown;
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

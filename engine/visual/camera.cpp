// SPDX-License-Identifier: MIT
#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "../core/finite_vector.hpp"
#include "../core/number_text.hpp"
#include "../core/position_box.hpp"

namespace odeskin::visual {
namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// The azimuth-zero direction: the axis after up's dominant one (y -> z, z -> x, x -> y), made
// normal to up. With up = +y this is +z, the direction OBJ and glTF models usually face.
Vec3 referenceDirection(const Vec3& up) {
  const Vec3 a = glm::abs(up);
  Vec3 ref = a.y >= a.x && a.y >= a.z ? Vec3(0, 0, 1) : (a.z >= a.x ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
  return glm::normalize(ref - up * glm::dot(ref, up));
}

}  // namespace

Bounds boundsOf(std::span<const Vec3> points) {
  Bounds b;
  for (const Vec3& p : points) b.add(p);
  return b;
}

Status validateViewSpec(const ViewSpec& v) {
  if (!isFinite(v.up)) return invalidArgument("view: the up axis is not finite");
  for (const auto& [name, value] : {std::pair{"azimuth", v.azimuth_deg}, std::pair{"elevation", v.elevation_deg},
                                    std::pair{"field of view", v.fov_y_deg}, std::pair{"margin", v.margin}}) {
    if (!std::isfinite(value)) {
      return invalidArgument(std::string("view: ") + name + " " + numberText(value) + " is not a finite number");
    }
  }
  if (std::abs(glm::length(v.up) - 1.0) > 1e-6) return invalidArgument("view: the up axis must have unit length");
  if (std::abs(v.elevation_deg) >= 89.0) {
    return invalidArgument("view: elevation " + numberText(v.elevation_deg) + " must lie in (-89, 89) degrees");
  }
  if (!(v.fov_y_deg > 1.0 && v.fov_y_deg < 170.0)) {
    return invalidArgument("view: field of view " + numberText(v.fov_y_deg) + " must lie in (1, 170) degrees");
  }
  if (!(v.margin >= 0.0 && v.margin <= 0.45)) {
    return invalidArgument("view: margin " + numberText(v.margin) + " must lie in [0, 0.45]");
  }
  return okStatus();
}

glm::dmat4 Camera::projection() const {
  const double f = 1.0 / std::tan(0.5 * fov_y_rad);
  glm::dmat4 p(0.0);
  p[0][0] = f / aspect;
  p[1][1] = -f;
  p[2][2] = far / (near - far);
  p[2][3] = -1.0;
  p[3][2] = near * far / (near - far);
  return p;
}

Vec3 Camera::position() const {
  const glm::dmat4 world = glm::inverse(view);
  return Vec3(world[3]);
}

Vec3 viewDirection(const ViewSpec& view) {
  const Vec3 ref = referenceDirection(view.up);
  const Vec3 side = glm::cross(view.up, ref);
  // Turns are whole first (fmod is exact): 1e308 degrees in radians overflowed to inf, and the
  // camera's cos/sin to NaN.
  const double az = radians(std::fmod(view.azimuth_deg, 360.0));
  const double el = radians(view.elevation_deg);
  const Vec3 horizontal = std::cos(az) * ref + std::sin(az) * side;
  return glm::normalize(std::cos(el) * horizontal + std::sin(el) * view.up);
}

namespace {

// The camera frame for `view`: dir towards the camera, right and up across the image.
struct ViewBasis {
  Vec3 dir;
  Vec3 right;
  Vec3 up;
};

ViewBasis viewBasis(const ViewSpec& view) {
  ViewBasis b;
  b.dir = viewDirection(view);
  b.right = glm::normalize(glm::cross(-b.dir, view.up));
  b.up = glm::cross(b.right, -b.dir);
  return b;
}

Status checkFraming(std::span<const Vec3> points, double aspect, const ViewSpec& view) {
  if (points.empty()) return invalidArgument("view: nothing to frame (no vertices)");
  if (!(aspect > 0.0 && std::isfinite(aspect))) return invalidArgument("view: the image aspect must be positive");
  // A camera for points too far apart for their squared distances would stand at infinity.
  ODESKIN_TRY(checkedPositionBox(points, "view").status());
  return validateViewSpec(view);
}

// Points that all coincide get a unit box's corners instead, so there is something to frame.
std::vector<Vec3> framable(std::span<const Vec3> points) {
  const Bounds b = boundsOf(points);
  if (b.diagonal() > 0.0) return {points.begin(), points.end()};
  std::vector<Vec3> corners;
  corners.reserve(8);
  for (int c = 0; c < 8; ++c) {
    corners.push_back(b.min + Vec3((c & 1) - 0.5, ((c >> 1) & 1) - 0.5, ((c >> 2) & 1) - 0.5));
  }
  return corners;
}

// A camera at `eye` looking along -basis.dir, with near and far planes around the points.
Camera cameraAt(const Vec3& eye, const ViewBasis& basis, std::span<const Vec3> points, double aspect,
                const ViewSpec& view) {
  double nearest = 1e300;
  double farthest = 0.0;
  for (const Vec3& p : points) {
    const double depth = glm::dot(eye - p, basis.dir);
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  Camera camera;
  // The view turns before it moves: a target at eye - dir is eye itself once eye is much longer
  // than 1 (1e16 times), and glm::lookAt would then look nowhere.
  camera.view = glm::translate(glm::lookAt(Vec3(0.0), -basis.dir, view.up), -eye);
  camera.fov_y_rad = radians(view.fov_y_deg);
  camera.aspect = aspect;
  // Planes just outside the points: tight planes keep depth precision.
  camera.far = 1.05 * farthest;
  camera.near = std::max(0.9 * nearest, 1e-4 * camera.far);
  return camera;
}

}  // namespace

Result<Camera> framePoints(std::span<const Vec3> points, double aspect, const ViewSpec& view) {
  ODESKIN_TRY(checkFraming(points, aspect, view));
  const std::vector<Vec3> framed = framable(points);
  const ViewBasis basis = viewBasis(view);
  const double ty = std::tan(0.5 * radians(view.fov_y_deg)) * (1.0 - view.margin);
  const double tx = ty * aspect;
  // Per image axis a with half-angle tangent t: every point needs |a_i - c| <= t (d - z_i), i.e.
  // max(a_i + t z_i) - t d <= c <= min(a_i - t z_i) + t d. The smallest d makes both bounds meet.
  double x_hi = -1e300;
  double x_lo = 1e300;
  double y_hi = -1e300;
  double y_lo = 1e300;
  for (const Vec3& p : framed) {
    const double x = glm::dot(p, basis.right);
    const double y = glm::dot(p, basis.up);
    const double z = glm::dot(p, basis.dir);
    x_hi = std::max(x_hi, x + tx * z);
    x_lo = std::min(x_lo, x - tx * z);
    y_hi = std::max(y_hi, y + ty * z);
    y_lo = std::min(y_lo, y - ty * z);
  }
  const double d = std::max((x_hi - x_lo) / (2.0 * tx), (y_hi - y_lo) / (2.0 * ty));
  const Vec3 eye = 0.5 * (x_hi + x_lo) * basis.right + 0.5 * (y_hi + y_lo) * basis.up + d * basis.dir;
  return cameraAt(eye, basis, framed, aspect, view);
}

Result<std::vector<Camera>> turntableCameras(std::span<const Vec3> points, double aspect, const ViewSpec& view,
                                             std::span<const double> azimuths_deg) {
  ODESKIN_TRY(checkFraming(points, aspect, view));
  const std::vector<Vec3> framed = framable(points);
  const Vec3 centre = boundsOf(framed).centre();
  const double ty = std::tan(0.5 * radians(view.fov_y_deg)) * (1.0 - view.margin);
  const double tx = ty * aspect;
  // Looking at the centre: |a_i| <= t (d - z_i) for every point, so d >= |a_i| / t + z_i.
  double distance = 0.0;
  for (double azimuth : azimuths_deg) {
    ViewSpec turned = view;
    turned.azimuth_deg = std::fmod(view.azimuth_deg, 360.0) + azimuth;
    const ViewBasis basis = viewBasis(turned);
    for (const Vec3& p : framed) {
      const Vec3 q = p - centre;
      const double z = glm::dot(q, basis.dir);
      distance = std::max({distance, std::abs(glm::dot(q, basis.right)) / tx + z,
                           std::abs(glm::dot(q, basis.up)) / ty + z});
    }
  }
  std::vector<Camera> cameras;
  for (double azimuth : azimuths_deg) {
    ViewSpec turned = view;
    turned.azimuth_deg = std::fmod(view.azimuth_deg, 360.0) + azimuth;
    const ViewBasis basis = viewBasis(turned);
    cameras.push_back(cameraAt(centre + distance * basis.dir, basis, framed, aspect, turned));
  }
  return cameras;
}

Vec3 projectToPixel(const Camera& camera, const Vec3& world, double width, double height) {
  const glm::dvec4 clip = camera.projection() * camera.view * glm::dvec4(world, 1.0);
  const Vec3 ndc = Vec3(clip) / clip.w;
  // Vulkan's viewport transform: framebuffer x = (ndc.x + 1) w / 2, y = (ndc.y + 1) h / 2.
  return Vec3(0.5 * (ndc.x + 1.0) * width, 0.5 * (ndc.y + 1.0) * height, ndc.z);
}

}  // namespace odeskin::visual

// SPDX-License-Identifier: MIT
#include "camera.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

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
  const bool finite = std::isfinite(v.up.x) && std::isfinite(v.up.y) && std::isfinite(v.up.z) &&
                      std::isfinite(v.azimuth_deg) && std::isfinite(v.elevation_deg) && std::isfinite(v.fov_y_deg) &&
                      std::isfinite(v.margin);
  if (!finite) return invalidArgument("view: a camera setting is not a finite number");
  if (std::abs(glm::length(v.up) - 1.0) > 1e-6) return invalidArgument("view: the up axis must have unit length");
  if (std::abs(v.elevation_deg) >= 89.0) {
    return invalidArgument("view: elevation " + std::to_string(v.elevation_deg) + " must lie in (-89, 89) degrees");
  }
  if (!(v.fov_y_deg > 1.0 && v.fov_y_deg < 170.0)) {
    return invalidArgument("view: field of view " + std::to_string(v.fov_y_deg) + " must lie in (1, 170) degrees");
  }
  if (!(v.margin >= 0.0 && v.margin <= 0.45)) {
    return invalidArgument("view: margin " + std::to_string(v.margin) + " must lie in [0, 0.45]");
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
  const double az = radians(view.azimuth_deg);
  const double el = radians(view.elevation_deg);
  const Vec3 horizontal = std::cos(az) * ref + std::sin(az) * side;
  return glm::normalize(std::cos(el) * horizontal + std::sin(el) * view.up);
}

double framingDistance(const Bounds& bounds, double aspect, const ViewSpec& view) {
  const Vec3 dir = viewDirection(view);
  const Vec3 right = glm::normalize(glm::cross(-dir, view.up));
  const Vec3 up = glm::cross(right, -dir);
  const double ty = std::tan(0.5 * radians(view.fov_y_deg)) * (1.0 - 2.0 * view.margin);
  const double tx = ty * aspect;
  const Vec3 centre = bounds.centre();
  double distance = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                 (corner & 4) ? bounds.max.z : bounds.min.z);
    const Vec3 q = c - centre;
    // A corner at depth (distance - q.dir) in front of the camera projects inside when
    // |q.right| <= tx depth and |q.up| <= ty depth.
    const double toward = glm::dot(q, dir);
    distance = std::max({distance, std::abs(glm::dot(q, right)) / tx + toward, std::abs(glm::dot(q, up)) / ty + toward});
  }
  return distance;
}

Camera orbitCamera(const Vec3& target, double distance, double radius, double aspect, const ViewSpec& view) {
  Camera camera;
  const Vec3 eye = target + distance * viewDirection(view);
  camera.view = glm::lookAt(eye, target, view.up);
  camera.fov_y_rad = radians(view.fov_y_deg);
  camera.aspect = aspect;
  // Planes just outside the sphere holding the model: tight planes keep depth precision.
  camera.near = std::max(distance - 1.05 * radius, 1e-3 * distance);
  camera.far = distance + 1.05 * radius;
  return camera;
}

Result<Camera> frameBounds(const Bounds& bounds, double aspect, const ViewSpec& view) {
  if (bounds.empty()) return invalidArgument("view: nothing to frame (no vertices)");
  if (!(aspect > 0.0 && std::isfinite(aspect))) return invalidArgument("view: the image aspect must be positive");
  ODESKIN_TRY(validateViewSpec(view));
  Bounds box = bounds;
  if (box.diagonal() == 0.0) {
    box.add(bounds.min - Vec3(0.5));
    box.add(bounds.max + Vec3(0.5));
  }
  return orbitCamera(box.centre(), framingDistance(box, aspect, view), 0.5 * box.diagonal(), aspect, view);
}

Vec3 projectToPixel(const Camera& camera, const Vec3& world, double width, double height) {
  const glm::dvec4 clip = camera.projection() * camera.view * glm::dvec4(world, 1.0);
  const Vec3 ndc = Vec3(clip) / clip.w;
  // Vulkan's viewport transform: framebuffer x = (ndc.x + 1) w / 2, y = (ndc.y + 1) h / 2.
  return Vec3(0.5 * (ndc.x + 1.0) * width, 0.5 * (ndc.y + 1.0) * height, ndc.z);
}

}  // namespace odeskin::visual

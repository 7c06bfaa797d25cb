// SPDX-License-Identifier: MIT
// The fixed camera of odeskin's pictures: an orbit around a bounding box (azimuth about an up axis,
// elevation above the horizon), a perspective projection for Vulkan's clip space, and the distance
// that fits every corner of the box in the image. Double precision; the renderer receives floats.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "../core/result.hpp"
#include "../core/types.hpp"

namespace odeskin::visual {

// Axis-aligned bounding box; empty (min > max) until a point is added.
struct Bounds {
  Vec3 min{1e300};
  Vec3 max{-1e300};

  void add(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void add(const Bounds& b) {
    if (b.empty()) return;
    add(b.min);
    add(b.max);
  }
  bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
  Vec3 centre() const { return 0.5 * (min + max); }
  double diagonal() const { return empty() ? 0.0 : glm::length(max - min); }
};

Bounds boundsOf(std::span<const Vec3> points);

// Where the camera stands. Azimuth turns about `up` (right-handed), measured from the reference
// direction: +z for up = +y, +x for up = +z, +y for up = +x (each the next axis after up's). Elevation
// raises the camera above the plane normal to `up`.
struct ViewSpec {
  Vec3 up{0.0, 1.0, 0.0};      // unit: one of +-x, +-y, +-z, or any unit vector
  double azimuth_deg = 30.0;
  double elevation_deg = 15.0;  // in (-90, 90)
  double fov_y_deg = 30.0;      // vertical field of view, in (0, 180)
  double margin = 0.05;         // free border on each side, a fraction of the image's half extent
};

// kInvalidArgument naming the field: up not unit length (within 1e-6), |elevation| >= 89, field of
// view outside (1, 170) degrees, margin outside [0, 0.45], a non-finite value.
Status validateViewSpec(const ViewSpec& view);

struct Camera {
  glm::dmat4 view{1.0};   // view from world: rigid, camera at the origin looking down -z, +y up
  double fov_y_rad = 0.5;
  double aspect = 1.0;    // width / height
  double near = 0.1;
  double far = 10.0;

  // Clip from view for Vulkan: y points down the image (so world up is drawn up), depth runs from
  // 0 at `near` to 1 at `far`, right-handed view space. x_ndc = (f / aspect) x / -z, y_ndc = -f y / -z,
  // f = 1 / tan(fov_y / 2).
  glm::dmat4 projection() const;
  Vec3 position() const;  // camera centre in world space
};

// Unit direction from the box centre towards the camera for `view` (see ViewSpec for the angles).
Vec3 viewDirection(const ViewSpec& view);

// The smallest distance from bounds.centre() along viewDirection(view) at which every corner of
// `bounds` projects inside the image of aspect `aspect`, less the margin. Precondition: bounds not
// empty, view valid, aspect > 0.
double framingDistance(const Bounds& bounds, double aspect, const ViewSpec& view);

// The camera at `distance` from `target` along viewDirection(view), looking at target, with near
// and far planes that enclose a sphere of radius `radius` about target.
Camera orbitCamera(const Vec3& target, double distance, double radius, double aspect, const ViewSpec& view);

// orbitCamera at framingDistance: the picture's camera. kInvalidArgument for an empty box, a
// non-positive aspect, or validateViewSpec's errors. A box with no extent (one point) is framed as a
// box of size 1 around it.
Result<Camera> frameBounds(const Bounds& bounds, double aspect, const ViewSpec& view);

// A world point in pixels of a width x height image: x right, y down from the top left corner
// (pixel centres at +0.5), z the Vulkan depth in [0, 1] (outside when the point is behind near or
// beyond far). What the vertex shader does, so tests can predict where a mesh lands.
Vec3 projectToPixel(const Camera& camera, const Vec3& world, double width, double height);

}  // namespace odeskin::visual

// SPDX-License-Identifier: MIT
// The fixed camera of odeskin's pictures: an orbit around a bounding box (azimuth about an up axis,
// elevation above the horizon), a perspective projection for Vulkan's clip space, and the distance
// that fits every corner of the box in the image. Double precision; the renderer receives floats.
#pragma once

#include <span>
#include <vector>

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
  double margin = 0.08;         // free border on each side, a fraction of the image's half extent
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

// Unit direction from the model towards the camera for `view` (see ViewSpec for the angles).
Vec3 viewDirection(const ViewSpec& view);

// The tightest camera looking along -viewDirection(view) that keeps every point inside the image
// of aspect `aspect` less the margin: the distance and the sideways shift that centre the points'
// projection are solved exactly (per image axis, |x - c| <= tan(fov / 2) (d - z) for all points is
// a pair of linear bounds on d and c). Near and far planes enclose the points. kInvalidArgument for
// no points, a non-positive aspect, or validateViewSpec's errors. Points that all coincide are
// framed as a unit box around them.
Result<Camera> framePoints(std::span<const Vec3> points, double aspect, const ViewSpec& view);

// A turntable: one camera per azimuth offset (degrees added to view.azimuth_deg), each looking at
// the centre of the points' bounding box from the same distance, the smallest that frames the
// points from every one of them, so the model turns in place without changing size. Errors as
// framePoints'; an empty `azimuths_deg` gives no cameras.
Result<std::vector<Camera>> turntableCameras(std::span<const Vec3> points, double aspect, const ViewSpec& view,
                                             std::span<const double> azimuths_deg);

// A world point in pixels of a width x height image: x right, y down from the top left corner
// (pixel centres at +0.5), z the Vulkan depth in [0, 1] (outside when the point is behind near or
// beyond far). What the vertex shader does, so tests can predict where a mesh lands.
Vec3 projectToPixel(const Camera& camera, const Vec3& world, double width, double height);

}  // namespace odeskin::visual

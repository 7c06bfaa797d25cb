// SPDX-License-Identifier: MIT
// A whole picture from world-space meshes: every panel drawn by the offscreen renderer with one
// shared camera, then laid out and labelled on the CPU (visual::layoutPicture / composePicture).
// What `odeskin render` and `odeskin play --png` draw with.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.hpp"
#include "engine/core/types.hpp"
#include "engine/visual/camera.hpp"
#include "engine/visual/image.hpp"
#include "engine/visual/picture_layout.hpp"
#include "offscreen_renderer.hpp"

namespace odeskin::vk {

// One panel's content, in world space; spans must stay valid during draw().
struct PanelContent {
  std::span<const Vec3> positions;
  std::span<const Vec3> normals;               // unit, one per position (visual::vertexNormals)
  std::span<const std::uint32_t> triangles;    // 3 per triangle (visual::triangulateFaces)
  std::span<const double> heat;                // per vertex error / box diagonal; empty: clay colour
  std::span<const Vec3> curve_endpoints;       // 2 per segment (visual::curveSegments)
  std::span<const std::uint32_t> curve_ids;    // 1 per segment: picks visual::curveColour (a curve or part)
  std::vector<std::string> label;              // lines under the panel (layout.label_lines shown)
};

struct PictureStyle {
  visual::Rgba8 background{247, 247, 249, 255};
  visual::Rgba8 ink{40, 40, 46, 255};          // labels and colour bar
  glm::vec3 base_colour{0.80f, 0.79f, 0.76f};  // clay
  float curve_width_px = 0.0f;                 // 0: about 0.45% of the panel height, at least 1.5
  std::uint32_t samples = 4;                   // multisampling
};

class PictureRenderer {
 public:
  // `device` must outlive the renderer. OffscreenRenderer::create's errors.
  static Result<PictureRenderer> create(const Device& device, const PictureStyle& style);

  // Draws the panels with `camera` (built for layout.panel_width / panel_height) and composes the
  // picture. Curves are pulled towards the camera by 0.2% of `scene_size` (the framed box's
  // diagonal) so they sit on the surface. kInvalidArgument when panels.size() differs from the
  // layout's panel count, or for inconsistent panel spans; the renderer's errors.
  Result<visual::Image> draw(const visual::PictureLayout& layout, const visual::Camera& camera, double scene_size,
                             std::span<const PanelContent> panels);

  const PictureStyle& style() const { return style_; }
  // Samples per pixel of the last draw: style().samples lowered to what the device offers (0 before
  // the first draw).
  std::uint32_t samples() const { return renderer_.width() == 0 ? 0 : renderer_.samples(); }

 private:
  const Device* device_ = nullptr;
  PictureStyle style_;
  OffscreenRenderer renderer_;  // rebuilt when the panel size changes
};

}  // namespace odeskin::vk

// SPDX-License-Identifier: MIT
// Draws view-space surfaces and curves into an offscreen image and reads it back: no window, no
// swapchain, so it runs headless on lavapipe. One command buffer per frame: render pass (clear,
// surfaces, curves, multisample resolve), copy to a host-visible buffer, wait on a fence.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/result.hpp"
#include "engine/visual/image.hpp"
#include "engine/visual/render_shading.hpp"
#include "host/device.hpp"
#include "render_pipelines.hpp"
#include "render_target.hpp"

namespace odeskin::vk {

struct RendererOptions {
  std::uint32_t width = 512;   // pixels, >= 1
  std::uint32_t height = 512;  // pixels, >= 1
  std::uint32_t samples = 4;   // multisampling; lowered to what the device supports (1: none)
};

// One triangle mesh in view space.
struct SurfaceDraw {
  std::span<const visual::SurfaceVertex> vertices;
  std::span<const std::uint32_t> triangles;  // 3 per triangle, each < vertices.size()
  glm::vec3 base_colour{0.8f};               // used when heat is false
  bool heat = false;                         // colour = heatColour(value / heat_max)
  float heat_max = 1.0f;                     // > 0 when heat is true
};

// Line segments in view space, drawn as bands of constant pixel width.
struct CurveDraw {
  std::span<const glm::vec3> endpoints;  // 2 per segment
  std::span<const glm::vec3> colours;    // 1 per segment
  float width_px = 2.0f;                 // > 0
  float depth_offset = 0.0f;             // >= 0: view-space pull towards the camera (render_shading.h)
};

struct FrameDraw {
  glm::mat4 projection{1.0f};  // clip from view (visual::Camera::projection)
  std::vector<SurfaceDraw> surfaces;
  std::vector<CurveDraw> curves;
};

class OffscreenRenderer {
 public:
  // `device` must outlive the renderer. kUnavailable when the device's queue cannot draw (no
  // graphics bit) and RenderTarget/RenderPipelines' errors.
  static Result<OffscreenRenderer> create(const Device& device, const RendererOptions& options);

  OffscreenRenderer() = default;
  OffscreenRenderer(OffscreenRenderer&&) noexcept = default;
  OffscreenRenderer& operator=(OffscreenRenderer&&) noexcept = default;

  std::uint32_t width() const { return target_.width(); }
  std::uint32_t height() const { return target_.height(); }
  std::uint32_t samples() const { return static_cast<std::uint32_t>(target_.samples()); }

  // Draws `frame` and returns its pixels, premultiplied by coverage: transparent black where
  // nothing was drawn (visual::overBackground puts a background behind). kInvalidArgument naming
  // the draw: a triangle index out of range, a triangle count not a multiple of 3, colours not one
  // per segment, a non-positive heat_max or line width; kDeviceError from the driver.
  Result<visual::Image> render(const FrameDraw& frame);

 private:
  const Device* device_ = nullptr;
  RenderTarget target_;
  RenderPipelines pipelines_;
};

// Six curve-pipeline vertices per segment (two triangles of a screen-space quad), as
// curve_vertex.vert expects them. Preconditions as CurveDraw's.
std::vector<visual::CurveVertex> curveVertices(const CurveDraw& curves);

}  // namespace odeskin::vk

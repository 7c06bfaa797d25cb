// SPDX-License-Identifier: MIT
// What `odeskin render` and `odeskin play --png` share: a Vulkan device with the picture renderer,
// mesh geometry prepared for drawing, the camera that frames a set of meshes, and option parsing
// for sizes, colours and numbered file names.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/iso_curve.hpp"
#include "engine/core/result.hpp"
#include "engine/visual/camera.hpp"
#include "engine/visual/image.hpp"
#include "host/render/picture_renderer.hpp"

namespace odeskin {

namespace vk {
struct Gpu;
}

// A mesh ready for PanelContent: its triangles, normals, curve segments, and the heat it shows.
struct PanelGeometry {
  std::vector<Vec3> positions;
  std::vector<std::uint32_t> triangles;
  std::vector<Vec3> normals;
  std::vector<Vec3> curve_endpoints;
  std::vector<std::uint32_t> curve_ids;
  std::vector<double> heat;  // empty: no heat map
  std::vector<std::string> label;

  // Spans into this object (which must outlive the result).
  vk::PanelContent content() const;
};

// triangulateFaces + vertexNormals, and the curves' segments when `curves` is given. Errors name
// `source` (a file): bad face indices, curve points out of range.
Result<PanelGeometry> preparePanel(const std::string& source, std::vector<Vec3> positions, const FaceList& faces,
                                   const std::vector<IsoCurve>* curves);

class RenderSession {
 public:
  // Opens the Vulkan device (`selector` as --device) with the validation layer when asked.
  // kUnavailable with a hint when no device opens (drawing needs one; there is no CPU fallback).
  static Result<RenderSession> open(const std::string& selector, bool validation, const vk::PictureStyle& style);

  RenderSession(RenderSession&&) noexcept;
  RenderSession& operator=(RenderSession&&) noexcept;
  ~RenderSession();

  Result<visual::Image> draw(const visual::PictureLayout& layout, const visual::Camera& camera, double scene_size,
                             std::span<const vk::PanelContent> panels);
  std::string deviceName() const;
  // Samples per pixel of the last draw (the requested count lowered to what the device offers).
  std::uint32_t samples() const;
  // kInternal when the validation layer reported messages (the count and the first one).
  Status checkValidation() const;

 private:
  RenderSession() = default;
  std::unique_ptr<vk::Gpu> gpu_;  // heap-held: the renderer keeps a pointer to its device
  std::unique_ptr<vk::PictureRenderer> renderer_;
};

// "WxH" (e.g. 800x600; 'X' too), each side in [16, 8192]. kInvalidArgument quoting the text.
Result<std::pair<std::uint32_t, std::uint32_t>> parseImageSize(std::string_view text);

// "RRGGBB" or "#RRGGBB" hex. kInvalidArgument quoting the text.
Result<visual::Rgba8> parseColour(std::string_view text);

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "render_session.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "engine/visual/curve_lines.hpp"
#include "engine/visual/surface_mesh.hpp"
#include "host/device.hpp"

namespace odeskin {
namespace {

constexpr std::uint32_t kMinSide = 16;
constexpr std::uint32_t kMaxSide = 8192;

std::string quoted(std::string_view text) {
  std::string out(1, '\'');
  out.append(text).push_back('\'');
  return out;
}

}  // namespace

vk::PanelContent PanelGeometry::content() const {
  vk::PanelContent c;
  c.positions = positions;
  c.normals = normals;
  c.triangles = triangles;
  c.heat = heat;
  c.curve_endpoints = curve_endpoints;
  c.curve_ids = curve_ids;
  c.label = label;
  return c;
}

Result<PanelGeometry> preparePanel(const std::string& source, std::vector<Vec3> positions, const FaceList& faces,
                                   const std::vector<IsoCurve>* curves) {
  PanelGeometry g;
  Result<std::vector<std::uint32_t>> triangles = visual::triangulateFaces(faces, positions.size());
  if (!triangles.ok()) return Status(triangles.status().code(), source + ": " + triangles.status().message());
  g.triangles = std::move(triangles).value();
  g.normals = visual::vertexNormals(positions, faces);
  if (curves != nullptr) {
    Result<visual::CurveSegments> segments = visual::curveSegments(*curves, positions);
    if (!segments.ok()) return Status(segments.status().code(), source + ": " + segments.status().message());
    g.curve_endpoints = std::move(segments->endpoints);
    // One colour per body part: the curves of a limb read as one family, as in the thesis's Fig. 6.7.
    g.curve_ids = std::move(segments->part_of_segment);
  }
  g.positions = std::move(positions);
  return g;
}

RenderSession::RenderSession(RenderSession&&) noexcept = default;
RenderSession& RenderSession::operator=(RenderSession&&) noexcept = default;
RenderSession::~RenderSession() {
  renderer_.reset();  // before the device it points at
  gpu_.reset();
}

Result<RenderSession> RenderSession::open(const std::string& selector, bool validation, const vk::PictureStyle& style) {
  Result<vk::Gpu> gpu = vk::Gpu::open(selector, validation);
  if (!gpu.ok()) {
    if (gpu.status().code() == StatusCode::kUnavailable) {
      return unavailable("drawing needs a Vulkan device and none opened (" + gpu.status().message() +
                         "); on a machine without a GPU install mesa-vulkan-drivers for lavapipe");
    }
    return gpu.status();
  }
  RenderSession session;
  session.gpu_ = std::make_unique<vk::Gpu>(std::move(gpu).value());
  ODESKIN_ASSIGN_OR_RETURN(vk::PictureRenderer renderer, vk::PictureRenderer::create(session.gpu_->device, style));
  session.renderer_ = std::make_unique<vk::PictureRenderer>(std::move(renderer));
  return session;
}

Result<visual::Image> RenderSession::draw(const visual::PictureLayout& layout, const visual::Camera& camera,
                                          double scene_size, std::span<const vk::PanelContent> panels) {
  return renderer_->draw(layout, camera, scene_size, panels);
}

std::string RenderSession::deviceName() const { return gpu_->device.name(); }

std::uint32_t RenderSession::samples() const { return renderer_->samples(); }

Status RenderSession::checkValidation() const {
  if (!gpu_->instance.validationEnabled() || gpu_->instance.debugLog().count() == 0) return okStatus();
  return internalError("the Vulkan validation layer reported " + std::to_string(gpu_->instance.debugLog().count()) +
                       " message(s); first: " + gpu_->instance.debugLog().messages().front());
}

Result<std::pair<std::uint32_t, std::uint32_t>> parseImageSize(std::string_view text) {
  const std::size_t x = text.find_first_of("xX");
  std::uint32_t w = 0;
  std::uint32_t h = 0;
  bool ok = x != std::string_view::npos && x > 0 && x + 1 < text.size();
  if (ok) {
    const std::string_view a = text.substr(0, x);
    const std::string_view b = text.substr(x + 1);
    const auto ra = std::from_chars(a.data(), a.data() + a.size(), w);
    const auto rb = std::from_chars(b.data(), b.data() + b.size(), h);
    ok = ra.ec == std::errc() && ra.ptr == a.data() + a.size() && rb.ec == std::errc() && rb.ptr == b.data() + b.size();
  }
  if (!ok) return invalidArgument("--size " + quoted(text) + " must be WIDTHxHEIGHT in pixels, e.g. 800x600");
  if (w < kMinSide || h < kMinSide || w > kMaxSide || h > kMaxSide) {
    return invalidArgument("--size " + quoted(text) + ": each side must lie in [16, 8192] pixels");
  }
  return std::pair{w, h};
}

Result<visual::Rgba8> parseColour(std::string_view text) {
  std::string_view hex = text;
  if (!hex.empty() && hex.front() == '#') hex.remove_prefix(1);
  std::uint32_t value = 0;
  const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), value, 16);
  if (hex.size() != 6 || r.ec != std::errc() || r.ptr != hex.data() + hex.size()) {
    return invalidArgument("colour " + quoted(text) + " must be RRGGBB in hex, e.g. f7f7f9");
  }
  return visual::Rgba8{static_cast<std::uint8_t>(value >> 16), static_cast<std::uint8_t>(value >> 8),
                       static_cast<std::uint8_t>(value), 255};
}

}  // namespace odeskin

// SPDX-License-Identifier: MIT
#include "picture_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/visual/curve_lines.hpp"
#include "engine/visual/view_geometry.hpp"

namespace odeskin::vk {
namespace {

Status validatePanel(const PanelContent& p, std::size_t index) {
  const std::string name = "picture: panel " + std::to_string(index);
  if (p.normals.size() != p.positions.size()) return invalidArgument(name + ": need one normal per position");
  if (!p.heat.empty() && p.heat.size() != p.positions.size()) {
    return invalidArgument(name + ": need one heat value per position");
  }
  if (p.curve_endpoints.size() != 2 * p.curve_ids.size()) {
    return invalidArgument(name + ": need one curve id per segment (two endpoints)");
  }
  return okStatus();
}

}  // namespace

Result<PictureRenderer> PictureRenderer::create(const Device& device, const PictureStyle& style) {
  PictureRenderer out;
  out.device_ = &device;
  out.style_ = style;
  return out;
}

Result<visual::Image> PictureRenderer::draw(const visual::PictureLayout& layout, const visual::Camera& camera,
                                            double scene_size, std::span<const PanelContent> panels) {
  if (panels.size() != layout.panel_left.size()) {
    return invalidArgument("picture: " + std::to_string(panels.size()) + " panels for a layout of " +
                           std::to_string(layout.panel_left.size()));
  }
  for (std::size_t i = 0; i < panels.size(); ++i) ODESKIN_TRY(validatePanel(panels[i], i));
  if (!(camera.far > 0.0 && std::isfinite(camera.far))) {
    return invalidArgument("picture: the camera's far plane must be positive and finite");
  }
  if (renderer_.width() != layout.panel_width || renderer_.height() != layout.panel_height) {
    ODESKIN_ASSIGN_OR_RETURN(renderer_, OffscreenRenderer::create(*device_, {layout.panel_width, layout.panel_height,
                                                                             style_.samples}));
  }
  const float curve_width = style_.curve_width_px > 0.0f
                                ? style_.curve_width_px
                                : std::max(1.5f, 0.0045f * static_cast<float>(layout.panel_height));
  const float heat_max = static_cast<float>(layout.heat_max.value_or(1.0));

  // The GPU draws in float, which holds neither a mesh 1e150 across nor one 1e-150 across: view
  // space is divided by the far plane's depth first (in double). Scaling view space and both clip
  // planes together leaves the picture as it was.
  const double unit = 1.0 / camera.far;
  const glm::dmat4 view = glm::scale(glm::dmat4(1.0), glm::dvec3(unit)) * camera.view;
  visual::Camera scaled = camera;
  scaled.near *= unit;
  scaled.far = 1.0;

  std::vector<visual::Image> images;
  std::vector<std::vector<std::string>> labels;
  for (const PanelContent& panel : panels) {
    const std::vector<visual::SurfaceVertex> vertices =
        visual::surfaceVertices(view, panel.positions, panel.normals, panel.heat);
    const std::vector<glm::vec3> endpoints = visual::viewPoints(view, panel.curve_endpoints);
    std::vector<glm::vec3> colours;
    colours.reserve(panel.curve_ids.size());
    for (std::uint32_t id : panel.curve_ids) colours.push_back(visual::curveColour(id));

    FrameDraw frame;
    frame.projection = glm::mat4(scaled.projection());
    SurfaceDraw surface;
    surface.vertices = vertices;
    surface.triangles = panel.triangles;
    surface.base_colour = style_.base_colour;
    surface.heat = !panel.heat.empty();
    surface.heat_max = heat_max;
    frame.surfaces.push_back(surface);
    if (!endpoints.empty()) {
      frame.curves.push_back(
          CurveDraw{endpoints, colours, curve_width, static_cast<float>(0.002 * scene_size * unit)});
    }
    ODESKIN_ASSIGN_OR_RETURN(visual::Image image, renderer_.render(frame));
    images.push_back(std::move(image));
    labels.push_back(panel.label);
  }
  return visual::composePicture(layout, images, labels, style_.background, style_.ink);
}

}  // namespace odeskin::vk

// SPDX-License-Identifier: MIT
#include "offscreen_renderer.hpp"

#include <array>
#include <string>

#include "host/buffer.hpp"
#include "host/vk_status.hpp"

namespace odeskin::vk {
namespace {

Status validateFrame(const FrameDraw& frame) {
  for (std::size_t s = 0; s < frame.surfaces.size(); ++s) {
    const SurfaceDraw& d = frame.surfaces[s];
    const std::string name = "renderer: surface " + std::to_string(s);
    if (d.triangles.size() % 3 != 0) return invalidArgument(name + ": index count is not a multiple of 3");
    for (std::uint32_t index : d.triangles) {
      if (index >= d.vertices.size()) {
        return invalidArgument(name + ": index " + std::to_string(index) + " >= vertex count " +
                               std::to_string(d.vertices.size()));
      }
    }
    if (d.heat && !(d.heat_max > 0.0f)) return invalidArgument(name + ": heat_max must be positive");
  }
  for (std::size_t c = 0; c < frame.curves.size(); ++c) {
    const CurveDraw& d = frame.curves[c];
    const std::string name = "renderer: curves " + std::to_string(c);
    if (d.endpoints.size() % 2 != 0) return invalidArgument(name + ": endpoints must come in pairs");
    if (d.colours.size() != d.endpoints.size() / 2) return invalidArgument(name + ": need one colour per segment");
    if (!(d.width_px > 0.0f)) return invalidArgument(name + ": width_px must be positive");
    if (!(d.depth_offset >= 0.0f)) return invalidArgument(name + ": depth_offset must be zero or positive");
  }
  return okStatus();
}

template <typename T>
Result<Buffer> uploadBuffer(const Device& device, std::span<const T> data, VkBufferUsageFlags usage) {
  ODESKIN_ASSIGN_OR_RETURN(Buffer buffer, Buffer::create(device, data.size_bytes(), usage));
  ODESKIN_TRY(uploadSpan(device, buffer, data));
  return buffer;
}

}  // namespace

std::vector<visual::CurveVertex> curveVertices(const CurveDraw& curves) {
  std::vector<visual::CurveVertex> out;
  out.reserve(3 * curves.endpoints.size());
  for (std::size_t s = 0; 2 * s + 1 < curves.endpoints.size(); ++s) {
    const glm::vec3 a = curves.endpoints[2 * s];
    const glm::vec3 b = curves.endpoints[2 * s + 1];
    const glm::vec3 c = curves.colours[s];
    // Seen from b the segment runs the other way, so the same side of the band has the other sign.
    auto vertex = [&c](const glm::vec3& here, const glm::vec3& there, float side) {
      return visual::CurveVertex{{here.x, here.y, here.z}, {there.x, there.y, there.z}, side, {c.r, c.g, c.b}};
    };
    const visual::CurveVertex a_left = vertex(a, b, 1.0f);
    const visual::CurveVertex a_right = vertex(a, b, -1.0f);
    const visual::CurveVertex b_left = vertex(b, a, -1.0f);
    const visual::CurveVertex b_right = vertex(b, a, 1.0f);
    for (const visual::CurveVertex& v : {a_left, a_right, b_left, a_right, b_right, b_left}) out.push_back(v);
  }
  return out;
}

Result<OffscreenRenderer> OffscreenRenderer::create(const Device& device, const RendererOptions& options) {
  if (!(device.queueFlags() & VK_QUEUE_GRAPHICS_BIT)) {
    return unavailable(std::string("renderer: the queue odeskin uses on ") + device.name() + " cannot draw graphics");
  }
  OffscreenRenderer renderer;
  renderer.device_ = &device;
  const VkSampleCountFlagBits samples = chooseSampleCount(device, options.samples);
  ODESKIN_ASSIGN_OR_RETURN(renderer.target_, RenderTarget::create(device, options.width, options.height, samples));
  ODESKIN_ASSIGN_OR_RETURN(renderer.pipelines_, RenderPipelines::create(device, renderer.target_.renderPass(), samples));
  return renderer;
}

Result<visual::Image> OffscreenRenderer::render(const FrameDraw& frame) {
  ODESKIN_TRY(validateFrame(frame));
  const Device& device = *device_;

  // Geometry for this frame: small next to a frame's pixels, so it is uploaded fresh each time.
  struct SurfaceBuffers {
    Buffer vertices;
    Buffer indices;
    std::uint32_t index_count = 0;
    const SurfaceDraw* draw = nullptr;
  };
  std::vector<SurfaceBuffers> surfaces;
  for (const SurfaceDraw& d : frame.surfaces) {
    if (d.triangles.empty()) continue;
    SurfaceBuffers b;
    ODESKIN_ASSIGN_OR_RETURN(b.vertices, uploadBuffer(device, d.vertices, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
    ODESKIN_ASSIGN_OR_RETURN(b.indices, uploadBuffer(device, d.triangles, VK_BUFFER_USAGE_INDEX_BUFFER_BIT));
    b.index_count = static_cast<std::uint32_t>(d.triangles.size());
    b.draw = &d;
    surfaces.push_back(std::move(b));
  }
  struct CurveBuffers {
    Buffer vertices;
    std::uint32_t vertex_count = 0;
    const CurveDraw* draw = nullptr;
  };
  std::vector<CurveBuffers> curves;
  for (const CurveDraw& d : frame.curves) {
    if (d.endpoints.empty()) continue;
    const std::vector<visual::CurveVertex> vertices = curveVertices(d);
    CurveBuffers b;
    ODESKIN_ASSIGN_OR_RETURN(b.vertices, uploadBuffer(device, std::span<const visual::CurveVertex>(vertices),
                                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT));
    b.vertex_count = static_cast<std::uint32_t>(vertices.size());
    b.draw = &d;
    curves.push_back(std::move(b));
  }

  visual::RenderPushConstants push{};
  push.projection = frame.projection;
  push.viewport_width = static_cast<float>(width());
  push.viewport_height = static_cast<float>(height());

  ODESKIN_TRY(device.submitAndWait([&](VkCommandBuffer cmd) {
    // 1. Clear to transparent black and far depth.
    std::array<VkClearValue, 2> clear{};
    clear[0].color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    clear[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = target_.renderPass();
    begin.framebuffer = target_.framebuffer();
    begin.renderArea = {{0, 0}, {width(), height()}};
    begin.clearValueCount = static_cast<std::uint32_t>(clear.size());
    begin.pClearValues = clear.data();
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, push.viewport_width, push.viewport_height, 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {width(), height()}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    const VkDeviceSize zero = 0;

    // 2. Surfaces, each with its colour mode in the push block.
    if (!surfaces.empty()) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.surface());
    for (const SurfaceBuffers& s : surfaces) {
      push.base_colour = glm::vec4(s.draw->base_colour, 1.0f);
      push.shade_mode = s.draw->heat ? ODESKIN_SHADE_HEAT : ODESKIN_SHADE_BASE;
      push.heat_max = s.draw->heat ? s.draw->heat_max : 1.0f;
      vkCmdPushConstants(cmd, pipelines_.layout(), RenderPipelines::kPushStages, 0, sizeof push, &push);
      VkBuffer vertex_buffer = s.vertices.handle();
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &zero);
      vkCmdBindIndexBuffer(cmd, s.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
      vkCmdDrawIndexed(cmd, s.index_count, 1, 0, 0, 0);
    }

    // 3. Curves over them.
    if (!curves.empty()) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_.curves());
    for (const CurveBuffers& c : curves) {
      push.line_half_width = 0.5f * c.draw->width_px;
      push.line_depth_offset = c.draw->depth_offset;
      vkCmdPushConstants(cmd, pipelines_.layout(), RenderPipelines::kPushStages, 0, sizeof push, &push);
      VkBuffer vertex_buffer = c.vertices.handle();
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertex_buffer, &zero);
      vkCmdDraw(cmd, c.vertex_count, 1, 0, 0);
    }
    vkCmdEndRenderPass(cmd);

    // 4. Resolved pixels to the host-visible buffer.
    target_.recordReadback(cmd);
  }));
  return target_.pixels();
}

}  // namespace odeskin::vk

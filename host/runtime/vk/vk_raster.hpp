// An offscreen raster pipeline with its render pass: colour attachments (in order) and an
// optional depth attachment, all cleared on begin (colour to 0, depth to 1) and left in
// eTransferSrcOptimal at the end, ready for Image::record_copy_to. No window, no swapchain.
// Vertex data come from vertex buffers (per-vertex and per-instance bindings), parameters from
// vertex-stage push constants; viewport and scissor are dynamic state.
#pragma once

#include <string>
#include <vector>

#include "host/runtime/vk/vk_context.hpp"
#include "host/runtime/vk/vk_image.hpp"

namespace binpick::vkrt {

struct RasterSpec {
  std::string vertex_shader, fragment_shader;  // embedded SPIR-V names, e.g. "bin_mesh.vert"
  std::vector<vk::Format> color_formats;
  vk::Format depth_format = vk::Format::eUndefined;  // eUndefined: no depth attachment
  std::vector<vk::VertexInputBindingDescription> vertex_bindings;
  std::vector<vk::VertexInputAttributeDescription> vertex_attributes;
  std::uint32_t push_constant_bytes = 0;  // vertex stage
  vk::CullModeFlags cull = vk::CullModeFlagBits::eNone;
};

class RasterProgram {
 public:
  RasterProgram(Context& ctx, const RasterSpec& spec);
  RasterProgram(const RasterProgram&) = delete;
  RasterProgram& operator=(const RasterProgram&) = delete;

  // A framebuffer over the colour images (in spec order) then the depth image, if any.
  vk::raii::Framebuffer framebuffer(const std::vector<const Image*>& attachments) const;

  // Begins the render pass on `area` of `fb` (only that rectangle is cleared and drawn),
  // binds the pipeline, pushes `push`, and sets viewport and scissor to `area`.
  void begin(const vk::raii::CommandBuffer& cmd, vk::Framebuffer fb, vk::Rect2D area,
             const void* push) const;
  void end(const vk::raii::CommandBuffer& cmd) const { cmd.endRenderPass(); }

 private:
  Context& ctx_;
  RasterSpec spec_;
  vk::raii::ShaderModule vertex_{nullptr}, fragment_{nullptr};
  vk::raii::RenderPass render_pass_{nullptr};
  vk::raii::PipelineLayout layout_{nullptr};
  vk::raii::Pipeline pipeline_{nullptr};
};

}  // namespace binpick::vkrt

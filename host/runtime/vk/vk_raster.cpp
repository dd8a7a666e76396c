#include "host/runtime/vk/vk_raster.hpp"

#include <array>

#include "host/core/error.hpp"
#include "host/runtime/embedded.hpp"

namespace binpick::vkrt {
namespace {

vk::raii::ShaderModule load_module(Context& ctx, const std::string& name) {
  const auto spirv = embedded::shader_spirv(name);
  return ctx.device().createShaderModule(
      {.codeSize = spirv.size() * sizeof(std::uint32_t), .pCode = spirv.data()});
}

vk::raii::RenderPass make_render_pass(Context& ctx, const RasterSpec& spec) {
  const bool has_depth = spec.depth_format != vk::Format::eUndefined;
  std::vector<vk::AttachmentDescription> attachments;
  std::vector<vk::AttachmentReference> color_refs;
  for (vk::Format f : spec.color_formats) {
    color_refs.push_back({.attachment = std::uint32_t(attachments.size()),
                          .layout = vk::ImageLayout::eColorAttachmentOptimal});
    attachments.push_back({.format = f,
                           .samples = vk::SampleCountFlagBits::e1,
                           .loadOp = vk::AttachmentLoadOp::eClear,
                           .storeOp = vk::AttachmentStoreOp::eStore,
                           .stencilLoadOp = vk::AttachmentLoadOp::eDontCare,
                           .stencilStoreOp = vk::AttachmentStoreOp::eDontCare,
                           .initialLayout = vk::ImageLayout::eUndefined,
                           .finalLayout = vk::ImageLayout::eTransferSrcOptimal});
  }
  vk::AttachmentReference depth_ref{.attachment = std::uint32_t(attachments.size()),
                                    .layout = vk::ImageLayout::eDepthStencilAttachmentOptimal};
  if (has_depth)
    attachments.push_back({.format = spec.depth_format,
                           .samples = vk::SampleCountFlagBits::e1,
                           .loadOp = vk::AttachmentLoadOp::eClear,
                           .storeOp = vk::AttachmentStoreOp::eStore,
                           .stencilLoadOp = vk::AttachmentLoadOp::eDontCare,
                           .stencilStoreOp = vk::AttachmentStoreOp::eDontCare,
                           .initialLayout = vk::ImageLayout::eUndefined,
                           .finalLayout = vk::ImageLayout::eTransferSrcOptimal});
  vk::SubpassDescription subpass{.pipelineBindPoint = vk::PipelineBindPoint::eGraphics,
                                 .colorAttachmentCount = std::uint32_t(color_refs.size()),
                                 .pColorAttachments = color_refs.data(),
                                 .pDepthStencilAttachment = has_depth ? &depth_ref : nullptr};
  using S = vk::PipelineStageFlagBits;
  using A = vk::AccessFlagBits;
  const vk::PipelineStageFlags attachment_stages =
      S::eColorAttachmentOutput | S::eEarlyFragmentTests | S::eLateFragmentTests;
  const vk::AccessFlags attachment_writes =
      A::eColorAttachmentWrite | A::eDepthStencilAttachmentWrite | A::eDepthStencilAttachmentRead;
  std::array<vk::SubpassDependency, 2> deps{
      // The previous frame's copies read these images: finish them before clearing.
      vk::SubpassDependency{.srcSubpass = VK_SUBPASS_EXTERNAL, .dstSubpass = 0,
                            .srcStageMask = S::eTransfer, .dstStageMask = attachment_stages,
                            .srcAccessMask = {}, .dstAccessMask = attachment_writes},
      // The copies after the pass read what it wrote.
      vk::SubpassDependency{.srcSubpass = 0, .dstSubpass = VK_SUBPASS_EXTERNAL,
                            .srcStageMask = attachment_stages, .dstStageMask = S::eTransfer,
                            .srcAccessMask = attachment_writes, .dstAccessMask = A::eTransferRead}};
  return ctx.device().createRenderPass({.attachmentCount = std::uint32_t(attachments.size()),
                                        .pAttachments = attachments.data(),
                                        .subpassCount = 1,
                                        .pSubpasses = &subpass,
                                        .dependencyCount = std::uint32_t(deps.size()),
                                        .pDependencies = deps.data()});
}

}  // namespace

RasterProgram::RasterProgram(Context& ctx, const RasterSpec& spec) : ctx_(ctx), spec_(spec) {
  const std::string what = "creating raster pipeline " + spec.vertex_shader + " + " + spec.fragment_shader;
  try {
    vertex_ = load_module(ctx, spec.vertex_shader);
    fragment_ = load_module(ctx, spec.fragment_shader);
    render_pass_ = make_render_pass(ctx, spec);
    vk::PushConstantRange range{.stageFlags = vk::ShaderStageFlagBits::eVertex,
                                .offset = 0, .size = spec.push_constant_bytes};
    layout_ = ctx.device().createPipelineLayout(
        {.pushConstantRangeCount = spec.push_constant_bytes ? 1u : 0u, .pPushConstantRanges = &range});

    std::array<vk::PipelineShaderStageCreateInfo, 2> stages{
        vk::PipelineShaderStageCreateInfo{.stage = vk::ShaderStageFlagBits::eVertex,
                                          .module = *vertex_, .pName = "main"},
        vk::PipelineShaderStageCreateInfo{.stage = vk::ShaderStageFlagBits::eFragment,
                                          .module = *fragment_, .pName = "main"}};
    vk::PipelineVertexInputStateCreateInfo vertex_input{
        .vertexBindingDescriptionCount = std::uint32_t(spec.vertex_bindings.size()),
        .pVertexBindingDescriptions = spec.vertex_bindings.data(),
        .vertexAttributeDescriptionCount = std::uint32_t(spec.vertex_attributes.size()),
        .pVertexAttributeDescriptions = spec.vertex_attributes.data()};
    vk::PipelineInputAssemblyStateCreateInfo assembly{.topology = vk::PrimitiveTopology::eTriangleList};
    vk::PipelineViewportStateCreateInfo viewport{.viewportCount = 1, .scissorCount = 1};
    vk::PipelineRasterizationStateCreateInfo raster{.depthClampEnable = VK_FALSE,
                                                    .rasterizerDiscardEnable = VK_FALSE,
                                                    .polygonMode = vk::PolygonMode::eFill,
                                                    .cullMode = spec.cull,
                                                    .frontFace = vk::FrontFace::eCounterClockwise,
                                                    .depthBiasEnable = VK_FALSE,
                                                    .lineWidth = 1.0f};
    vk::PipelineMultisampleStateCreateInfo multisample{.rasterizationSamples = vk::SampleCountFlagBits::e1};
    const bool has_depth = spec.depth_format != vk::Format::eUndefined;
    vk::PipelineDepthStencilStateCreateInfo depth{.depthTestEnable = has_depth,
                                                  .depthWriteEnable = has_depth,
                                                  .depthCompareOp = vk::CompareOp::eLess};
    std::vector<vk::PipelineColorBlendAttachmentState> blend(
        spec.color_formats.size(),
        {.blendEnable = VK_FALSE,
         .colorWriteMask = vk::ColorComponentFlagBits::eR | vk::ColorComponentFlagBits::eG |
                           vk::ColorComponentFlagBits::eB | vk::ColorComponentFlagBits::eA});
    vk::PipelineColorBlendStateCreateInfo blending{.attachmentCount = std::uint32_t(blend.size()),
                                                   .pAttachments = blend.data()};
    std::array<vk::DynamicState, 2> dynamic_states{vk::DynamicState::eViewport, vk::DynamicState::eScissor};
    vk::PipelineDynamicStateCreateInfo dynamic{.dynamicStateCount = 2, .pDynamicStates = dynamic_states.data()};
    pipeline_ = ctx.device().createGraphicsPipeline(
        nullptr, {.stageCount = std::uint32_t(stages.size()),
                  .pStages = stages.data(),
                  .pVertexInputState = &vertex_input,
                  .pInputAssemblyState = &assembly,
                  .pViewportState = &viewport,
                  .pRasterizationState = &raster,
                  .pMultisampleState = &multisample,
                  .pDepthStencilState = has_depth ? &depth : nullptr,
                  .pColorBlendState = &blending,
                  .pDynamicState = &dynamic,
                  .layout = *layout_,
                  .renderPass = *render_pass_,
                  .subpass = 0});
  } catch (const vk::SystemError& e) {
    throw DeviceError("Vulkan: " + what + ": " + e.what());
  }
  ctx.check_validation(what);
}

vk::raii::Framebuffer RasterProgram::framebuffer(const std::vector<const Image*>& attachments) const {
  std::vector<vk::ImageView> views;
  for (const Image* image : attachments) views.push_back(image->view());
  if (attachments.empty()) throw DeviceError("a framebuffer needs at least one attachment");
  return ctx_.device().createFramebuffer({.renderPass = *render_pass_,
                                          .attachmentCount = std::uint32_t(views.size()),
                                          .pAttachments = views.data(),
                                          .width = attachments.front()->width(),
                                          .height = attachments.front()->height(),
                                          .layers = 1});
}

void RasterProgram::begin(const vk::raii::CommandBuffer& cmd, vk::Framebuffer fb, vk::Rect2D area,
                          const void* push) const {
  std::vector<vk::ClearValue> clears;
  for (std::size_t i = 0; i < spec_.color_formats.size(); ++i)
    clears.push_back(vk::ClearValue{.color = vk::ClearColorValue{.uint32 = std::array<std::uint32_t, 4>{0, 0, 0, 0}}});
  if (spec_.depth_format != vk::Format::eUndefined)
    clears.push_back(vk::ClearValue{.depthStencil = {.depth = 1.0f, .stencil = 0}});
  cmd.beginRenderPass({.renderPass = *render_pass_,
                       .framebuffer = fb,
                       .renderArea = area,
                       .clearValueCount = std::uint32_t(clears.size()),
                       .pClearValues = clears.data()},
                      vk::SubpassContents::eInline);
  cmd.bindPipeline(vk::PipelineBindPoint::eGraphics, *pipeline_);
  if (spec_.push_constant_bytes)
    (*cmd).pushConstants(*layout_, vk::ShaderStageFlagBits::eVertex, 0, spec_.push_constant_bytes, push);
  cmd.setViewport(0, vk::Viewport{.x = float(area.offset.x), .y = float(area.offset.y),
                                  .width = float(area.extent.width), .height = float(area.extent.height),
                                  .minDepth = 0.0f, .maxDepth = 1.0f});
  cmd.setScissor(0, area);
}

}  // namespace binpick::vkrt

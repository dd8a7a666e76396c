#include "host/runtime/vk/vk_compute.hpp"

#include "host/core/error.hpp"
#include "host/runtime/embedded.hpp"

namespace binpick::vkrt {

ComputeProgram::ComputeProgram(Context& ctx, const std::string& shader, std::uint32_t buffer_count,
                               std::uint32_t push_constant_bytes)
    : ctx_(ctx), name_(shader), buffer_count_(buffer_count), push_bytes_(push_constant_bytes) {
  const auto spirv = embedded::shader_spirv(shader);
  try {
    module_ = ctx.device().createShaderModule(
        {.codeSize = spirv.size() * sizeof(std::uint32_t), .pCode = spirv.data()});
    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    for (std::uint32_t i = 0; i < buffer_count; ++i)
      bindings.push_back({.binding = i,
                          .descriptorType = vk::DescriptorType::eStorageBuffer,
                          .descriptorCount = 1,
                          .stageFlags = vk::ShaderStageFlagBits::eCompute});
    set_layout_ = ctx.device().createDescriptorSetLayout(
        {.bindingCount = buffer_count, .pBindings = bindings.data()});
    vk::PushConstantRange range{.stageFlags = vk::ShaderStageFlagBits::eCompute,
                                .offset = 0, .size = push_constant_bytes};
    vk::DescriptorSetLayout raw_layout = *set_layout_;
    layout_ = ctx.device().createPipelineLayout(
        {.setLayoutCount = 1, .pSetLayouts = &raw_layout,
         .pushConstantRangeCount = push_constant_bytes ? 1u : 0u, .pPushConstantRanges = &range});
    pipeline_ = ctx.device().createComputePipeline(
        nullptr, {.stage = {.stage = vk::ShaderStageFlagBits::eCompute,
                            .module = *module_, .pName = "main"},
                  .layout = *layout_});
    vk::DescriptorPoolSize size{.type = vk::DescriptorType::eStorageBuffer,
                                .descriptorCount = std::max(buffer_count, 1u)};
    pool_ = ctx.device().createDescriptorPool(
        {.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
         .maxSets = 1, .poolSizeCount = 1, .pPoolSizes = &size});
  } catch (const vk::SystemError& e) {
    throw DeviceError("Vulkan: creating compute pipeline " + shader + ": " + e.what());
  }
  ctx.check_validation("creating compute pipeline " + shader);
}

void ComputeProgram::run(const std::vector<const Buffer*>& buffers, const void* push,
                         std::uint32_t groups_x, std::uint32_t groups_y) {
  if (buffers.size() != buffer_count_)
    throw DeviceError(name_ + " takes " + std::to_string(buffer_count_) + " buffers, got " +
                      std::to_string(buffers.size()));
  vk::DescriptorSetLayout raw_layout = *set_layout_;
  vk::raii::DescriptorSets sets(ctx_.device(), {.descriptorPool = *pool_,
                                                .descriptorSetCount = 1,
                                                .pSetLayouts = &raw_layout});
  std::vector<vk::DescriptorBufferInfo> infos;
  for (const Buffer* b : buffers) infos.push_back({.buffer = b->get(), .offset = 0, .range = VK_WHOLE_SIZE});
  std::vector<vk::WriteDescriptorSet> writes;
  for (std::uint32_t i = 0; i < buffer_count_; ++i)
    writes.push_back({.dstSet = *sets.front(), .dstBinding = i, .descriptorCount = 1,
                      .descriptorType = vk::DescriptorType::eStorageBuffer,
                      .pBufferInfo = &infos[i]});
  ctx_.device().updateDescriptorSets(writes, {});
  ctx_.submit_and_wait(
      [&](const vk::raii::CommandBuffer& cmd) {
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_);
        cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout_, 0, *sets.front(), {});
        if (push_bytes_)
          (*cmd).pushConstants(*layout_, vk::ShaderStageFlagBits::eCompute, 0, push_bytes_, push);
        if (groups_x && groups_y) cmd.dispatch(groups_x, groups_y, 1);
        // Make the shader's writes visible to the host reads that follow the fence.
        vk::MemoryBarrier to_host{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                  .dstAccessMask = vk::AccessFlagBits::eHostRead};
        cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader,
                            vk::PipelineStageFlagBits::eHost, {}, to_host, {}, {});
      },
      "running " + name_);
}

}  // namespace binpick::vkrt

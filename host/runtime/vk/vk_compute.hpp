// A compute shader with its pipeline: storage buffer i is bound at binding i (the argument
// position), push constants carry the parameters.
#pragma once

#include <string>
#include <vector>

#include "host/runtime/vk/vk_buffer.hpp"
#include "host/runtime/vk/vk_context.hpp"

namespace binpick::vkrt {

class ComputeProgram {
 public:
  // shader: the name of an embedded SPIR-V module, e.g. "depth_from_zbuffer.comp".
  ComputeProgram(Context& ctx, const std::string& shader, std::uint32_t buffer_count,
                 std::uint32_t push_constant_bytes);

  // Binds buffers[i] at binding i, pushes `push` and dispatches groups_x * groups_y groups.
  void run(const std::vector<const Buffer*>& buffers, const void* push, std::uint32_t groups_x,
           std::uint32_t groups_y = 1);

 private:
  Context& ctx_;
  std::string name_;
  std::uint32_t buffer_count_, push_bytes_;
  vk::raii::ShaderModule module_{nullptr};
  vk::raii::DescriptorSetLayout set_layout_{nullptr};
  vk::raii::PipelineLayout layout_{nullptr};
  vk::raii::Pipeline pipeline_{nullptr};
  vk::raii::DescriptorPool pool_{nullptr};
};

}  // namespace binpick::vkrt

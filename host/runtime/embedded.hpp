// Files embedded into the binary at build time (cmake/embed_files.cmake): OpenCL C sources and
// headers from kernels/, SPIR-V compiled from shaders/.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace binpick::embedded {

struct File {
  std::string_view name;  // file name without directory; SPIR-V without its ".spv" suffix
  std::span<const unsigned char> data;
};

std::span<const File> kernels();
std::span<const File> shaders();

// The text of kernels/NAME; throws DeviceError naming the file if it was not embedded.
std::string kernel_source(std::string_view name);
// The SPIR-V words of shaders/NAME (e.g. "depth_from_zbuffer.comp").
std::vector<std::uint32_t> shader_spirv(std::string_view name);

}  // namespace binpick::embedded

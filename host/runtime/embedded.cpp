#include "host/runtime/embedded.hpp"

#include <cstring>

#include "host/core/error.hpp"

namespace binpick::embedded {
namespace {

const File& find(std::span<const File> files, std::string_view name, const char* what) {
  for (const File& f : files)
    if (f.name == name) return f;
  throw DeviceError(std::string(what) + " '" + std::string(name) +
                    "' is not embedded in this binary (rebuild after adding it)");
}

}  // namespace

std::string kernel_source(std::string_view name) {
  const File& f = find(kernels(), name, "OpenCL source");
  return {reinterpret_cast<const char*>(f.data.data()), f.data.size()};
}

std::vector<std::uint32_t> shader_spirv(std::string_view name) {
  const File& f = find(shaders(), name, "SPIR-V shader");
  if (f.data.size() % 4 != 0) throw DeviceError("SPIR-V of '" + std::string(name) + "' is not whole words");
  std::vector<std::uint32_t> words(f.data.size() / 4);
  std::memcpy(words.data(), f.data.data(), f.data.size());
  return words;
}

}  // namespace binpick::embedded

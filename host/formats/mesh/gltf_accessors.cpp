#include "host/formats/mesh/gltf_accessors.hpp"

#include <string>

#include "host/core/error.hpp"
#include "host/formats/mesh/little_endian.hpp"

namespace binpick::gltf {
namespace {

// Where an accessor's elements are: element i starts at data + i * stride.
struct ElementView {
  const char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
};

ElementView view_of(const tinygltf::Model& model, int accessor_index, int expected_type,
                    const char* what) {
  const std::string name =
      std::string("glTF accessor ") + std::to_string(accessor_index) + " (" + what + ")";
  if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= model.accessors.size())
    throw InputError(name + " does not exist");
  const auto& accessor = model.accessors[accessor_index];
  if (accessor.sparse.isSparse) throw InputError(name + ": sparse accessors are not supported");
  if (accessor.type != expected_type) throw InputError(name + " has the wrong element type");
  if (accessor.bufferView < 0 ||
      static_cast<std::size_t>(accessor.bufferView) >= model.bufferViews.size())
    throw InputError(name + " has no valid bufferView");
  const auto& view = model.bufferViews[accessor.bufferView];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw InputError(name + ": its bufferView has no valid buffer");
  const auto& buffer = model.buffers[view.buffer].data;

  const int component_size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
  const int components = tinygltf::GetNumComponentsInType(accessor.type);
  if (component_size <= 0 || components <= 0) throw InputError(name + " has an invalid type");
  const std::size_t element_size = static_cast<std::size_t>(component_size) * components;
  const std::size_t stride = view.byteStride == 0 ? element_size : view.byteStride;
  if (stride < element_size) throw InputError(name + ": byteStride is smaller than an element");

  ElementView result{nullptr, stride, accessor.count};
  if (accessor.count == 0) return result;
  // All in 64 bits with overflow-safe ordering: the sizes come from the file.
  const std::uint64_t view_end = std::uint64_t{view.byteOffset} + view.byteLength;
  const std::uint64_t first = std::uint64_t{view.byteOffset} + accessor.byteOffset;
  if (accessor.count > (UINT64_MAX / 2) / stride || view_end > buffer.size() ||
      first + stride * (accessor.count - 1) + element_size > view_end)
    throw InputError(name + " reaches past the end of its buffer");
  result.data = reinterpret_cast<const char*>(buffer.data()) + first;
  return result;
}

}  // namespace

std::vector<Eigen::Vector3f> read_vec3(const tinygltf::Model& model, int accessor) {
  const auto view = view_of(model, accessor, TINYGLTF_TYPE_VEC3, "VEC3");
  if (model.accessors[accessor].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw InputError("glTF accessor " + std::to_string(accessor) +
                     ": only float positions and normals are supported (no quantized meshes)");
  std::vector<Eigen::Vector3f> result(view.count);
  for (std::size_t i = 0; i < view.count; ++i) {
    const char* element = view.data + i * view.stride;
    result[i] = {load_little_endian<float>(element), load_little_endian<float>(element + 4),
                 load_little_endian<float>(element + 8)};
  }
  return result;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int accessor) {
  const auto view = view_of(model, accessor, TINYGLTF_TYPE_SCALAR, "indices");
  std::vector<std::uint32_t> result(view.count);
  const int type = model.accessors[accessor].componentType;
  for (std::size_t i = 0; i < view.count; ++i) {
    const char* element = view.data + i * view.stride;
    switch (type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        result[i] = load_little_endian<std::uint8_t>(element);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        result[i] = load_little_endian<std::uint16_t>(element);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        result[i] = load_little_endian<std::uint32_t>(element);
        break;
      default:
        throw InputError("glTF accessor " + std::to_string(accessor) +
                         ": indices must be unsigned byte, short or int");
    }
  }
  return result;
}

}  // namespace binpick::gltf

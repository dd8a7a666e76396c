#include "host/detect/batch/detect_targets.hpp"

#include <fmt/format.h>

#include "host/core/error.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/bop/test_targets.hpp"
#include "host/train/model_store.hpp"

namespace binpick {

// The largest budget a detector takes (DetectParams::instances).
constexpr int kMaxInstances = 1000;

std::uint32_t DetectTargets::count(int scene_id, int im_id, int obj_id) const {
  const auto it = inst_count.find({scene_id, im_id, obj_id});
  return it == inst_count.end() ? 0 : it->second;
}

DetectTargets read_detect_targets(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(fmt::format("--targets {}: no such file", file.string()));
  DetectTargets t;
  t.file = file;
  const std::string bytes = read_file_bytes(file);
  t.checksum = checksum_hex(bytes);
  // The same parser as eval's, so that detect and eval agree on what a target list is.
  for (const bop::TestTarget& e : bop::parse_test_targets(bytes, file.string())) {
    if (e.inst_count == 0) continue;
    if (e.inst_count > kMaxInstances)
      throw InputError(fmt::format(
          "{}: scene {} image {} obj_id {} asks for {} instances; detection finds at most {}",
          file.string(), e.scene_id, e.im_id, e.obj_id, e.inst_count, kMaxInstances));
    t.inst_count[{e.scene_id, e.im_id, e.obj_id}] = std::uint32_t(e.inst_count);
  }
  return t;
}

}  // namespace binpick

#include "host/train/ppf_table.hpp"

#include <algorithm>
#include <string>

#include "host/runtime/cl/cl_buffer.hpp"
#include "host/core/error.hpp"
#include "host/core/timing.hpp"
#include "host/core/cloud_input.hpp"
#include "host/train/device_scan.hpp"

namespace binpick {
std::size_t PpfTable::distinct_keys() const {
  std::size_t count = 0;
  for (std::size_t k = 0; k + 1 < offsets.size(); ++k) count += offsets[k + 1] != offsets[k];
  return count;
}

std::size_t ppf_table_groups(std::size_t n, std::size_t n_keys, std::size_t cores) {
  // Two per core keep every core busy (every row pairs with all points: equal blocks are equal
  // work); more only add histograms to clear and scan, n_keys counters each (2 MiB at the
  // defaults: 31 groups took 40-50 ms of the bracket's training).
  return std::max<std::size_t>(1, std::min({n, 2 * std::max<std::size_t>(cores, 1), kPpfTableGroups,
                                            (std::size_t(1) << 24) / std::max<std::size_t>(n_keys, 1)}));
}

PpfTable build_ppf_table(ocl::Device& dev, const PointCloud& input, const bp_ppf_quant& quant,
                         PpfTableTimes* times) {
  const PointCloud cloud = ppf_input(input, kMaxPpfModelPoints, "PPF table");
  const std::size_t n = cloud.points.size();
  const std::size_t n_keys = bp_ppf_key_count(quant);
  PpfTableTimes t;
  Stopwatch clock;

  const std::size_t groups =
      ppf_table_groups(n, n_keys, dev.device().getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
  const auto rows_per_group = static_cast<std::uint32_t>((n + groups - 1) / groups);
  const auto count = static_cast<std::uint32_t>(n);
  const auto keys = static_cast<std::uint32_t>(n_keys);
  const auto group_count = static_cast<std::uint32_t>(groups);
  ocl::Buffer<cl_float4> points(dev, std::span<const cl_float4>(pack_float4(cloud.points)),
                                CL_MEM_READ_ONLY);
  ocl::Buffer<cl_float4> normals(dev, std::span<const cl_float4>(pack_float4(cloud.normals)),
                                 CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> counts(dev, groups * n_keys), totals(dev, n_keys),
      offsets(dev, n_keys + 1);
  counts.fill(dev, 0u);
  cl::Kernel count_kernel = dev.kernel("ppf_table.cl", "ppf_count");
  ocl::launch(dev, count_kernel, n > 0 ? groups : 0, points, normals, count, quant,
              rows_per_group, keys, counts);
  ocl::finish(dev);
  t.count_s = clock.lap_seconds();

  cl::Kernel totals_kernel = dev.kernel("ppf_table.cl", "ppf_bucket_totals");
  ocl::launch(dev, totals_kernel, n_keys, counts, group_count, keys, totals);
  // n <= kMaxPpfModelPoints keeps the total below 2^27.
  const std::uint32_t total = exclusive_scan(dev, totals, n_keys, offsets);
  cl::Kernel slots_kernel = dev.kernel("ppf_table.cl", "ppf_group_slots");
  ocl::launch(dev, slots_kernel, n_keys, counts, group_count, keys, offsets);
  ocl::finish(dev);
  t.scan_s = clock.lap_seconds();

  ocl::Buffer<bp_ppf_entry> entries(dev, total);
  cl::Kernel scatter = dev.kernel("ppf_table.cl", "ppf_scatter");
  ocl::launch(dev, scatter, n > 0 ? groups : 0, points, normals, count, quant, rows_per_group,
              keys, counts, entries);
  ocl::finish(dev);
  t.scatter_s = clock.lap_seconds();

  PpfTable table{offsets.read(dev), entries.read(dev)};
  t.read_s = clock.lap_seconds();
  if (times) *times = t;
  return table;
}

PpfTable ppf_table_from_features(const PairFeatures& features, const bp_ppf_quant& quant) {
  const std::size_t n_keys = bp_ppf_key_count(quant);
  const std::size_t n = features.n;
  PpfTable table;
  table.offsets.assign(n_keys + 1, 0);
  for (std::uint32_t key : features.keys)
    if (key != BP_PPF_NO_KEY) {
      if (key >= n_keys) throw std::logic_error("PPF key " + std::to_string(key) + " out of range");
      ++table.offsets[key + 1];
    }
  for (std::size_t k = 0; k < n_keys; ++k) table.offsets[k + 1] += table.offsets[k];
  table.entries.resize(table.offsets.back());
  std::vector<std::uint32_t> fill(table.offsets.begin(), table.offsets.end() - 1);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t key = features.keys[r * n + i];
      if (key == BP_PPF_NO_KEY) continue;
      table.entries[fill[key]++] = {static_cast<std::uint32_t>(r), features.alphas[r * n + i]};
    }
  return table;
}

PpfTable build_ppf_table_reference(const PointCloud& cloud, const bp_ppf_quant& quant) {
  ppf_input(cloud, kMaxPpfModelPoints, "PPF table");
  return ppf_table_from_features(ppf_pair_features_reference(cloud, quant), quant);
}

}  // namespace binpick

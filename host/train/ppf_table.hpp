// The PPF hash table of a model (kernels/ppf_table.cl): for every discretised feature key, the
// range of entries (m_r, alpha_m) of all model pairs with that key, in CSR form. Keys index the
// table directly (bp_ppf_key is dense), so no pair is ever lost to a collision. Within a bucket
// entries are in the order of the pairs (m_r, m_i): by reference point, then by partner point,
// so the table is identical run to run.
#pragma once

#include <cstdint>
#include <vector>

#include "host/core/mesh.hpp"
#include "host/train/ppf_features.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

// At most 2^27 pairs (a 1 GiB table): 11585 points.
inline constexpr std::size_t kMaxPpfModelPoints = 11585;

// Work items of the table build (each a block of reference points with its own histogram).
inline constexpr std::size_t kPpfTableGroups = 64;
// The build's split of n reference points into groups of consecutive rows on a device of
// `cores` compute units: at most kPpfTableGroups, and the histograms within 2^24 counters
// (64 MiB). The table does not depend on it: a bucket's entries stay in row order.
std::size_t ppf_table_groups(std::size_t n, std::size_t n_keys, std::size_t cores);

struct PpfTable {
  std::vector<std::uint32_t> offsets;  // bp_ppf_key_count(quant) + 1; offsets.back() = entries
  std::vector<bp_ppf_entry> entries;

  std::size_t distinct_keys() const;  // non-empty buckets
};

struct PpfTableTimes {
  double count_s = 0, scan_s = 0, scatter_s = 0, read_s = 0;
};

// Device routine: all ordered pairs of the cloud (normals required, scaled to unit length).
// Throws InputError for non-finite input or more than kMaxPpfModelPoints points. An empty or
// one-point cloud gives an empty table.
PpfTable build_ppf_table(ocl::Device& dev, const PointCloud& cloud, const bp_ppf_quant& quant,
                         PpfTableTimes* times = nullptr);

// The table of given pair features (row-major n x n, as ppf_pair_features returns), built on the
// host: with the device's features it must equal build_ppf_table's result exactly.
PpfTable ppf_table_from_features(const PairFeatures& features, const bp_ppf_quant& quant);

// Plain C++ reference: ppf_table_from_features(ppf_pair_features_reference(cloud)).
PpfTable build_ppf_table_reference(const PointCloud& cloud, const bp_ppf_quant& quant);

}  // namespace binpick

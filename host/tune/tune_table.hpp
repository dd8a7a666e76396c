// The table `binpick tune` explored: printed one row per measurement as it goes (precision in the
// order the objective compares it: top, strict top, all, strict all), and written as
// OUT/tune.csv (the same columns, machine-readable, rewritten after every row).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/tune/tune_search.hpp"

namespace binpick {

// Column headings for the printed table.
std::string tune_table_header();
// One printed row; `best` marks the best point so far.
std::string tune_table_row(const TuneRow& row, bool best);

// index,round,axis,ref_ratio,cluster_distance,cluster_angle,exclusion_ratio,angle_steps,
// distance_steps,top,all,strict_top,strict_all,ms_per_hypothesis,within_budget,best
void write_tune_csv(const std::filesystem::path& path, const std::vector<TuneRow>& rows,
                    std::size_t best);

}  // namespace binpick

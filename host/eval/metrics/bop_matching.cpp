#include "host/eval/metrics/bop_matching.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace binpick::eval {
namespace {

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double ratio(int matched, int targets) {
  return targets == 0 ? 0.0 : static_cast<double>(matched) / targets;
}

}  // namespace

int matched_instances(const std::vector<EstimateErrors>& estimates, double threshold) {
  std::set<int> matched;
  for (const auto& e : estimates) {
    int best = -1;
    double best_error = threshold;
    for (const auto& [instance, error] : e.errors)
      if (!matched.count(instance) && error < best_error) {
        best = instance;
        best_error = error;
      }
    if (best >= 0) matched.insert(best);
  }
  return static_cast<int>(matched.size());
}

MetricRecall recall_over_thresholds(const std::vector<TargetGroup>& groups,
                                    const std::vector<double>& thresholds) {
  std::map<int, int> targets;                 // per obj_id
  std::map<int, std::vector<int>> matched;    // per obj_id, per threshold
  for (const auto& g : groups) {
    targets[g.obj_id] += g.targets;
    auto& m = matched[g.obj_id];
    m.resize(thresholds.size(), 0);
    for (std::size_t k = 0; k < thresholds.size(); ++k)
      // A group never matches more instances than it has targets: errors exist only to targets.
      m[k] += matched_instances(g.estimates, thresholds[k]);
  }
  MetricRecall out;
  out.overall.thresholds = thresholds;
  int all_targets = 0;
  std::vector<int> all_matched(thresholds.size(), 0);
  for (const auto& [obj_id, count] : targets) {
    ObjectRecall o{obj_id, count, {thresholds, {}, 0}};
    for (std::size_t k = 0; k < thresholds.size(); ++k) {
      o.curve.recall.push_back(ratio(matched[obj_id][k], count));
      all_matched[k] += matched[obj_id][k];
    }
    o.curve.average = mean(o.curve.recall);
    all_targets += count;
    out.objects.push_back(std::move(o));
  }
  for (std::size_t k = 0; k < thresholds.size(); ++k)
    out.overall.recall.push_back(ratio(all_matched[k], all_targets));
  out.overall.average = mean(out.overall.recall);
  return out;
}

std::vector<double> arange(double start, double stop, double step) {
  std::vector<double> v;
  const auto n = static_cast<long>(std::ceil((stop - start) / step));
  for (long i = 0; i < n; ++i) v.push_back(start + static_cast<double>(i) * step);
  return v;
}

}  // namespace binpick::eval

#include "bench/lib/scaling_bench.hpp"

#include <algorithm>
#include <cmath>

#include "host/detect/vote/ppf_vote.hpp"

namespace binpick::bench {
namespace {

// Median over repeats of the mean vote + cluster time of detect_subsampled over the clouds.
double vote_cluster_ms(Detector& detector, const std::vector<PointCloud>& clouds, int repeats) {
  std::vector<double> per_rep;
  for (int r = 0; r < repeats; ++r) {
    DetectTimes t;
    for (const PointCloud& c : clouds) (void)detector.detect_subsampled(c, &t);
    per_rep.push_back((t.vote_ms + t.cluster_ms) / double(std::max<std::size_t>(t.hypotheses, 1)));
  }
  return median(per_rep);
}

std::vector<PointCloud> clouds_of(const std::vector<BenchCrop>& crops) {
  std::vector<PointCloud> clouds;
  for (const auto& c : crops) clouds.push_back(c.cloud);
  return clouds;
}

// The points within fraction f of the cloud's radius around its centroid, in their order.
PointCloud inner_part(const PointCloud& cloud, double f) {
  if (cloud.points.empty()) return cloud;
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();
  for (const auto& p : cloud.points) centre += p;
  centre /= float(cloud.points.size());
  float radius = 0;
  for (const auto& p : cloud.points) radius = std::max(radius, (p - centre).norm());
  PointCloud part;
  for (std::size_t i = 0; i < cloud.points.size(); ++i)
    if ((cloud.points[i] - centre).norm() <= float(f) * radius) {
      part.points.push_back(cloud.points[i]);
      part.normals.push_back(cloud.normals[i]);
    }
  return part;
}

double mean_size(const std::vector<PointCloud>& clouds) {
  double n = 0;
  for (const auto& c : clouds) n += double(c.points.size());
  return clouds.empty() ? 0 : n / double(clouds.size());
}

}  // namespace

double log_log_slope(const std::vector<ScalingPoint>& points) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& p : points) {
    if (!(p.size > 0 && p.ms > 0)) continue;
    const double x = std::log(p.size), y = std::log(p.ms);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  const double den = n * sxx - sx * sx;
  return n < 2 || std::abs(den) < 1e-12 ? 0 : (n * sxy - sx * sy) / den;
}

Scaling scale_with_ref_ratio(const PpfModel& model, const DetectParams& params,
                             const std::vector<BenchCrop>& crops,
                             const std::vector<double>& ratios, int repeats) {
  Scaling s{"voting + clustering vs reference points", "reference ratio", "reference points", {}, 0};
  const auto clouds = clouds_of(crops);
  for (double ratio : ratios) {
    DetectParams p = params;
    p.ref_ratio = ratio;
    Detector detector(model, p);
    double refs = 0;
    for (const auto& c : clouds) refs += double(select_reference_points(c.points.size(), ratio).size());
    s.points.push_back({ratio, clouds.empty() ? 0 : refs / double(clouds.size()),
                        vote_cluster_ms(detector, clouds, repeats), 0});
  }
  s.exponent = log_log_slope(s.points);
  return s;
}

Scaling scale_with_scene_points(const PpfModel& model, const DetectParams& params,
                                const std::vector<BenchCrop>& crops,
                                const std::vector<double>& fractions, int repeats) {
  Scaling s{"voting + clustering vs neighbourhood points", "fraction of the crop radius",
            "scene points", {}, 0};
  Detector detector(model, params);
  for (double f : fractions) {
    std::vector<PointCloud> clouds;
    for (const auto& c : crops) clouds.push_back(inner_part(c.cloud, f));
    s.points.push_back({f, mean_size(clouds), vote_cluster_ms(detector, clouds, repeats), 0});
  }
  s.exponent = log_log_slope(s.points);
  return s;
}

std::vector<Scaling> scale_with_model_points(const Mesh& mesh, const BenchOptions& o,
                                             const std::vector<BenchScene>& scenes) {
  Scaling detect{"detection vs model points", "voxel ratio", "model points", {}, 0};
  Scaling train{"training vs model points", "voxel ratio", "model points", {}, 0};
  for (double v : o.scaling_voxel_ratios) {
    PpfTrainParams tp = o.train;
    tp.voxel_ratio = v;
    std::vector<double> train_ms;
    PpfModel model = train_ppf_model(mesh, tp);  // warm-up (PoCL compiles per work size)
    for (int r = 0; r < o.repeats; ++r) {
      Stopwatch clock;
      model = train_ppf_model(mesh, tp);
      train_ms.push_back(clock.lap());
    }
    const double points = double(model.cloud.points.size());
    const double entries = double(model.table.entries.size());
    train.points.push_back({v, points, median(train_ms), entries});

    DetectParams p = o.detect;
    p.ref_ratio = o.ref_ratios.front();
    Detector detector(model, p);
    if (!scenes.empty()) (void)detector.detect(scenes[0].depth, scenes[0].camera);  // warm-up
    std::vector<double> per_rep;
    for (int r = 0; r < o.repeats; ++r) {
      DetectTimes t;
      for (const auto& s : scenes) (void)detector.detect(s.depth, s.camera, &t);
      per_rep.push_back(t.total_ms() / double(std::max<std::size_t>(t.hypotheses, 1)));
    }
    detect.points.push_back({v, points, median(per_rep), entries});
  }
  detect.exponent = log_log_slope(detect.points);
  train.exponent = log_log_slope(train.points);
  return {detect, train};
}

}  // namespace binpick::bench

// Detection on a point cloud (`detect --cloud`, Python's detect_cloud): the cloud's own highest
// points and crops, verification against the cloud seen through a virtual camera
// (cloud_image.hpp), and the region (--roi, --bin) found on that camera's depth image as on a
// sensor's, so that a bin's walls and rim are left out of the highest points and crops.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "host/core/timing.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/detector_steps.hpp"
#include "host/detect/hypotheses/prerank.hpp"
#include "host/detect/hypotheses/scene_cloud.hpp"
#include "host/detect/scene/cloud_image.hpp"
#include "host/detect/scene/depth_noise.hpp"
#include "host/detect/scene/scene_crop.hpp"
#include "host/detect/scene/scene_prepare.hpp"
#include "host/train/voxel_subsample.hpp"

namespace binpick {

using detector_steps::crop_about;
using detector_steps::detection_for;
using detector_steps::require;

Detector::CloudRegion Detector::cloud_region(const CloudImage& image, const PointCloud& cloud,
                                             DetectTimes& t) {
  CloudRegion out;
  const bp_camera& cam = image.camera;
  const DepthView depth(cam.width, cam.height, image.depth);
  bp_camera depth_cam = cam;
  depth_cam.depth_scale = image.depth_scale;
  const double noise = bin_spec_.mode != BinSpec::Mode::none ? depth_noise_mm(depth, depth_cam) : 0;
  const RegionSetup setup = region_setup(noise);
  if (!setup.wanted()) {
    out.kept = cloud;
    return out;
  }
  ScenePrepOptions prep;
  prep.read_back = false;
  prep.normals_everywhere = false;  // the bin fit and the mask read points only
  prep.lowpass = false;
  PreparedScene scene = prepare_scene(dev_, depth, depth_cam, prep);
  t.stages.insert(t.stages.end(), scene.timings.begin(), scene.timings.end());
  const SceneRegionMask masked = apply_region(scene, setup, prep.lowpass_radius, &t.stages);
  note_region(masked, setup, depth, t);
  out.bin = masked.bin;
  if (!masked.mask) {
    out.kept = cloud;
    return out;
  }
  // A point stays when its pixel does (the pixel cloud_point_image gives it).
  const std::vector<std::uint8_t> keep = masked.mask->read(dev_);
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    if (!(p.z() > 0)) continue;
    const long u = std::lround(cam.fx * p.x() / p.z() + cam.cx);
    const long v = std::lround(cam.fy * p.y() / p.z() + cam.cy);
    if (u < 0 || v < 0 || u >= long(cam.width) || v >= long(cam.height)) continue;
    if (!keep[std::size_t(v) * cam.width + std::size_t(u)]) continue;
    out.kept.points.push_back(p);
    out.kept.normals.push_back(cloud.normals[i]);
  }
  return out;
}

std::vector<Detection> Detector::detect(const PointCloud& input, DetectTimes* times) {
  DetectTimes t;
  Stopwatch clock;
  const Stopwatch started;
  skipped_.clear();
  region_report_.clear();
  last_bin_.reset();
  check_cloud(input);
  require(!input.points.empty(), "the point cloud is empty");
  PointCloud full = input;
  if (full.normals.empty())
    full.normals = cloud_normals(full, float(params_.normal_ratio * model_.diameter));
  // Verification needs what the sensor saw along each ray: the cloud seen through a virtual
  // camera (scene_cloud.hpp). --roi and --bin look at that image as at a depth image.
  const CloudImage image = cloud_point_image(full, 0.5f * model_.voxel_size);
  const double region_ms = clock.lap();
  t.prepare_ms += region_ms;
  t.stages.push_back({"cloud image", region_ms});
  const CloudRegion region = cloud_region(image, full, t);
  const PointCloud& cloud = region.kept;
  require(!cloud.points.empty(), "no point of the cloud lies in the region (--roi, --bin)");
  clock.lap();
  CloudHypothesisOptions ho;
  // Highest points to stand in for those the flat-region test skips (a cloud's rounds are cheap:
  // all found at once).
  ho.hypotheses.count = hypotheses_sought(params_) * (params_.flat_region > 0 ? 2 : 1);
  ho.hypotheses.exclusion_radius = float(params_.exclusion_ratio * model_.diameter);
  const std::vector<Hypothesis> hyps = find_hypotheses(cloud, ho);
  const double prep_ms = clock.lap();
  t.prepare_ms += prep_ms;
  t.stages.push_back({"cloud hypotheses", prep_ms});
  const ocl::Buffer<float> points(dev_, std::span<const float>(image.points.xyzw),
                                  CL_MEM_READ_ONLY);
  t.prepare_ms += clock.lap();

  std::vector<std::optional<HypothesisCrop>> crops(hyps.size());  // as on a depth image
  const auto crop = [&](std::size_t k) -> const HypothesisCrop& {
    if (!crops[k]) {
      clock.lap();
      const PointCloud neighbourhood =
          crop_sphere(cloud, crop_about(hyps[k], params_.crop_ratio * model_.diameter));
      HypothesisCrop c;
      c.cropped = neighbourhood.points.size();
      // The scene is subsampled like the model (its voxel), so that densities, and so votes,
      // match.
      c.cloud = voxel_subsample(dev_, neighbourhood, model_.voxel_size).cloud;
      const double ms = clock.lap();
      t.prepare_ms += ms;
      t.stages.push_back({"crop+subsample", ms});
      c.reason = flat_skip_->reason(c.cloud, hyps[k].point, 0, 1);
      c.flat = !c.reason.empty();
      crops[k] = std::move(c);
    }
    return *crops[k];
  };
  // The stand-ins for flat-skipped points (the second half) follow in height order.
  VoteQueue queue{vote_order(hyps.size(), hypotheses_sought(params_), crop, t)};
  Voted voted;
  const auto vote = [&](std::size_t from, std::size_t to) {
    vote_from_queue(queue, from, to, crop, hyps, nullptr, voted, clock, t);
  };
  RefineMemo refined;  // the first round's ICP, for the second
  const BinFit* bin = region.bin && region.bin->found ? &*region.bin : nullptr;
  const auto rank = [&] {
    return refine_and_rank(voted.detections, voted.candidates, points, image.camera, t, false,
                           bin, nullptr, &refined);
  };
  std::vector<Detection> detections =
      in_rounds(std::min(hyps.size(), hypotheses_sought(params_)), vote, rank, started, t);
  // Picks against the same virtual image and the bin if one was found (without, the approach
  // cone is about the view axis). Its pixels are the nearest points, the sensor's noise unknown:
  // the tolerance is --pick-tolerance alone.
  add_picks(detections, points, image.camera, bin, 0.0, t);
  if (times) *times += t;
  return detections;
}

}  // namespace binpick

#include "host/detect/refine/plane_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "host/core/cloud_input.hpp"
#include "host/core/error.hpp"

namespace binpick {
namespace {

std::vector<float> pack_poses(const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<float> out;
  out.reserve(12 * poses.size());
  for (const Eigen::Isometry3d& T : poses) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out.push_back(float(T.linear()(r, c)));
    for (int r = 0; r < 3; ++r) out.push_back(float(T.translation()[r]));
  }
  return out;
}

constexpr std::uint32_t kMinProbes = 10;  // BP_EDGE_SEARCH_MIN_PROBES

}  // namespace

Eigen::Vector3d sheet_normal(const PointCloud& model_points, const Eigen::Vector3d& centre) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3f& p : model_points.points) {
    const Eigen::Vector3d q = p.cast<double>() - centre;
    cov += q * q.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0).normalized();
}

PlaneSearchModel upload_plane_search_model(ocl::Device& dev, const PointCloud& edge_probes,
                                           const PointCloud& model_points,
                                           const Eigen::Vector3d& centre) {
  if (edge_probes.normals.size() != edge_probes.points.size() ||
      model_points.normals.size() != model_points.points.size())
    throw InputError("the plane search needs edge probes and model points with normals");
  PlaneSearchModel m;
  m.axis = sheet_normal(model_points, centre);
  m.centre = centre;
  if (edge_probes.points.empty() || model_points.points.empty()) return m;
  m.probes = static_cast<std::uint32_t>(edge_probes.points.size() + model_points.points.size());
  std::vector<cl_float4> p = pack_float4(edge_probes.points), n = pack_float4(edge_probes.normals);
  std::vector<cl_float4> own = pack_float4(model_points.points);
  const std::vector<cl_float4> own_n = pack_float4(model_points.normals);
  for (cl_float4& q : own) q.s[3] = 1.0f;  // the part's own surface
  p.insert(p.end(), own.begin(), own.end());
  n.insert(n.end(), own_n.begin(), own_n.end());
  m.points = ocl::Buffer<cl_float4>(dev, std::span<const cl_float4>(p), CL_MEM_READ_ONLY);
  m.normals = ocl::Buffer<cl_float4>(dev, std::span<const cl_float4>(n), CL_MEM_READ_ONLY);
  return m;
}

ocl::Buffer<float> point_depths(ocl::Device& dev, const ocl::Buffer<float>& points,
                                const bp_camera& cam) {
  const std::size_t n = std::size_t(cam.width) * cam.height;
  if (points.size() != 4 * n)
    throw InputError("plane search: the point image does not match the camera");
  ocl::Buffer<float> depth(dev, n);
  cl::Kernel k = dev.kernel("plane_search.cl", "point_depths");
  ocl::launch(dev, k, n, points, static_cast<std::uint32_t>(n), depth);
  return depth;
}

std::vector<float> point_depths_reference(const std::vector<float>& points) {
  std::vector<float> depth(points.size() / 4);
  for (std::size_t i = 0; i < depth.size(); ++i)
    depth[i] = points[4 * i + 3] != 0.0f ? points[4 * i + 2] : 0.0f;
  return depth;
}

std::vector<float> edge_step_scores(ocl::Device& dev, const ocl::Buffer<float>& depth,
                                    const bp_camera& cam, const PlaneSearchModel& model,
                                    const std::vector<Eigen::Isometry3d>& poses,
                                    std::uint32_t stride, float tolerance) {
  if (stride == 0) throw InputError("edge step scores: the probe stride must be positive");
  if (depth.size() != std::size_t(cam.width) * cam.height)
    throw InputError("edge step scores: the depth image does not match the camera");
  if (poses.empty()) return {};
  if (model.probes == 0) return std::vector<float>(poses.size(), -1.0f);
  const ocl::Buffer<float> pose_buf(dev, std::span<const float>(pack_poses(poses)),
                                    CL_MEM_READ_ONLY);
  ocl::Buffer<float> scores(dev, poses.size());
  cl::Kernel k = dev.kernel("plane_search.cl", "edge_step_scores");
  ocl::launch(dev, k, poses.size(), depth, cam, model.points, model.normals, model.probes, stride,
              pose_buf, static_cast<std::uint32_t>(poses.size()), tolerance, scores);
  return scores.read(dev);
}

std::vector<float> edge_step_scores_reference(const std::vector<float>& points,
                                              const bp_camera& cam, const PointCloud& probes,
                                              std::size_t edge_probes,
                                              const std::vector<Eigen::Isometry3d>& poses,
                                              std::uint32_t stride, float tolerance) {
  if (stride == 0) throw InputError("edge step scores: the probe stride must be positive");
  if (points.size() != 4 * std::size_t(cam.width) * cam.height)
    throw InputError("edge step scores: the point image does not match the camera");
  std::vector<float> out;
  const std::vector<float> packed = pack_poses(poses);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const float* P = &packed[12 * k];
    // Per lane, as the kernel's 8-wide vectors sum (probe j / stride in lane j / stride % 8).
    std::array<float, 8> sum{}, own{};
    std::uint32_t count = 0, own_count = 0;
    for (std::size_t j = 0; j < probes.points.size(); j += stride) {
      const std::size_t lane = (j / stride) % 8;
      const Eigen::Vector3f& q = probes.points[j];
      const Eigen::Vector3f& m = probes.normals[j];
      const float x = P[0] * q.x() + P[1] * q.y() + P[2] * q.z() + P[9];
      const float y = P[3] * q.x() + P[4] * q.y() + P[5] * q.z() + P[10];
      const float z = P[6] * q.x() + P[7] * q.y() + P[8] * q.z() + P[11];
      const float nx = P[0] * m.x() + P[1] * m.y() + P[2] * m.z();
      const float ny = P[3] * m.x() + P[4] * m.y() + P[5] * m.z();
      const float nz = P[6] * m.x() + P[7] * m.y() + P[8] * m.z();
      if (!(z > 0.0f) || nx * x + ny * y + nz * z >= 0.0f) continue;
      const float fu = std::floor(cam.fx * x / z + cam.cx + 0.5f);
      const float fv = std::floor(cam.fy * y / z + cam.cy + 0.5f);
      if (!(fu >= 0.0f && fv >= 0.0f && fu < float(cam.width) && fv < float(cam.height))) continue;
      const float* s = &points[4 * (std::size_t(fv) * cam.width + std::size_t(fu))];
      float e = j >= edge_probes ? 0.5f * tolerance : tolerance;  // no depth (kernel's comment)
      if (s[3] != 0.0f) {
        e = (s[2] - z) * (std::sqrt(x * x + y * y + z * z) / z);
        if (e < -tolerance) continue;
        e = std::min(e, tolerance);
      }
      if (j >= edge_probes) {
        own[lane] += std::max(e, 0.0f);
        ++own_count;
      } else {
        sum[lane] += e;
        ++count;
      }
    }
    const auto total = [](const std::array<float, 8>& v) {
      return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7]));
    };
    out.push_back(count >= kMinProbes && own_count >= kMinProbes
                      ? total(sum) / float(count) - total(own) / float(own_count)
                      : -1.0f);
  }
  return out;
}

bool search_reads_lowpass(double noise, double thickness) { return noise > 0.5 * thickness; }

int search_lowpass_radius(double margin, double pixel) {
  if (!(margin > 0) || !(pixel > 0)) return 0;
  return int(std::clamp(std::ceil(margin / pixel) - 1.0, 0.0, 64.0));
}

Eigen::Isometry3d in_plane_pose(const Eigen::Isometry3d& pose, const Eigen::Vector3d& axis,
                                const Eigen::Vector3d& centre, double angle, double a, double b) {
  const Eigen::Vector3d n = pose.linear() * axis;
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const Eigen::Vector3d c = pose * centre + a * e1 + b * e2;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(angle, n).toRotationMatrix() * pose.linear();
  out.translation() = c - out.linear() * centre;
  return out;
}

std::vector<PlaneSearchResult> plane_search(ocl::Device& dev, const ocl::Buffer<float>& depth,
                                            const bp_camera& cam, const PlaneSearchModel& model,
                                            const std::vector<Eigen::Isometry3d>& starts,
                                            double span, float tolerance) {
  std::vector<PlaneSearchResult> best(starts.size());
  const std::vector<float> s0 = edge_step_scores(dev, depth, cam, model, starts, 1, tolerance);
  for (std::size_t r = 0; r < starts.size(); ++r) {
    best[r].pose = starts[r];
    best[r].start_score = best[r].score = s0[r];
  }
  if (starts.empty() || model.probes == 0 || !(span > 0)) return best;
  // Coarse: the whole turn, shifts of a quarter of the span; every start's grid in one launch.
  const double coarse = span / kShiftSteps, turn = 2 * std::numbers::pi / kCoarseAngles;
  std::vector<Eigen::Isometry3d> grid;
  for (const Eigen::Isometry3d& start : starts)
    for (int a = 0; a < kCoarseAngles; ++a)
      for (int i = -kShiftSteps; i <= kShiftSteps; ++i)
        for (int j = -kShiftSteps; j <= kShiftSteps; ++j)
          grid.push_back(in_plane_pose(start, model.axis, model.centre, a * turn, i * coarse,
                                       j * coarse));
  const std::vector<float> s = edge_step_scores(dev, depth, cam, model, grid, kCoarseStride,
                                                tolerance);
  const std::size_t per_start = grid.size() / starts.size();
  // Fine: around each start's best coarse poses, a quarter of their steps.
  std::vector<Eigen::Isometry3d> fine;
  std::vector<std::size_t> fine_start;  // the start each fine pose belongs to
  std::vector<std::size_t> order(per_start);
  for (std::size_t r = 0; r < starts.size(); ++r) {
    const std::size_t base = r * per_start;
    for (std::size_t k = 0; k < per_start; ++k) order[k] = base + k;
    const std::size_t n_best = std::min<std::size_t>(kFineStarts, per_start);
    std::partial_sort(order.begin(), order.begin() + n_best, order.end(),
                      [&](std::size_t x, std::size_t y) {
                        return s[x] > s[y] || (s[x] == s[y] && x < y);
                      });
    for (std::size_t b = 0; b < n_best; ++b) {
      if (s[order[b]] < 0) break;
      for (int a = -kFineSteps; a <= kFineSteps; ++a)
        for (int i = -kFineSteps; i <= kFineSteps; ++i)
          for (int j = -kFineSteps; j <= kFineSteps; ++j) {
            fine.push_back(in_plane_pose(grid[order[b]], model.axis, model.centre,
                                         a * turn / kFineDivisions, i * coarse / kFineDivisions,
                                         j * coarse / kFineDivisions));
            fine_start.push_back(r);
          }
    }
  }
  const std::vector<float> f = edge_step_scores(dev, depth, cam, model, fine, 1, tolerance);
  for (std::size_t k = 0; k < fine.size(); ++k) {
    PlaneSearchResult& b = best[fine_start[k]];
    if (f[k] > b.score) {
      b.score = f[k];
      b.pose = fine[k];
    }
  }
  return best;
}

std::vector<PlaneSearchResult> plane_search(PlaneSearchMemo& memo, ocl::Device& dev,
                                            const ocl::Buffer<float>& depth, const bp_camera& cam,
                                            const PlaneSearchModel& model,
                                            const std::vector<Eigen::Isometry3d>& starts,
                                            double span, float tolerance) {
  std::size_t known = 0;
  while (known < memo.starts.size() && known < starts.size() &&
         memo.starts[known].matrix() == starts[known].matrix())
    ++known;
  std::vector<PlaneSearchResult> found(memo.found.begin(), memo.found.begin() + long(known));
  const std::vector<Eigen::Isometry3d> rest(starts.begin() + long(known), starts.end());
  const std::vector<PlaneSearchResult> more =
      plane_search(dev, depth, cam, model, rest, span, tolerance);
  found.insert(found.end(), more.begin(), more.end());
  memo.starts = starts;
  memo.found = found;
  return found;
}

}  // namespace binpick

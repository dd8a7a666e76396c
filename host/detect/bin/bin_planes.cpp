#include "host/detect/bin/bin_planes.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace binpick {
namespace {

bp_plane to_shared(const Eigen::Vector3d& n, double d) {
  return {float(n.x()), float(n.y()), float(n.z()), float(d)};
}

// Least-squares plane of the points (the smallest principal axis), facing the camera.
FoundPlane fit_plane(const std::vector<Eigen::Vector3f>& pts,
                     const std::vector<std::uint32_t>& idx) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::uint32_t i : idx) mean += pts[i].cast<double>();
  mean /= double(idx.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::uint32_t i : idx) {
    const Eigen::Vector3d q = pts[i].cast<double>() - mean;
    cov += q * q.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  FoundPlane p;
  p.normal = eig.eigenvectors().col(0).normalized();
  if (p.normal.dot(mean) > 0) p.normal = -p.normal;
  p.d = -p.normal.dot(mean);
  return p;
}

std::vector<std::uint32_t> inliers_of(const std::vector<Eigen::Vector3f>& pts,
                                      const std::vector<std::uint32_t>& alive,
                                      const FoundPlane& p, float tol) {
  const bp_plane s = to_shared(p.normal, p.d);
  std::vector<std::uint32_t> out;
  for (std::uint32_t i : alive)
    if (bp_plane_distance(&s, pts[i].x(), pts[i].y(), pts[i].z()) <= tol) out.push_back(i);
  return out;
}

}  // namespace

std::uint32_t sample_stride(std::size_t valid, std::size_t max_points) {
  return std::max<std::uint32_t>(
      1, std::uint32_t(std::ceil(std::sqrt(double(valid) / double(std::max<std::size_t>(max_points, 1))))));
}

PlaneSamples sample_points(const std::vector<float>& xyzw, std::uint32_t width,
                           std::uint32_t height, std::size_t max_points) {
  PlaneSamples s;
  s.width = width, s.height = height;
  std::size_t valid = 0;
  for (std::size_t i = 0; i < std::size_t(width) * height; ++i) valid += xyzw[4 * i + 3] != 0.0f;
  s.stride = sample_stride(valid, max_points);
  for (std::uint32_t v = 0; v < height; v += s.stride)
    for (std::uint32_t u = 0; u < width; u += s.stride) {
      const float* p = &xyzw[4 * (std::size_t(v) * width + u)];
      if (p[3] == 0.0f) continue;
      s.points.emplace_back(p[0], p[1], p[2]);
      s.u.push_back(u);
      s.v.push_back(v);
    }
  return s;
}

PlaneSamples sample_points(ocl::Device& dev, const ocl::Buffer<float>& points,
                           std::uint32_t width, std::uint32_t height, std::size_t valid,
                           std::size_t max_points) {
  if (points.size() < 4 * std::size_t(width) * height)
    throw std::logic_error("sample_points: the point buffer is smaller than the image");
  PlaneSamples s;
  s.width = width, s.height = height;
  s.stride = sample_stride(valid, max_points);
  const std::uint32_t gw = (width + s.stride - 1) / s.stride, gh = (height + s.stride - 1) / s.stride;
  const std::size_t cells = std::size_t(gw) * gh;
  if (cells == 0) return s;
  ocl::Buffer<float> grid(dev, 4 * cells, CL_MEM_WRITE_ONLY);
  cl::Kernel k = dev.kernel("bin_planes.cl", "bin_sample_grid");
  ocl::launch(dev, k, cells, points, cl_uint(width), cl_uint(s.stride), cl_uint(gw), cl_uint(cells),
              grid);
  const std::vector<float> g = grid.read(dev);
  for (std::size_t c = 0; c < cells; ++c) {
    const float* p = &g[4 * c];
    if (p[3] == 0.0f) continue;
    s.points.emplace_back(p[0], p[1], p[2]);
    s.u.push_back(std::uint32_t(c % gw) * s.stride);
    s.v.push_back(std::uint32_t(c / gw) * s.stride);
  }
  return s;
}

std::vector<std::uint32_t> count_plane_inliers(ocl::Device& dev,
                                               const std::vector<Eigen::Vector3f>& points,
                                               const std::vector<bp_plane>& planes, float tol) {
  if (planes.empty()) return {};
  const std::size_t n = points.size();
  std::vector<float> xyz(3 * n);  // x of every point, then y, then z
  for (std::size_t i = 0; i < n; ++i)
    xyz[i] = points[i].x(), xyz[n + i] = points[i].y(), xyz[2 * n + i] = points[i].z();
  auto axis = [&](int a) {
    return ocl::Buffer<float>(dev, std::span<const float>(xyz.data() + a * n, n), CL_MEM_READ_ONLY);
  };
  const ocl::Buffer<float> xs = axis(0), ys = axis(1), zs = axis(2);
  ocl::Buffer<bp_plane> pl(dev, std::span<const bp_plane>(planes), CL_MEM_READ_ONLY);
  ocl::Buffer<cl_uint> counts(dev, planes.size());
  cl::Kernel k = dev.kernel("bin_planes.cl", "bin_plane_inliers");
  // One plane a work group: a plane's scan is long enough, and both cores get work.
  ocl::launch_tasks(dev, k, planes.size(), xs, ys, zs, cl_uint(n), pl, cl_uint(planes.size()),
                    tol, counts);
  return counts.read(dev);
}

std::vector<std::uint32_t> count_plane_inliers_reference(const std::vector<Eigen::Vector3f>& points,
                                                         const std::vector<bp_plane>& planes,
                                                         float tol) {
  std::vector<std::uint32_t> out(planes.size(), 0);
  for (std::size_t k = 0; k < planes.size(); ++k)
    for (const Eigen::Vector3f& p : points)
      out[k] += bp_plane_distance(&planes[k], p.x(), p.y(), p.z()) <= tol ? 1u : 0u;
  return out;
}

std::vector<FoundPlane> find_planes(ocl::Device& dev, const PlaneSamples& s,
                                    const PlaneSearch& opt) {
  const std::vector<Eigen::Vector3f>& pts = s.points;
  std::vector<FoundPlane> found;
  if (pts.size() < 3) return found;
  // The samples on their grid, to draw a triple's other two points near the first.
  const std::uint32_t gw = (s.width + s.stride - 1) / s.stride;
  const std::uint32_t gh = (s.height + s.stride - 1) / s.stride;
  std::vector<std::int64_t> grid(std::size_t(gw) * gh, -1);
  for (std::size_t i = 0; i < pts.size(); ++i)
    grid[std::size_t(s.v[i] / s.stride) * gw + s.u[i] / s.stride] = std::int64_t(i);
  const int reach = int(std::max<std::uint32_t>(3, std::max(gw, gh) / 10));
  std::vector<std::uint8_t> alive(pts.size(), 1);
  const std::size_t need =
      std::max<std::size_t>(50, std::size_t(std::ceil(opt.min_fraction * double(pts.size()))));
  const double min_span = 10.0 * opt.tol;  // a triple this small defines no plane reliably
  std::mt19937 rng(opt.seed);

  for (std::size_t round = 0; round < opt.max_planes; ++round) {
    std::vector<std::uint32_t> alive_idx;
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      if (alive[i]) alive_idx.push_back(i);
    if (alive_idx.size() < need) break;
    std::uniform_int_distribution<std::size_t> first(0, alive_idx.size() - 1);
    std::uniform_int_distribution<int> off(-reach, reach);
    std::vector<bp_plane> cand;
    for (std::size_t attempt = 0; cand.size() < opt.candidates && attempt < 20 * opt.candidates;
         ++attempt) {
      const std::uint32_t a = alive_idx[first(rng)];
      std::int64_t b = -1, c = -1;
      for (int t = 0; t < 16 && (b < 0 || c < 0); ++t) {
        const long gu = long(s.u[a] / s.stride) + off(rng), gv = long(s.v[a] / s.stride) + off(rng);
        if (gu < 0 || gv < 0 || gu >= long(gw) || gv >= long(gh)) continue;
        const std::int64_t j = grid[std::size_t(gv) * gw + std::size_t(gu)];
        if (j < 0 || !alive[j] || j == a || j == b) continue;
        (b < 0 ? b : c) = j;
      }
      if (b < 0 || c < 0) continue;
      const Eigen::Vector3d pa = pts[a].cast<double>(), pb = pts[b].cast<double>(),
                            pc = pts[c].cast<double>();
      const Eigen::Vector3d cr = (pb - pa).cross(pc - pa);
      if (cr.norm() < min_span * min_span) continue;
      Eigen::Vector3d n = cr.normalized();
      if (n.dot(pa) > 0) n = -n;
      cand.push_back(to_shared(n, -n.dot(pa)));
    }
    if (cand.empty()) break;
    std::vector<Eigen::Vector3f> alive_pts;
    alive_pts.reserve(alive_idx.size());
    for (std::uint32_t i : alive_idx) alive_pts.push_back(pts[i]);
    const std::vector<std::uint32_t> counts = count_plane_inliers(dev, alive_pts, cand, opt.tol);
    const std::size_t best = std::size_t(std::max_element(counts.begin(), counts.end()) - counts.begin());
    if (counts[best] < need) break;
    FoundPlane p;
    p.normal = Eigen::Vector3d(cand[best].nx, cand[best].ny, cand[best].nz);
    p.d = cand[best].d;
    // Two least-squares refits on the inliers: the sampled triple's noise leaves the plane.
    for (int refit = 0; refit < 2; ++refit) {
      const std::vector<std::uint32_t> in = inliers_of(pts, alive_idx, p, opt.tol);
      if (in.size() < 3) break;
      p = fit_plane(pts, in);
    }
    p.inliers = inliers_of(pts, alive_idx, p, opt.tol);
    if (p.inliers.size() < need) break;
    for (std::uint32_t i : inliers_of(pts, alive_idx, p, 1.5f * opt.tol)) alive[i] = 0;
    found.push_back(std::move(p));
  }
  return found;
}

}  // namespace binpick

#include "host/detect/refine/pose_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <fmt/format.h>

#include "host/core/cloud_input.hpp"
#include "host/core/error.hpp"

namespace binpick {
namespace {

// Points per work item's partial sums, added up in double.
void add_partial(const bp_fit_sums& s, FitSums& out) {
  int e = 0;
  for (int row = 0; row < 6; ++row) {
    for (int col = row; col < 6; ++col, ++e) {
      out.jtj(row, col) += s.jtj[e];
      if (col != row) out.jtj(col, row) += s.jtj[e];
    }
    out.jtr(row) += s.jtr[row];
  }
  out.cost += s.cost;
  out.agreement += s.agreement;
  for (unsigned c = 0; c < BP_FIT_CLASSES; ++c) out.count[c] += s.count[c];
  out.used += s.used;
  out.outline_continue += s.outline_continue;
  out.outline_step += s.outline_step;
}

void check_fits(const std::vector<bp_pose_fit>& fits) {
  for (const bp_pose_fit& f : fits)
    if (f.dim > BP_FIT_MAX_DIM || !(f.cell > 0) || !(f.gate > 0) || !(f.tolerance >= 0) ||
        !(f.outline >= 0))
      throw std::logic_error(fmt::format("pose fit with grid {} x {} cells of {} px, gate {}",
                                         f.dim, f.dim, f.cell, f.gate));
}

// The outline cells of one pose's z-buffer (pose_fit_shared.h), as the kernel counts them.
void add_outline_reference(const bp_pose_fit& f, const bp_camera& cam,
                           const std::vector<float>& grid, const PointImage& image, FitSums& s) {
  const std::uint32_t dim = f.dim;
  for (std::uint32_t gv = 0; gv < dim; ++gv)
    for (std::uint32_t gu = 0; gu < dim; ++gu) {
      const std::size_t i = std::size_t(gv) * dim + gu;
      if (std::isfinite(grid[i])) continue;
      float zn = std::numeric_limits<float>::infinity();
      if (gu + 1 < dim) zn = std::min(zn, grid[i + 1]);
      if (gu > 0) zn = std::min(zn, grid[i - 1]);
      if (gv + 1 < dim) zn = std::min(zn, grid[i + dim]);
      if (gv > 0) zn = std::min(zn, grid[i - dim]);
      std::uint32_t pixel = 0;
      if (!std::isfinite(zn) || !bp_fit_outline_pixel(&f, &cam, gu, gv, &pixel)) continue;
      const float* p = &image.xyzw[std::size_t(pixel) * 4];
      const std::uint32_t cls = bp_fit_outline_class(&f, zn, p[2], p[3]);
      s.outline_continue += cls == BP_FIT_OUTLINE_CONTINUE;
      s.outline_step += cls == BP_FIT_OUTLINE_STEP;
    }
}

}  // namespace

std::uint32_t FitSums::visible() const {
  std::uint32_t n = 0;
  for (unsigned c = 0; c < BP_FIT_CLASSES; ++c)
    if (c != BP_FIT_HIDDEN) n += count[c];
  return n;
}

DeviceFitModel upload_fit_model(ocl::Device& dev, const PointCloud& model) {
  if (model.normals.size() != model.points.size())
    throw InputError("the model has no normal per point");
  DeviceFitModel d;
  const std::vector<cl_float4> p = pack_float4(model.points), n = pack_float4(model.normals);
  d.points = ocl::Buffer<cl_float4>(dev, std::span<const cl_float4>(p), CL_MEM_READ_ONLY);
  d.normals = ocl::Buffer<cl_float4>(dev, std::span<const cl_float4>(n), CL_MEM_READ_ONLY);
  d.size = static_cast<std::uint32_t>(model.points.size());
  return d;
}

Eigen::Vector3d model_centroid(const PointCloud& model) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3f& p : model.points) sum += p.cast<double>();
  return model.points.empty() ? sum : Eigen::Vector3d(sum / double(model.points.size()));
}

bp_pose_fit make_pose_fit(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                          const bp_camera& cam, const FitGeometry& g, const FitThresholds& th) {
  bp_pose_fit f{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f.r[3 * i + j] = float(R(i, j));
    f.t[i] = float(t(i));
  }
  const Eigen::Vector3d c = R * g.centroid + t;
  for (int i = 0; i < 3; ++i) f.centre[i] = float(c(i));
  f.gate = th.gate;
  f.tolerance = th.tolerance;
  f.slack = th.slack;
  f.outline = th.outline;
  f.residuals = th.residuals ? 1u : 0u;
  f.near_gate = th.near_gate;
  f.cell = 1;
  f.dim = 0;  // nothing visible unless the pose lies in front of the camera
  const double near = c.z() - 0.5 * g.diameter;
  if (!(near > 1e-3 * g.diameter) || !std::isfinite(c.z())) return f;
  const double focal = std::max(cam.fx, cam.fy);
  const double radius_px = 0.5 * g.diameter * focal / near + 1.0;
  const double cell = std::max({1.0, 1.5 * g.voxel_size * focal / c.z(),
                                2.0 * radius_px / BP_FIT_MAX_DIM});
  f.cell = float(cell);
  f.dim = std::min<std::uint32_t>(BP_FIT_MAX_DIM, std::uint32_t(std::ceil(2.0 * radius_px / cell)));
  f.u0 = float(cam.fx * c.x() / c.z() + cam.cx - radius_px);
  f.v0 = float(cam.fy * c.y() / c.z() + cam.cy - radius_px);
  return f;
}

std::vector<FitSums> pose_fit_sums(ocl::Device& dev, const ocl::Buffer<float>& points,
                                   const bp_camera& cam, const DeviceFitModel& model,
                                   const std::vector<bp_pose_fit>& fits) {
  check_fits(fits);
  if (points.size() != std::size_t(cam.width) * cam.height * 4)
    throw std::logic_error("pose_fit: the point image does not match the camera");
  std::vector<FitSums> out(fits.size());
  if (fits.empty()) return out;
  ocl::Buffer<bp_pose_fit> fb(dev, std::span<const bp_pose_fit>(fits), CL_MEM_READ_ONLY);
  ocl::Buffer<std::uint32_t> grids(dev, fits.size() * BP_FIT_MAX_DIM * BP_FIT_MAX_DIM);
  ocl::Buffer<bp_fit_sums> sums(dev, fits.size() * BP_FIT_GROUP);
  // Residuals only when a fit asks for them (the verification pass, not every ICP step).
  const bool any_residuals =
      std::any_of(fits.begin(), fits.end(), [](const bp_pose_fit& f) { return f.residuals != 0; });
  const std::size_t per_point = any_residuals ? std::max<std::size_t>(1, fits.size() * model.size) : 1;
  ocl::Buffer<float> residuals(dev, per_point);
  ocl::Buffer<std::uint8_t> classes(dev, per_point);
  cl::Kernel kernel = dev.kernel("pose_fit.cl", "pose_fit");
  ocl::launch_local(dev, kernel, fits.size() * BP_FIT_GROUP, BP_FIT_GROUP, points, cam,
                    model.points, model.normals, model.size, fb,
                    static_cast<std::uint32_t>(fits.size()), grids, sums, residuals, classes);
  const std::vector<bp_fit_sums> partial = sums.read(dev);
  for (std::size_t k = 0; k < fits.size(); ++k)
    for (std::size_t i = 0; i < BP_FIT_GROUP; ++i) add_partial(partial[k * BP_FIT_GROUP + i], out[k]);
  if (any_residuals) {
    const std::vector<float> all = residuals.read(dev);
    const std::vector<std::uint8_t> all_classes = classes.read(dev);
    for (std::size_t k = 0; k < fits.size(); ++k)
      if (fits[k].residuals != 0) {
        const auto from = std::ptrdiff_t(k * model.size), to = std::ptrdiff_t((k + 1) * model.size);
        out[k].residuals.assign(all.begin() + from, all.begin() + to);
        out[k].classes.assign(all_classes.begin() + from, all_classes.begin() + to);
      }
  }
  return out;
}

std::vector<FitSums> pose_fit_sums_reference(const PointImage& image, const bp_camera& cam,
                                             const PointCloud& model,
                                             const std::vector<bp_pose_fit>& fits) {
  check_fits(fits);
  if (image.width != cam.width || image.height != cam.height)
    throw std::logic_error("pose_fit: the point image does not match the camera");
  std::vector<FitSums> out(fits.size());
  float q[3], nq[3], a[6], r = 0;
  std::uint32_t pixel = 0, cell = 0;
  for (std::size_t k = 0; k < fits.size(); ++k) {
    const bp_pose_fit& f = fits[k];
    std::vector<float> grid(std::size_t(f.dim) * f.dim, std::numeric_limits<float>::infinity());
    auto project = [&](std::size_t j) {
      const Eigen::Vector3f& m = model.points[j];
      const Eigen::Vector3f& n = model.normals[j];
      return bp_fit_project(&f, &cam, m.x(), m.y(), m.z(), n.x(), n.y(), n.z(), q, nq, &pixel,
                            &cell);
    };
    for (std::size_t j = 0; j < model.points.size(); ++j)
      if (project(j) != 0) grid[cell] = std::min(grid[cell], q[2]);
    FitSums& s = out[k];
    if (f.residuals != 0) {
      s.residuals.assign(model.points.size(), std::numeric_limits<float>::quiet_NaN());
      s.classes.assign(model.points.size(), std::uint8_t(BP_FIT_HIDDEN));
    }
    for (std::size_t j = 0; j < model.points.size(); ++j) {
      if (project(j) != 2) continue;
      const float* p = &image.xyzw[std::size_t(pixel) * 4];
      float agree = 0;
      const unsigned cls = bp_fit_classify(&f, &cam, q, nq, grid[cell], p[0], p[1], p[2], p[3], &agree);
      if (f.residuals != 0) s.classes[j] = std::uint8_t(cls);
      ++s.count[cls];
      s.agreement += agree;
      if (cls == BP_FIT_HIDDEN || cls == BP_FIT_MISSING) continue;
      const float w = bp_fit_term(&f, q, nq, p[0], p[1], p[2], a, &r);
      if (w == 0.0f) continue;
      if (f.residuals != 0) s.residuals[j] = r;
      ++s.used;
      const Eigen::Map<const Eigen::Matrix<float, 6, 1>> av(a);
      const Eigen::Matrix<double, 6, 1> ad = av.cast<double>();
      s.jtj += double(w) * ad * ad.transpose();
      s.jtr += double(w) * double(r) * ad;
      s.cost += double(w) * double(r) * double(r);
    }
    if (f.outline > 0.0f) add_outline_reference(f, cam, grid, image, s);
  }
  return out;
}

}  // namespace binpick

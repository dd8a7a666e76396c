#include "host/detect/scene/scene_neighbourhood.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "host/core/error.hpp"

namespace binpick {
namespace {

enum NormalState : std::uint8_t { kUnknown, kValid, kInvalid };

// Lazily computed normals of the cropped pixels.
class LazyNormals {
 public:
  LazyNormals(ocl::Device& dev, const PreparedScene& scene, const CroppedPixels& crop,
              const NormalOptions& opt)
      : dev_(dev), scene_(scene), crop_(crop), opt_(opt), state_(crop.pixels.size(), kUnknown),
        normals_(crop.pixels.size(), Eigen::Vector3f::Zero()) {}

  // Computes the normals of the listed crop indices not computed yet (one launch).
  void compute(const std::vector<std::uint32_t>& indices) {
    std::vector<std::uint32_t> todo, pixels;
    for (std::uint32_t i : indices)
      if (state_[i] == kUnknown) todo.push_back(i);
    std::sort(todo.begin(), todo.end());  // an extreme point may be a kept one too
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    for (std::uint32_t i : todo) pixels.push_back(crop_.pixels[i]);
    if (todo.empty()) return;
    const std::vector<float> n = normals_at_pixels(dev_, scene_.device->points, scene_.width,
                                                   scene_.height, pixels, opt_);
    for (std::size_t j = 0; j < todo.size(); ++j) {
      const float* o = &n[4 * j];
      state_[todo[j]] = o[3] != 0.0f ? kValid : kInvalid;
      normals_[todo[j]] = Eigen::Vector3f(o[0], o[1], o[2]);
    }
    computed_ += todo.size();
  }

  NormalState state(std::uint32_t i) const { return NormalState(state_[i]); }
  const Eigen::Vector3f& normal(std::uint32_t i) const { return normals_[i]; }
  std::size_t computed() const { return computed_; }

 private:
  ocl::Device& dev_;
  const PreparedScene& scene_;
  const CroppedPixels& crop_;
  NormalOptions opt_;
  std::vector<std::uint8_t> state_;
  std::vector<Eigen::Vector3f> normals_;
  std::size_t computed_ = 0;
};

// The point as the voxel grid sees it: z divided by the stretch, so that a voxel spans
// depth_stretch voxels along the camera's axis.
Eigen::Vector3f squash(const Eigen::Vector3f& p, float depth_stretch) {
  return {p.x(), p.y(), p.z() / depth_stretch};
}

void check_depth_stretch(float depth_stretch) {
  if (!(depth_stretch >= 1 && std::isfinite(depth_stretch)))
    throw InputError("the neighbourhood's depth stretch must be finite and at least 1");
}

// Positions (into s) of one point of smallest and one of largest coordinate per axis: they
// fix voxel_grid's origin and dimensions.
std::vector<std::uint32_t> extremes(const PointCloud& s) {
  std::vector<std::uint32_t> out;
  for (int a = 0; a < 3; ++a) {
    std::uint32_t lo = 0, hi = 0;
    for (std::uint32_t i = 1; i < s.points.size(); ++i) {
      if (s.points[i][a] < s.points[lo][a]) lo = i;
      if (s.points[i][a] > s.points[hi][a]) hi = i;
    }
    out.push_back(lo);
    out.push_back(hi);
  }
  return out;
}

// The positions (into s) of the points that share a voxel of the grid with a listed one: the
// candidates to win those voxels once the listed ones are out. The cell is computed as the
// subsampling kernel does; a point rounded into a neighbouring cell only costs a round more,
// since the result is checked, not assumed.
std::vector<std::uint32_t> voxel_mates(const PointCloud& s, float voxel_size,
                                       const std::vector<std::uint32_t>& listed) {
  const VoxelGrid g = voxel_grid(s, voxel_size);
  const auto cell = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector3f f = (p - g.origin) * g.inv_voxel;
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::min<std::uint64_t>(static_cast<std::uint64_t>(std::max(0.0f, std::floor(f[a]))),
                                     g.dims[a] - 1);
    return (c[2] * g.dims[1] + c[1]) * g.dims[0] + c[0];
  };
  std::vector<std::uint64_t> cells;
  for (std::uint32_t k : listed) cells.push_back(cell(s.points[k]));
  std::sort(cells.begin(), cells.end());
  std::vector<std::uint32_t> out;
  for (std::uint32_t k = 0; k < s.points.size(); ++k)
    if (std::binary_search(cells.begin(), cells.end(), cell(s.points[k]))) out.push_back(k);
  return out;
}

}  // namespace

NeighbourhoodSample sample_neighbourhood(const PreparedScene& scene, const CropOptions& crop,
                                         const NormalOptions& normal_opt, float voxel_size,
                                         StageTimings* timings,
                                         const ocl::Buffer<std::uint8_t>* mask,
                                         float depth_stretch) {
  if (!scene.device) throw InputError("sample_neighbourhood needs a scene on the device");
  check(normal_opt);
  check_depth_stretch(depth_stretch);
  auto& dev = *scene.device->dev;
  Stopwatch clock;
  const CroppedPixels c = crop_pixels(dev, scene.device->points, scene.camera, crop, mask);
  if (timings) timings->push_back({"crop", clock.lap()});

  NeighbourhoodSample out;
  out.cropped = c.pixels.size();
  LazyNormals normals(dev, scene, c, normal_opt);
  std::vector<std::uint32_t> active(c.pixels.size());  // crop indices still in S
  std::iota(active.begin(), active.end(), 0u);
  double subsample_ms = 0, normals_ms = 0;
  auto to_crop = [&](const std::vector<std::uint32_t>& positions) {
    std::vector<std::uint32_t> idx;
    idx.reserve(positions.size());
    for (std::uint32_t k : positions) idx.push_back(active[k]);
    return idx;
  };
  auto drop_invalid = [&] {
    std::erase_if(active, [&](std::uint32_t i) { return normals.state(i) == kInvalid; });
  };
  while (!active.empty()) {
    ++out.rounds;
    const bool last = out.rounds > kLazyNormalRounds;
    if (last) {  // many invalid normals: compute all of S, keep V
      normals.compute(active);
      drop_invalid();
      normals_ms += clock.lap();
      if (active.empty()) break;
    }
    PointCloud s;
    s.points.reserve(active.size());
    for (std::uint32_t i : active) s.points.push_back(squash(c.points[i], depth_stretch));
    const VoxelSubsample sub = voxel_subsample(dev, s, voxel_size);
    subsample_ms += clock.lap();

    std::vector<std::uint32_t> need = sub.kept;
    if (!last) {
      const std::vector<std::uint32_t> ext = extremes(s);
      need.insert(need.end(), ext.begin(), ext.end());
    }
    const std::vector<std::uint32_t> need_idx = to_crop(need);
    normals.compute(need_idx);
    normals_ms += clock.lap();
    if (std::all_of(need_idx.begin(), need_idx.end(),
                    [&](std::uint32_t i) { return normals.state(i) == kValid; })) {
      for (std::uint32_t i : to_crop(sub.kept)) {
        out.cloud.points.push_back(c.points[i]);
        out.cloud.normals.push_back(normals.normal(i));
      }
      break;
    }
    // A voxel whose winner has no normal goes to the next nearest point of it: compute the
    // normals of all its points now, so the next round's winner there is known. One winner at a
    // time took up to 46 rounds (or all of S after kLazyNormalRounds) under patchy depth.
    std::vector<std::uint32_t> failed;
    for (std::size_t j = 0; j < sub.kept.size(); ++j)
      if (normals.state(need_idx[j]) == kInvalid) failed.push_back(sub.kept[j]);
    if (!last && !failed.empty()) {
      normals.compute(to_crop(voxel_mates(s, voxel_size, failed)));
      normals_ms += clock.lap();
    }
    drop_invalid();
  }
  out.normals = normals.computed();
  if (timings) {
    timings->push_back({"subsample", subsample_ms});
    timings->push_back({"normals", normals_ms});
  }
  return out;
}

NeighbourhoodSample sample_neighbourhood_reference(const PointImage& points,
                                                   const CropOptions& crop,
                                                   const NormalOptions& normal_opt,
                                                   float voxel_size,
                                                   const std::vector<std::uint8_t>* mask,
                                                   float depth_stretch) {
  check_depth_stretch(depth_stretch);
  PointImage normals = normals_from_points_reference(points, normal_opt);
  if (mask) {
    if (mask->size() != std::size_t(points.width) * points.height)
      throw InputError("the neighbourhood mask does not match the point image");
    for (std::size_t i = 0; i < mask->size(); ++i)
      if (!(*mask)[i]) normals.xyzw[4 * i + 3] = 0.0f;  // crop_sphere drops it
  }
  CropOptions with_normals = crop;
  with_normals.require_normals = true;
  NeighbourhoodSample out;
  const PointCloud cropped = crop_sphere_reference(points, normals, with_normals);
  PointCloud squashed = cropped;
  for (Eigen::Vector3f& p : squashed.points) p = squash(p, depth_stretch);
  for (std::uint32_t i : voxel_subsample_reference(squashed, voxel_size).kept) {
    out.cloud.points.push_back(cropped.points[i]);
    out.cloud.normals.push_back(cropped.normals[i]);
  }
  out.cropped = crop_pixels_reference(points, crop, mask).pixels.size();
  out.normals = std::size_t(points.width) * points.height;
  out.rounds = 1;
  return out;
}

}  // namespace binpick

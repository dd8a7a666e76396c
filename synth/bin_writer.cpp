#include "synth/bin_writer.hpp"
#include "synth/sensor/sensor_apply.hpp"

#include <cmath>
#include <fmt/format.h>

#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/core/error.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"

namespace binpick {
namespace {

namespace fs = std::filesystem;

GrayImage<std::uint16_t> depth_png(const RenderedBin& r, double depth_scale) {
  GrayImage<std::uint16_t> img{r.width, r.height, std::vector<std::uint16_t>(r.depth_mm.size())};
  for (std::size_t i = 0; i < r.depth_mm.size(); ++i) {
    const double v = std::round(r.depth_mm[i] / depth_scale);
    if (v > 65535.0) throw InputError("depth beyond the 16-bit range: increase depth_scale");
    img.pixels[i] = r.depth_mm[i] > 0 ? std::uint16_t(std::max(v, 1.0)) : 0;
  }
  return img;
}

PointCloud visible_cloud(const RenderedBin& r) {
  PointCloud cloud;
  for (std::size_t i = 0; i < r.depth_mm.size(); ++i) {
    if (!(r.depth_mm[i] > 0)) continue;
    cloud.points.emplace_back(r.points[3 * i], r.points[3 * i + 1], r.points[3 * i + 2]);
    cloud.normals.emplace_back(r.normals[3 * i], r.normals[3 * i + 1], r.normals[3 * i + 2]);
  }
  return cloud;
}

bop::GroundTruthInfo info_of(const RenderedBin& r, const std::vector<std::uint32_t>& valid,
                             std::size_t part) {
  bop::GroundTruthInfo g;
  g.bbox_obj = r.bbox_all[part];
  g.bbox_visib = r.bbox_visible[part];
  g.px_count_all = r.px_all[part];
  g.px_count_visib = r.px_visible[part];
  // Visible pixels the sensor gave depth (BOP counts those of the whole silhouette, occlusion
  // ignored: not yet, docs/formats.md).
  g.px_count_valid = valid[part];
  g.visib_fract = r.px_all[part] ? double(r.px_visible[part]) / double(r.px_all[part]) : 0.0;
  return g;
}

}  // namespace

void write_bop_scene(const fs::path& dir, const BinRecord& bin) {
  const RenderedBin& r = bin.render;
  for (const char* sub : {"depth", "gray", "cloud"}) fs::create_directories(dir / sub);
  write_png(dir / "depth" / "000000.png", depth_png(r, bin.depth_scale));
  write_png(dir / "gray" / "000000.png", GrayImage<std::uint8_t>{r.width, r.height, r.gray});
  if (bin.write_cloud) write_point_cloud_ply(dir / "cloud" / "000000.ply", visible_cloud(r));

  bop::SceneCamera cam;
  cam.K << bin.camera.fx, 0, bin.camera.cx, 0, bin.camera.fy, bin.camera.cy, 0, 0, 1;
  cam.depth_scale = bin.depth_scale;
  cam.world_to_camera = bop::Pose::from(bin.world_to_camera);
  bop::write_scene_cameras(dir / "scene_camera.json", {{0, cam}});

  if (bin.obj_ids.size() != bin.part_to_camera.size())
    throw InputError("bin writer: an obj_id is needed for every part");
  std::vector<bop::GroundTruth> gt;
  std::vector<bop::GroundTruthInfo> info;
  const std::vector<std::uint32_t> valid = valid_pixels_per_part(r);
  for (std::size_t i = 0; i < bin.part_to_camera.size(); ++i) {
    gt.push_back({bin.obj_ids[i], bop::Pose::from(bin.part_to_camera[i])});
    info.push_back(info_of(r, valid, i));
  }
  bop::write_scene_gt(dir / "scene_gt.json", {{0, gt}});
  bop::write_scene_gt_info(dir / "scene_gt_info.json", {{0, info}});

  if (bin.write_masks) {
    fs::create_directories(dir / "mask_visib");
    for (std::size_t part = 0; part < bin.part_to_camera.size(); ++part) {
      GrayImage<std::uint8_t> mask{r.width, r.height, std::vector<std::uint8_t>(r.instance.size(), 0)};
      for (std::size_t i = 0; i < r.instance.size(); ++i)
        if (r.instance[i] == int(part)) mask.pixels[i] = 255;
      write_png(dir / "mask_visib" / fmt::format("000000_{:06d}.png", part), mask);
    }
  }
}

}  // namespace binpick

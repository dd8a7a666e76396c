#include "synth/bin_writer.hpp"

#include <cmath>
#include <fmt/format.h>

#include "synth/bop_visibility.hpp"
#include "host/formats/bop/bop_files.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/core/error.hpp"
#include "host/formats/mesh/point_cloud_ply.hpp"
#include "synth/render/part_pixels.hpp"

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

// BOP's visibility of one part against the depth image as written (bop_visibility.hpp).
BopVisibility visibility_of(const BinRecord& bin, const GrayImage<std::uint16_t>& depth,
                            std::size_t part, bool keep_pixels) {
  Eigen::Matrix3d K;
  K << bin.camera.fx, 0, bin.camera.cx, 0, bin.camera.fy, bin.camera.cy, 0, 0, 1;
  return bop_visibility(bin.silhouettes[part],
                        {depth.width, depth.height, &depth.pixels, bin.depth_scale}, K,
                        kBopVisibDelta, keep_pixels);
}

// calc_2d_bbox of the part's unoccluded pixels.
std::array<int, 4> bbox_of(const PartSilhouette& s, std::uint32_t width) {
  PartPixels box(1);
  for (std::uint32_t p : s.pixels) box.add(0, int(p % width), int(p / width));
  return bop_bbox(box.box[0]);
}

// calc_gt_info.py's entry for one part, from its silhouette s and visibility v.
bop::GroundTruthInfo info_of(const PartSilhouette& s, std::uint32_t width, const BopVisibility& v) {
  bop::GroundTruthInfo g;
  g.px_count_all = std::uint32_t(s.pixels.size());
  g.px_count_valid = v.px_count_valid;
  g.px_count_visib = v.px_count_visib;
  g.visib_fract = g.px_count_all ? double(g.px_count_visib) / double(g.px_count_all) : 0.0;
  // The toolkit fills bbox_obj only for a part with a visible pixel.
  g.bbox_obj = v.px_count_visib > 0 ? bbox_of(s, width) : std::array<int, 4>{-1, -1, -1, -1};
  g.bbox_visib = v.bbox_visib;
  return g;
}

GrayImage<std::uint8_t> mask_of(const RenderedBin& r, const std::vector<std::uint32_t>& pixels) {
  GrayImage<std::uint8_t> mask{r.width, r.height, std::vector<std::uint8_t>(r.depth_mm.size(), 0)};
  for (std::uint32_t p : pixels) mask.pixels[p] = 255;
  return mask;
}

}  // namespace

void write_bop_scene(const fs::path& dir, const BinRecord& bin) {
  const RenderedBin& r = bin.render;
  for (const char* sub : {"depth", "gray", "cloud"}) fs::create_directories(dir / sub);
  const GrayImage<std::uint16_t> depth = depth_png(r, bin.depth_scale);
  write_png(dir / "depth" / "000000.png", depth);
  write_png(dir / "gray" / "000000.png", GrayImage<std::uint8_t>{r.width, r.height, r.gray});
  if (bin.write_cloud) write_point_cloud_ply(dir / "cloud" / "000000.ply", visible_cloud(r));

  bop::SceneCamera cam;
  cam.K << bin.camera.fx, 0, bin.camera.cx, 0, bin.camera.fy, bin.camera.cy, 0, 0, 1;
  cam.depth_scale = bin.depth_scale;
  cam.world_to_camera = bop::Pose::from(bin.world_to_camera);
  bop::write_scene_cameras(dir / "scene_camera.json", {{0, cam}});

  if (bin.obj_ids.size() != bin.part_to_camera.size())
    throw InputError("bin writer: an obj_id is needed for every part");
  if (bin.silhouettes.size() != bin.part_to_camera.size())
    throw InputError("bin writer: every part's silhouette is needed (BinRenderer::silhouettes)");
  std::vector<bop::GroundTruth> gt;
  std::vector<bop::GroundTruthInfo> info;
  std::vector<BopVisibility> visibility;  // per part; with the visible pixels for the masks
  for (std::size_t i = 0; i < bin.part_to_camera.size(); ++i) {
    gt.push_back({bin.obj_ids[i], bop::Pose::from(bin.part_to_camera[i])});
    visibility.push_back(visibility_of(bin, depth, i, bin.write_masks));
    info.push_back(info_of(bin.silhouettes[i], r.width, visibility.back()));
  }
  bop::write_scene_gt(dir / "scene_gt.json", {{0, gt}});
  bop::write_scene_gt_info(dir / "scene_gt_info.json", {{0, info}});

  // calc_masks.py: mask/ the part alone, mask_visib/ its pixels visible by the rule above.
  if (bin.write_masks) {
    fs::create_directories(dir / "mask");
    fs::create_directories(dir / "mask_visib");
    for (std::size_t part = 0; part < bin.part_to_camera.size(); ++part) {
      const std::string name = fmt::format("000000_{:06d}.png", part);
      write_png(dir / "mask" / name, mask_of(r, bin.silhouettes[part].pixels));
      write_png(dir / "mask_visib" / name, mask_of(r, visibility[part].visible));
    }
  }
}

}  // namespace binpick

// Where each part is drawn alone for its unoccluded pixel count (BOP's px_count_all): every
// part gets a tile of an atlas image the size of the image rectangle its projection can cover,
// so one render pass of the atlas replaces one full-image render per part. Tiles are placed on
// shelves; when the atlas is full the rest go to the next batch (another pass of the same atlas).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "synth/render/bin_camera.hpp"

namespace binpick {

struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool empty() const { return w <= 0 || h <= 0; }
};

// The pixels of the image the part can cover, from its vertices' projections (a triangle's
// projection lies in the convex hull of its corners' projections when they are in front of the
// camera), padded by a pixel and clipped to the image. A part reaching the near plane gets the
// whole image (clipping changes its outline); one entirely outside the view, an empty rect.
PixelRect projected_rect(const Mesh& part, const Eigen::Isometry3d& part_to_camera,
                         const RenderCamera& camera);

struct AtlasTile {
  int part = 0;
  PixelRect image;           // the part's rectangle in the image
  int atlas_x = 0, atlas_y = 0;  // where that rectangle goes in the atlas
};

struct AtlasBatch {
  std::vector<AtlasTile> tiles;
  int width = 0, height = 0;  // the atlas rows and columns used
};

// Shelf packing of the non-empty rects (index = part) into atlases of at most
// atlas_width x atlas_height; every rect must fit in one atlas (image rects do when the atlas
// is at least the image's size).
std::vector<AtlasBatch> pack_atlas(const std::vector<PixelRect>& rects, int atlas_width,
                                   int atlas_height);

}  // namespace binpick

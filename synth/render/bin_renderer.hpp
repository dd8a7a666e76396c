// Rendering a synthetic bin as the sensor sees it (paper, section III-A): all parts (one
// instanced draw per kind of part) and the bin itself in one Vulkan raster pass into a
// z-buffer, a part-id and a normal attachment, then a compute pass to depth (equation 1),
// points, normals, intensity and per-part visible pixels; optionally each part alone (tiles of
// an atlas, one more pass) for its unoccluded pixels and, if asked, its depth there. The bin's pixels are surfaces like any
// other (depth, intensity) but belong to no part: instance -1, counted for none. Without a bin
// mesh only the parts are drawn (as in the paper's figure 2).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "synth/bin/bin_model.hpp"
#include "synth/render/bin_camera.hpp"
#include "synth/render/part_silhouette.hpp"

namespace binpick {

namespace vkrt {
class Context;
}

struct RenderOptions {
  double noise_sigma_mm = 0;   // Gaussian noise along each viewing ray; 0: none (exactly)
  std::uint64_t seed = 0;      // same seed, same noise
  bool count_unoccluded = true;  // fill px_all and bbox_all (one more raster + compute pass)
  // Also fill silhouettes (each part alone: its pixels and depth, from the same pass; needs
  // count_unoccluded).
  bool silhouettes = false;
};

struct RenderedBin {
  std::uint32_t width = 0, height = 0;
  std::vector<float> depth_mm;          // z along the optical axis, 0 = no surface
  std::vector<std::uint8_t> gray;       // 0.2 ambient + 0.8 Lambert, light at the camera; 0 = none
  std::vector<float> points;            // 3 a pixel, camera frame, mm (0 where none)
  std::vector<float> normals;           // 3 a pixel, camera frame, unit, facing the camera
  std::vector<std::int32_t> instance;   // index of the part seen at each pixel, -1 none
  std::vector<std::uint32_t> px_visible;  // per part: pixels where it is seen
  std::vector<std::uint32_t> px_all;      // per part: pixels it covers alone (empty if not counted)
  // BOP [x, y, w, h] as bop_toolkit computes them (w = max x - min x); [-1, -1, -1, -1] for a
  // part with no pixel. bbox_all is empty when not counted.
  std::vector<std::array<int, 4>> bbox_visible, bbox_all;
  // Per part drawn alone, when asked (RenderOptions::silhouettes): the image pixels it covers
  // and its depth there; empty otherwise.
  std::vector<PartSilhouette> silhouettes;
};

// Milliseconds of the stages of the last render (wall clock, each waits for the device).
struct RenderTimings {
  double raster_ms = 0;    // scene pass + copies of the attachments
  double compute_ms = 0;   // bin_gbuffer.comp
  double readback_ms = 0;  // device buffers into RenderedBin
  double coverage_ms = 0;  // atlas packing, passes and bin_coverage.comp (px_all)
  double silhouettes_ms = 0;  // of coverage_ms: reading the silhouettes out of the atlas
};

// What one render shows: the parts (poses and kinds) and where the bin is.
struct RenderScene {
  std::vector<Eigen::Isometry3d> part_to_camera;  // mm
  std::vector<int> kinds;                         // per part, its mesh; empty: all the first
  // The bin mesh is in the world frame: world -> camera places it. None: no bin is drawn.
  std::optional<Eigen::Isometry3d> world_to_camera;
};

// Pipelines, attachments and buffers for the part meshes, the bin and one camera, reused across
// renders (building them compiles shaders: keep a renderer for a series of bins).
class BinRenderer {
 public:
  // Throws InputError for a mesh without triangles or per-vertex normals, or an unusable
  // camera. cull_back_faces: skip triangles seen from behind, right for a closed mesh whose
  // triangles are counter-clockwise seen from outside (the Mesh contract) and about 25 % faster;
  // pass false for an open or inconsistently wound mesh.
  explicit BinRenderer(const Mesh& part, const RenderCamera& camera, bool cull_back_faces = true);
  BinRenderer(const Mesh& part, const RenderCamera& camera, bool cull_back_faces, vkrt::Context& ctx);
  // Several kinds of part (kind k = parts[k]) and the bin (none: parts only). The bin is drawn
  // with back faces culled only if it is closed (not double_sided).
  BinRenderer(const std::vector<Mesh>& parts, const BinModel* bin, const RenderCamera& camera,
              bool cull_back_faces = true);
  BinRenderer(const std::vector<Mesh>& parts, const BinModel* bin, const RenderCamera& camera,
              bool cull_back_faces, vkrt::Context& ctx);
  ~BinRenderer();
  BinRenderer(const BinRenderer&) = delete;
  BinRenderer& operator=(const BinRenderer&) = delete;

  // Parts of the first kind, no bin.
  RenderedBin render(const std::vector<Eigen::Isometry3d>& part_to_camera,
                     const RenderOptions& options = {});
  RenderedBin render_scene(const RenderScene& scene, const RenderOptions& options = {});
  // Only each part drawn alone (RenderOptions::silhouettes without the scene pass, which costs
  // as much again): what BOP's pose errors render, the model at one pose at a time. The bin of
  // the scene, if any, is not drawn.
  std::vector<PartSilhouette> silhouettes(const RenderScene& scene);
  const RenderTimings& last_timings() const { return timings_; }
  const RenderCamera& camera() const { return camera_; }

 private:
  struct Device;  // the Vulkan objects (bin_renderer.cpp)
  // The image rectangle each part can cover (bin_atlas.hpp).
  std::vector<PixelRect> part_rects(const RenderScene& scene, const std::vector<int>& kinds) const;
  RenderCamera camera_;
  std::vector<Mesh> parts_;
  std::unique_ptr<Device> device_;
  RenderTimings timings_;
};

// One render with a fresh renderer (shader compilation included).
RenderedBin render_bin(const Mesh& part, const std::vector<Eigen::Isometry3d>& part_to_camera,
                       const RenderCamera& camera, const RenderOptions& options = {});

}  // namespace binpick

// The in-plane search of thin parts (DetectParams::plane_search; kernels/plane_search.cl;
// docs/detect/refine.md, "The in-plane search").
//
// Why: sheet metal lying on sheet metal is a plane with steps of one thickness. Voting on
// surface features finds the plane but not where the part lies in it (a pose shifted or turned
// in the plane fits the surface as well), and the edge step (edge_step.hpp) can only rank the
// candidates voting gives. The search moves each candidate over the plane, turns it about the
// sheet's normal through the whole turn, and keeps the pose whose edges the sensor sees step
// down most (the mean clamped excess depth at the edge probes, edge_step_scores). Coarse first
// (every kCoarseStride-th probe, kCoarseAngles turns, shifts of a quarter of the span), then
// fine around the kFineStarts best coarse poses, with every probe. The pose found is refined and verified as an
// extra candidate beside the voted one, so a right voted pose is never lost.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "host/core/mesh.hpp"
#include "host/runtime/cl/cl_buffer.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

inline constexpr std::uint32_t kCoarseStride = 8;
inline constexpr int kCoarseAngles = 90;        // 4 degree steps over the whole turn
inline constexpr int kShiftSteps = 4;           // coarse shifts: +-4 steps of span / 4 a side
inline constexpr int kFineStarts = 3;
inline constexpr int kFineDivisions = 4;        // fine steps: a quarter of the coarse ones,
inline constexpr int kFineSteps = 2;            // +-2 of them: half a coarse step each way

// The edge probes and the model's surface points on the device, and the sheet's frame.
struct PlaneSearchModel {
  std::uint32_t probes = 0;            // edge probes and surface points
  ocl::Buffer<cl_float4> points, normals;  // model frame; w = 1 for surface points
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // the sheet's normal, model frame
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // turns are about this model point
};

// The sheet's normal: the least-variance axis of the model points about `centre`.
Eigen::Vector3d sheet_normal(const PointCloud& model_points, const Eigen::Vector3d& centre);

// Uploads the edge probes, then the model points (both with normals; InputError otherwise).
PlaneSearchModel upload_plane_search_model(ocl::Device& dev, const PointCloud& edge_probes,
                                           const PointCloud& model_points,
                                           const Eigen::Vector3d& centre);

// Routine: the depth the search reads, one float a pixel (z, 0 where the point image has no
// data; kernels/plane_search.cl says why), from a point image on the device (float4 a pixel).
ocl::Buffer<float> point_depths(ocl::Device& dev, const ocl::Buffer<float>& points,
                                const bp_camera& cam);
// Reference: the same from a host point image.
std::vector<float> point_depths_reference(const std::vector<float>& points);

// Noisy depth. A sheet on a sheet steps down by one thickness at its edges, and a depth image
// whose noise is deeper than half that drowns the step: the search then reads the points moved
// to their low-passed depth (scene_lowpass.hpp: lowpass_points), the noise averaged over the
// widest box whose half-width is less than the edge probes' margin beyond the edges (at the
// pixel size of the farthest part searched), so that no probe's box reaches the sheet's own
// depth. noise: the image's depth noise (sigma, mm; depth_noise.hpp); thickness: the sheet's
// (the model's thinnest extent). Figures: docs/decisions/2026-12-01-plane-search-lowpass.md.
bool search_reads_lowpass(double noise, double thickness);
// The box's radius in pixels for an edge-probe margin and a pixel width (mm); 0: no box (a
// pixel as wide as the margin), at most 64.
int search_lowpass_radius(double margin, double pixel);

// Routine: the edge step score of each pose (model to camera, mm) over every stride-th probe
// on a depth image on the device (point_depths): kernels/plane_search.cl says what it is.
std::vector<float> edge_step_scores(ocl::Device& dev, const ocl::Buffer<float>& depth,
                                    const bp_camera& cam, const PlaneSearchModel& model,
                                    const std::vector<Eigen::Isometry3d>& poses,
                                    std::uint32_t stride, float tolerance);
// Reference: the same arithmetic in plain C++ on a host point image.
// probes: the edge probes, then the surface points (from index edge_probes on).
std::vector<float> edge_step_scores_reference(const std::vector<float>& points,
                                              const bp_camera& cam, const PointCloud& probes,
                                              std::size_t edge_probes,
                                              const std::vector<Eigen::Isometry3d>& poses,
                                              std::uint32_t stride, float tolerance);

// The pose turned by `angle` (radians) about the sheet's normal through the centre, and the
// centre moved by (a, b) along two fixed axes of the plane (mm).
Eigen::Isometry3d in_plane_pose(const Eigen::Isometry3d& pose, const Eigen::Vector3d& axis,
                                const Eigen::Vector3d& centre, double angle, double a, double b);

struct PlaneSearchResult {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  float score = -1;        // its edge step score (-1: too few probes at every pose)
  float start_score = -1;  // the starting pose's
};

// The search about each start over shifts within +-span (mm) and the whole turn, on a depth
// image from point_depths; one launch a stage for all starts. A result holds its start itself
// when no pose scores higher.
std::vector<PlaneSearchResult> plane_search(ocl::Device& dev, const ocl::Buffer<float>& depth,
                                            const bp_camera& cam, const PlaneSearchModel& model,
                                            const std::vector<Eigen::Isometry3d>& starts,
                                            double span, float tolerance);

// The searches done on one image so far. With a second round of hypotheses, the candidates are
// refined and ranked again with the first round's in front (detector.cpp, in_rounds), and a
// start's search depends only on the start and the image: the first round's are not redone
// (docs/decisions/2026-11-28-plane-search-memo.md).
struct PlaneSearchMemo {
  std::vector<Eigen::Isometry3d> starts;
  std::vector<PlaneSearchResult> found;
};

// plane_search over the starts not in the memo: the memo's results stand for the longest
// prefix of `starts` that equals (bit for bit) the start the memo holds at that position; the
// memo then holds all of `starts`. The same results as plane_search on all of them.
std::vector<PlaneSearchResult> plane_search(PlaneSearchMemo& memo, ocl::Device& dev,
                                            const ocl::Buffer<float>& depth, const bp_camera& cam,
                                            const PlaneSearchModel& model,
                                            const std::vector<Eigen::Isometry3d>& starts,
                                            double span, float tolerance);

}  // namespace binpick

// The text forms of --roi and --bin (docs/cli.md), as they appear on the command line and in a
// --params file:
//   --roi camera:x0,y0,z0,x1,y1,z1   a box in the camera frame (mm)
//   --roi bin:x0,y0,z0,x1,y1,z1      a box in the bin's frame (mm; needs a bin, bin_fit.hpp)
//   --bin none | auto | W,D,H        no bin; find it; find a bin of this interior size (mm)
// and the bin of a fixed cell, given (--bin-pose FILE, bin_pose_file.hpp).
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

namespace binpick {

struct RoiSpec {
  enum class Frame { camera, bin } frame = Frame::camera;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  // mm, lo < hi
};

struct BinSpec {
  enum class Mode { none, find, sized, given } mode = Mode::none;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // sized, given: interior W x D x H (mm)
  // given: the bin's frame (bin_fit.hpp) in the camera frame, p_camera = R p_bin + t (mm).
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// Empty text: no ROI. Otherwise InputError("'TEXT': expected ...") for anything malformed: an
// unknown frame, not six numbers, a NaN or infinite value, or a box with lo >= hi on an axis.
std::optional<RoiSpec> parse_roi(const std::string& text);
// InputError("'TEXT': expected ...") for anything but none, auto, three positive sizes or
// mesh:FILE (read here: bin_mesh_interior.hpp; its errors prefixed with 'TEXT').
BinSpec parse_bin(const std::string& text);

}  // namespace binpick

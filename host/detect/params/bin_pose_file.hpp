// The bin of a fixed cell, given once (--bin-pose FILE; docs/formats.md, "Bin pose file"): cells
// calibrate where their bin stands, so detection takes it instead of finding it in each image.
// A JSON object:
//   "cam_R_bin":   the bin frame's rotation into the camera frame, 9 numbers, row-major
//   "cam_t_bin":   the bin frame's origin (the interior floor's centre) in the camera frame, mm
//   "interior_mm": the interior W, D, H, mm
// p_camera = cam_R_bin p_bin + cam_t_bin, as BOP's cam_R_m2c and cam_t_m2c. The bin frame is
// bin_fit.hpp's: z up out of the bin, x along W. Other keys are ignored (a note, a date).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "host/detect/params/bin_spec.hpp"

namespace binpick {

// A spec of Mode::given. R is taken to the nearest rotation (a calibration written with a few
// digits is not exactly orthonormal); with W < D the frame is turned a quarter about z so that
// x lies along the longer side. InputError("NAME: ...") for malformed JSON, a missing or
// non-numeric key, a non-finite value, a matrix further than 0.01 from a rotation, or a size
// that is not positive.
BinSpec parse_bin_pose(std::string_view text, const std::string& name);
// The same from a file (InputError naming it when it cannot be read).
BinSpec read_bin_pose(const std::filesystem::path& path);

// The file's text for a bin frame (R, t) of this interior, and the file written atomically.
std::string bin_pose_text(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                          const Eigen::Vector3d& interior);
void write_bin_pose(const std::filesystem::path& path, const Eigen::Matrix3d& R,
                    const Eigen::Vector3d& t, const Eigen::Vector3d& interior);

}  // namespace binpick

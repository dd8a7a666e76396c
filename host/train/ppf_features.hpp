// Point pair features (Drost 2010) of a cloud with normals, discretised with bp_ppf_quant
// (kernels/binpick_shared.h): the key of every ordered pair (m_r, m_i) and its alpha_m.
//
// Conventions (the same on the device, see bp_ppf_pair8):
//   d = m_i - m_r, F = (|d|, angle(n_r, d), angle(n_i, d), angle(n_r, n_i)), angles in [0, pi];
//   pairs with |d| > max_distance or |d| <= BP_PPF_MIN_DIST_RATIO * max_distance (coincident
//   points: undefined angles) and m_r with itself get BP_PPF_NO_KEY;
//   alpha_m: R takes n_r onto +x by the rotation about n_r x e_x (a half turn about z if n_r is
//   -x), and alpha_m = atan2(z, y) of R d in [-pi, pi) (0 when R d is on the x axis).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "host/core/mesh.hpp"
#include "host/runtime/cl/cl_device.hpp"
#include "kernels/binpick_shared.h"

namespace binpick {

// The discretisation of the paper: distance_steps bins up to max_distance, angle_step =
// 2 pi / angle_steps for the feature angles (ceil(angle_steps / 2) bins in [0, pi]) and for
// alpha (angle_steps bins). Throws InputError for a non-positive or non-finite max_distance,
// distance_steps outside [1, 1000], angle_steps outside [4, 360], or more than 2^24 keys.
bp_ppf_quant make_ppf_quant(float max_distance, std::uint32_t distance_steps,
                            std::uint32_t angle_steps);

// Keys and alphas of all n x n ordered pairs, row r = reference point m_r.
struct PairFeatures {
  std::size_t n = 0;
  std::vector<std::uint32_t> keys;  // n * n, BP_PPF_NO_KEY for skipped pairs
  std::vector<float> alphas;        // n * n
};

// Device routine (kernels/ppf_features.cl), for checking and inspection: it stores n^2 pairs,
// so n is limited to 8192. Normals are required (scaled to unit length first); non-finite
// values are InputError.
PairFeatures ppf_pair_features(ocl::Device& dev, const PointCloud& cloud, const bp_ppf_quant& quant);

// The undiscretised feature of one pair, computed with Eigen (the reference).
struct PairFeature {
  bool valid = false;       // false: skipped (see above)
  Eigen::Vector4f f{0, 0, 0, 0};  // |d|, angle(n_r, d), angle(n_i, d), angle(n_r, n_i)
  float alpha = 0;
  std::uint32_t key = BP_PPF_NO_KEY;
};
PairFeature ppf_pair_feature_reference(const Eigen::Vector3f& pr, const Eigen::Vector3f& nr,
                                       const Eigen::Vector3f& pi, const Eigen::Vector3f& ni,
                                       const bp_ppf_quant& quant);

// alpha_m of the reference point's unit normal nr and d = m_i - m_r (the convention above).
float ppf_alpha_reference(const Eigen::Vector3f& nr, const Eigen::Vector3f& d);

// Plain C++ version of ppf_pair_features.
PairFeatures ppf_pair_features_reference(const PointCloud& cloud, const bp_ppf_quant& quant);

// Shared input check of the PPF routines: InputError for non-finite points, missing, zero or
// non-finite normals, more than max_points points; returns the cloud with unit normals.
PointCloud ppf_input(const PointCloud& cloud, std::size_t max_points, const char* what);

}  // namespace binpick

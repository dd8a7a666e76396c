#include "host/detect/params/bin_pose_file.hpp"

#include <cmath>
#include <vector>

#include <Eigen/SVD>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/atomic_file.hpp"
#include "host/core/error.hpp"
#include "host/core/read_file.hpp"

namespace binpick {
namespace {

using Json = nlohmann::json;

std::vector<double> numbers(const Json& json, const char* key, std::size_t count,
                            const std::string& name) {
  const auto bad = [&](const std::string& why) {
    return InputError(fmt::format("{}: \"{}\" {}", name, key, why));
  };
  if (!json.contains(key)) throw bad(fmt::format("is missing ({} numbers expected)", count));
  const Json& v = json.at(key);
  if (!v.is_array() || v.size() != count) throw bad(fmt::format("must be {} numbers", count));
  std::vector<double> out;
  for (const Json& x : v) {
    if (!x.is_number()) throw bad(fmt::format("must be {} numbers", count));
    out.push_back(x.get<double>());
    if (!std::isfinite(out.back())) throw bad("holds a value that is not finite");
  }
  return out;
}

}  // namespace

BinSpec parse_bin_pose(std::string_view text, const std::string& name) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::exception& e) {
    throw InputError(fmt::format("{}: not a bin pose (JSON: {})", name, e.what()));
  }
  if (!json.is_object())
    throw InputError(name + ": a bin pose is a JSON object with cam_R_bin, cam_t_bin and "
                            "interior_mm");
  const std::vector<double> r = numbers(json, "cam_R_bin", 9, name);
  const std::vector<double> t = numbers(json, "cam_t_bin", 3, name);
  const std::vector<double> size = numbers(json, "interior_mm", 3, name);
  BinSpec spec;
  spec.mode = BinSpec::Mode::given;
  const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
  if (!((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 0.01 &&
        R.determinant() > 0))
    throw InputError(name + ": \"cam_R_bin\" is not a rotation (orthonormal, determinant 1)");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  spec.R = svd.matrixU() * svd.matrixV().transpose();
  spec.t = Eigen::Vector3d(t[0], t[1], t[2]);
  spec.size = Eigen::Vector3d(size[0], size[1], size[2]);
  if (!(spec.size.minCoeff() > 0))
    throw InputError(name + ": \"interior_mm\" must be three positive sizes W, D, H");
  if (spec.size.x() < spec.size.y()) {  // x along the longer side: new x = old y, new y = -old x
    spec.R = spec.R * Eigen::Matrix3d((Eigen::Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished());
    std::swap(spec.size.x(), spec.size.y());
  }
  return spec;
}

BinSpec read_bin_pose(const std::filesystem::path& path) {
  return parse_bin_pose(read_file_bytes(path), path.string());
}

std::string bin_pose_text(const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                          const Eigen::Vector3d& interior) {
  Json json;
  json["cam_R_bin"] = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2)};
  json["cam_t_bin"] = {t.x(), t.y(), t.z()};
  json["interior_mm"] = {interior.x(), interior.y(), interior.z()};
  return json.dump(2) + "\n";
}

void write_bin_pose(const std::filesystem::path& path, const Eigen::Matrix3d& R,
                    const Eigen::Vector3d& t, const Eigen::Vector3d& interior) {
  const std::string text = bin_pose_text(R, t, interior);
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace binpick

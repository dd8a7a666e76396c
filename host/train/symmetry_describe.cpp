#include "host/train/symmetry_describe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>

namespace binpick {
namespace {

// Rounded to `step`, without a minus sign on zero.
std::string number(double v, double step) {
  const double r = std::round(v / step) * step;
  return fmt::format("{:g}", r == 0 ? 0.0 : r);
}

// The unit direction rounded to 1e-4, with its first largest component positive: rounded first,
// so that (0.7071, -0.7071, 0) does not print as its negative when rounding favours y.
Eigen::Vector3d canonical_rounded(const Eigen::Vector3d& v) {
  Eigen::Vector3d r = (v.normalized() * 1e4).array().round() / 1e4;
  Eigen::Index k;
  r.cwiseAbs().maxCoeff(&k);
  if (r[k] < 0) r = -r;
  return r;
}

std::string point(const Eigen::Vector3d& v, double step) {
  return fmt::format("({}, {}, {})", number(v.x(), step), number(v.y(), step), number(v.z(), step));
}

std::string direction(const Eigen::Vector3d& v) { return point(canonical_rounded(v), 1e-4); }

struct Axis {
  Eigen::Vector3d direction;
  double smallest_angle;  // rad, of the rotations about it
  int order() const { return int(std::lround(2 * std::numbers::pi / smallest_angle)); }
};

}  // namespace

std::string describe_symmetries(const PartSymmetries& s) {
  const auto& round = s.continuous;
  if (round.size() >= 2) return "any rotation (a sphere)";
  if (round.size() == 1) {
    const Eigen::Vector3d a = round[0].axis.normalized();
    std::string text =
        "continuous about " + direction(a) + " through " + point(round[0].offset, 1e-3);
    for (const auto& m : s.discrete)
      if (a.dot(m.topLeftCorner<3, 3>() * a) < 0) return text + ", ends swapped by a half turn";
    return text;
  }
  if (s.discrete.empty()) return "none found";

  std::vector<Axis> axes;
  const double same = std::cos(std::numbers::pi / 180);
  for (const auto& m : s.discrete) {
    const Eigen::AngleAxisd r(Eigen::Matrix3d(m.topLeftCorner<3, 3>()));
    if (!(r.angle() > 1e-9)) continue;
    const double angle = std::min(r.angle(), 2 * std::numbers::pi - r.angle());
    auto it = std::find_if(axes.begin(), axes.end(), [&](const Axis& x) {
      return std::fabs(x.direction.dot(r.axis())) >= same;
    });
    if (it == axes.end())
      axes.push_back({canonical_rounded(r.axis()), angle});
    else
      it->smallest_angle = std::min(it->smallest_angle, angle);
  }
  // Highest order first; axes of one order in descending (x, y, z).
  std::stable_sort(axes.begin(), axes.end(), [](const Axis& a, const Axis& b) {
    if (a.order() != b.order()) return a.order() > b.order();
    const Eigen::Vector3d& u = a.direction;
    const Eigen::Vector3d& v = b.direction;
    return std::tie(u.x(), u.y(), u.z()) > std::tie(v.x(), v.y(), v.z());
  });
  std::string text = fmt::format("{} discrete", s.discrete.size());
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const bool first_of_order = i == 0 || axes[i - 1].order() != axes[i].order();
    text += first_of_order ? fmt::format("{} {}-fold about ", i == 0 ? ":" : ";", axes[i].order())
                           : ", ";
    text += direction(axes[i].direction);
  }
  return text;
}

}  // namespace binpick

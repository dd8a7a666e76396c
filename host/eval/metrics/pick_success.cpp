#include "host/eval/metrics/pick_success.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/angles.hpp"
#include "host/core/error.hpp"
#include "host/core/gripper.hpp"
#include "host/core/read_file.hpp"
#include "host/formats/grasps/grasp_json.hpp"

namespace binpick::eval {
namespace {

constexpr double kGraspPointRatio = 0.05;  // of the diameter: the grasp's position tolerance
constexpr double kGraspAngleDeg = 15;      // the grasp's approach tolerance
constexpr double kTouchRatio = 0.02;       // of the diameter: deeper inside the gripper collides
constexpr int kTurnSteps = 72;             // continuous symmetries: turns tried, 5 degrees apart

std::vector<double> numbers(const std::string& cell) {
  std::vector<double> out;
  std::istringstream in(cell);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

// The model-frame transforms that leave the part unchanged: the identity, its discrete
// symmetries, and turns about each continuous axis.
std::vector<Eigen::Isometry3d> symmetry_transforms(const PartSymmetries& s) {
  std::vector<Eigen::Isometry3d> out{Eigen::Isometry3d::Identity()};
  for (const Eigen::Matrix4d& m : s.discrete) out.emplace_back(Eigen::Isometry3d(m));
  for (const ContinuousSymmetry& c : s.continuous)
    for (int k = 1; k < kTurnSteps; ++k) {
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      t.linear() = Eigen::AngleAxisd(2 * std::numbers::pi * k / kTurnSteps, c.axis.normalized()).toRotationMatrix();
      t.translation() = c.offset - t.linear() * c.offset;
      out.push_back(t);
    }
  return out;
}

}  // namespace

std::vector<PickRow> read_first_picks(const std::filesystem::path& path) {
  std::istringstream in(read_file_bytes(path));
  std::string line;
  std::getline(in, line);
  if (line.rfind("scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,clearance,score,gripper", 0) != 0)
    throw InputError(path.string() + ": not a picks file of binpick detect --picks (its header)");
  std::vector<PickRow> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    // Eleven plain columns, then the gripper's text in double quotes (it holds commas).
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string c; f.size() < 11 && std::getline(cells, c, ',');) f.push_back(c);
    const auto bad = [&](const char* what) {
      return InputError(fmt::format("{}: line {}: {}", path.string(), n, what));
    };
    std::string rest;
    std::getline(cells, rest);
    std::string gripper;
    std::size_t at = 1;
    for (; !rest.empty() && rest[0] == '"' && at < rest.size(); ++at) {
      if (rest[at] != '"') {
        gripper += rest[at];
      } else if (at + 1 < rest.size() && rest[at + 1] == '"') {
        gripper += '"';
        ++at;
      } else {
        break;
      }
    }
    if (f.size() < 11 || rest.empty() || rest[0] != '"' || at >= rest.size())
      throw bad("13 columns expected, the gripper and the reason in double quotes");
    f.push_back(gripper);
    if (f[4] != "1") continue;
    PickRow r;
    try {
      r.scene_id = std::stoi(f[0]);
      r.im_id = std::stoi(f[1]);
      r.obj_id = std::stoi(f[2]);
      r.rank = std::stoi(f[3]);
    } catch (const std::exception&) {
      throw bad("scene_id, im_id, obj_id and rank must be integers");
    }
    const auto R = numbers(f[6]), t = numbers(f[7]);
    if (R.size() != 9 || t.size() != 3) throw bad("R needs 9 numbers and t 3");
    Eigen::Matrix3d m;
    for (int k = 0; k < 9; ++k) m(k / 3, k % 3) = R[std::size_t(k)];
    if (!m.allFinite() || !(m.transpose() * m).isApprox(Eigen::Matrix3d::Identity(), 1e-4))
      throw bad("R is not a rotation");
    r.grasp = bop::Pose{m, Eigen::Vector3d(t[0], t[1], t[2])}.isometry();
    r.gripper = f[11];
    rows.push_back(r);
  }
  return rows;
}

std::optional<Eigen::Vector3d> synth_bin_interior(const std::filesystem::path& root) {
  const auto file = root / "synth.json";
  if (!std::filesystem::is_regular_file(file)) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(read_file_bytes(file));
    const auto& s = j.at("bin_size_mm");
    return Eigen::Vector3d(s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>());
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // a synth.json of another version: no bin to check against
  }
}

std::string PickOutcome::verdict() const {
  if (!right) return "on a wrong detection";
  if (!on_grasp) return "off the true grasp";
  if (!collision.empty()) return "hits " + collision;
  return "succeeds";
}

PickSummary evaluate_picks(const Dataset& dataset, const EvalSummary& summary,
                           const std::vector<PickRow>& picks, const EvalVertices& vertices,
                           const std::optional<Eigen::Vector3d>& bin_interior,
                           const OperatingPoint& right) {
  PickSummary out;
  for (const auto& [key, image] : dataset.images) out.images += !image.gt.empty();
  std::map<std::tuple<int, int, int, int>, const HypothesisResult*> results;
  for (const HypothesisResult& h : summary.results)
    results[{h.scene_id, h.im_id, h.obj_id, h.rank}] = &h;
  std::map<ImageKey, bool> picked;
  for (const PickRow& p : picks) {
    const auto found = results.find({p.scene_id, p.im_id, p.obj_id, p.rank});
    if (found == results.end())
      throw InputError(fmt::format("a pick of scene {} image {} obj_id {} rank {}: no such row in "
                                   "the results", p.scene_id, p.im_id, p.obj_id, p.rank));
    const HypothesisResult& h = *found->second;
    const auto info = dataset.models.find(p.obj_id);
    const auto verts = vertices.by_object.find(p.obj_id);
    if (info == dataset.models.end() || verts == vertices.by_object.end())
      throw InputError(fmt::format("a pick of obj_id {}: the dataset has no such model", p.obj_id));
    const Gripper gripper = parse_gripper(p.gripper);
    if (gripper.kind != Grasp::Kind::suction) continue;  // not judged (see the header)
    const EvalImage& image = dataset.images.at({p.scene_id, p.im_id});
    const double d = info->second.diameter;
    PickOutcome o;
    o.pick = p;
    o.right = h.gt_index >= 0 && h.translation_pct <= right.translation_pct &&
              h.rotation_deg <= right.rotation_deg;
    // The grasp in the model frame (from the detection's pose), at the true pose, the nearest of
    // the part's symmetric equivalents.
    Grasp g;
    const Eigen::Isometry3d in_model = bop::Pose{h.row.R, h.row.t}.isometry().inverse() * p.grasp;
    g.point = in_model.translation();
    g.approach = in_model.linear().col(2);
    g.closing = in_model.linear().col(0);
    g.size = gripper.a;
    if (h.gt_index >= 0) {
      const bop::GroundTruth& gt = image.gt[std::size_t(h.gt_index)];
      const Eigen::Isometry3d truth = gt.model_to_camera.isometry();
      for (const Eigen::Isometry3d& s : symmetry_transforms(info->second.symmetries)) {
        const Eigen::Vector3d point = truth * (s * g.point);
        const Eigen::Vector3d approach = truth.linear() * s.linear() * g.approach;
        const double angle = std::acos(std::clamp(approach.dot(p.grasp.linear().col(2)), -1.0, 1.0));
        if ((point - p.grasp.translation()).norm() <= kGraspPointRatio * d &&
            angle <= kGraspAngleDeg * kDeg)
          o.on_grasp = true;
      }
    }
    // The gripper at the planned grasp against every part at its true pose, and the bin.
    const std::vector<GripperSolid> solids = gripper.solids(g);
    const Eigen::Isometry3d to_grasp = p.grasp.inverse();
    const double touch = kTouchRatio * d, reach = gripper.length() + gripper.a + d;
    for (std::size_t k = 0; k < image.gt.size() && o.collision.empty(); ++k) {
      const bop::GroundTruth& gt = image.gt[k];
      if ((gt.model_to_camera.t - p.grasp.translation()).norm() > reach + dataset.models.at(gt.obj_id).diameter)
        continue;
      const auto v = vertices.by_object.find(gt.obj_id);
      if (v == vertices.by_object.end()) continue;
      const bool own = int(k) == h.gt_index;
      for (const Eigen::Vector3d& m : v->second) {
        const Eigen::Vector3d q = to_grasp * (gt.model_to_camera.R * m + gt.model_to_camera.t);
        if (own && q.z() >= -kGraspPointRatio * d) continue;  // the contact: the part's own face
        double inside = 1e30;
        for (const GripperSolid& s : solids) inside = std::min(inside, signed_distance(s, q));
        if (inside < -touch) {
          o.collision = own ? "its own part" : fmt::format("part {} (obj_id {})", k, gt.obj_id);
          break;
        }
      }
    }
    if (o.collision.empty() && bin_interior)
      o.collision = bin_contact(solids, p.grasp, image.camera.world_to_camera.R,
                                image.camera.world_to_camera.t, *bin_interior, touch);
    picked[{p.scene_id, p.im_id}] = true;
    out.success += o.success();
    out.firsts.push_back(o);
  }
  out.picked = picked.size();
  return out;
}

}  // namespace binpick::eval

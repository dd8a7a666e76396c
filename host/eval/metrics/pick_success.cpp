#include "host/eval/metrics/pick_success.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "host/core/angles.hpp"
#include "host/core/error.hpp"
#include "host/core/gripper.hpp"
#include "host/core/read_file.hpp"
#include "host/core/cloud_input.hpp"
#include "host/core/point_grid.hpp"
#include "host/formats/grasps/grasp_json.hpp"
#include "host/formats/mesh/load_model.hpp"
#include "host/train/ppf_model.hpp"
#include "host/train/suction_grasps.hpp"
#include "host/train/surface_sampling.hpp"

namespace binpick::eval {
namespace {

constexpr double kGraspPointRatio = 0.05;  // of the diameter: the cup's travel to the true part
constexpr double kGraspAngleDeg = 15;      // the tilt between the cup's axis and the face it seals on
constexpr std::size_t kPlainColumns = 12;  // of OUT.picks.csv, before the quoted gripper
constexpr double kTouchRatio = 0.02;       // of the diameter: deeper inside the gripper collides

std::vector<double> numbers(const std::string& cell) {
  std::vector<double> out;
  std::istringstream in(cell);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

// Whether the cup of grasp g (model frame of the true part), moved along its approach to the
// first surface facing it under the cup, at most `travel` mm, seals there.
bool seals(const PointCloud& surface, const PointGrid& index, const Grasp& g,
           const SuctionGraspOptions& o, double travel) {
  const Eigen::Vector3d up = -g.approach;  // out of the part, towards the cup
  // Where the cup settles: the surface point facing it nearest its axis, under the cup and
  // within its travel (the points are train's, a refinement voxel apart).
  double nearest = o.cup_diameter / 2;
  std::uint32_t at = std::numeric_limits<std::uint32_t>::max();
  index.near(g.point.cast<float>(), float(travel + o.cup_diameter / 2), [&](std::uint32_t j) {
    const Eigen::Vector3d d = surface.points[j].cast<double>() - g.point;
    const double h = d.dot(up), radial = (d - h * up).norm();
    if (std::abs(h) <= travel && radial < nearest && surface.normals[j].cast<double>().dot(up) > 0)
      nearest = radial, at = j;
  });
  if (at == std::numeric_limits<std::uint32_t>::max()) return false;
  // The cup's lip settles on the face there (a bellows cup follows a face tilted up to
  // kGraspAngleDeg from its axis) and must seal as a generated grasp does.
  const Eigen::Vector3d n = surface.normals[at].cast<double>();
  if (n.dot(up) < std::cos(kGraspAngleDeg * kDeg)) return false;
  return cup_held(index, surface, surface.points[at].cast<double>(), n, o);
}

// Whether parallel jaws at grasp g (model frame of the true part; size the opening) closing
// along its closing axis hold the part: some of it lies between the fingers' pads (within the
// opening, the fingers' depth across it and their length along the approach), and where the jaws
// stop, on either side, its surface faces that jaw within 45 degrees (an antipodal grasp).
bool jaws_hold(const PointCloud& surface, const Grasp& g, const Gripper& jaws, double touch) {
  const Eigen::Vector3d x = g.closing, z = g.approach, y = z.cross(x);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::vector<std::pair<double, double>> between;  // (x, the normal's x) of points between the pads
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    const Eigen::Vector3d d = surface.points[i].cast<double>() - g.point;
    const double qx = d.dot(x), qy = d.dot(y), qz = d.dot(z);
    if (std::abs(qx) > g.size / 2 || std::abs(qy) > jaws.b / 2 || qz < -0.75 * jaws.c || qz > 0.25 * jaws.c)
      continue;
    between.emplace_back(qx, surface.normals[i].cast<double>().dot(x));
    lo = std::min(lo, qx);
    hi = std::max(hi, qx);
  }
  bool left = false, right = false;  // the faces the jaws meet, facing them
  for (const auto& [qx, nx] : between) {
    right = right || (qx >= hi - touch && nx >= std::cos(45 * kDeg));
    left = left || (qx <= lo + touch && nx <= -std::cos(45 * kDeg));
  }
  return left && right;
}

}  // namespace

std::vector<PickRow> read_first_picks(const std::filesystem::path& path) {
  std::istringstream in(read_file_bytes(path));
  std::string line;
  std::getline(in, line);
  if (line.rfind("scene_id,im_id,obj_id,rank,order,grasp,R,t,approach,width,clearance,score,gripper", 0) != 0)
    throw InputError(path.string() + ": not a picks file of binpick detect --picks (its header)");
  std::vector<PickRow> rows;
  for (int n = 2; std::getline(in, line); ++n) {
    // Twelve plain columns, then the gripper's text in double quotes (it holds commas).
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string c; f.size() < kPlainColumns && std::getline(cells, c, ',');) f.push_back(c);
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
    if (f.size() < kPlainColumns || rest.empty() || rest[0] != '"' || at >= rest.size())
      throw bad("14 columns expected, the gripper and the reason in double quotes");
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
    try {
      r.width = std::stod(f[9]);
    } catch (const std::exception&) {
      r.width = 0;
    }
    if (!(r.width > 0 && std::isfinite(r.width))) throw bad("the width must be a positive number of mm");
    r.gripper = f[12];
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

PartSurfaces sample_part_surfaces(const Dataset& dataset, const std::set<int>& obj_ids) {
  PartSurfaces out;
  for (const int obj_id : obj_ids) {
    const auto path = dataset.root / "models" / fmt::format("obj_{:06d}.ply", obj_id);
    const auto info = dataset.models.find(obj_id);
    if (info == dataset.models.end())
      throw InputError(fmt::format("obj_id {}: not in models_info.json", obj_id));
    out[obj_id] = sample_part_surface(load_model(path.string(), {}), info->second.diameter);
  }
  return out;
}

PointCloud sample_part_surface(const Mesh& mesh, double diameter) {
  // Train's dense sample at its refinement voxel (16 a voxel face), not subsampled: the lip
  // finds the surface wherever it is, not where a subsample's lattice happens to put a point.
  const double voxel = PpfTrainParams{}.voxel_ratio * diameter / kFitVoxelDivisor;
  return with_unit_normals(sample_surface(mesh, model_surface_samples(surface_area(mesh), voxel)));
}

PickSummary evaluate_picks(const Dataset& dataset, const EvalSummary& summary,
                           const std::vector<PickRow>& picks, const PartSurfaces& surfaces,
                           const std::optional<Eigen::Vector3d>& bin_interior,
                           const OperatingPoint& right) {
  PickSummary out;
  for (const auto& [key, image] : dataset.images) out.images += !image.gt.empty();
  std::map<std::tuple<int, int, int, int>, const HypothesisResult*> results;
  for (const HypothesisResult& h : summary.results)
    results[{h.scene_id, h.im_id, h.obj_id, h.rank}] = &h;
  std::map<ImageKey, bool> picked;
  std::map<std::pair<int, float>, std::unique_ptr<PointGrid>> grids;
  for (const PickRow& p : picks) {
    const auto found = results.find({p.scene_id, p.im_id, p.obj_id, p.rank});
    if (found == results.end())
      throw InputError(fmt::format("a pick of scene {} image {} obj_id {} rank {}: no such row in "
                                   "the results", p.scene_id, p.im_id, p.obj_id, p.rank));
    const HypothesisResult& h = *found->second;
    const auto info = dataset.models.find(p.obj_id);
    const auto surface = surfaces.find(p.obj_id);
    if (info == dataset.models.end() || surface == surfaces.end())
      throw InputError(fmt::format("a pick of obj_id {}: the dataset has no such model", p.obj_id));
    const Gripper gripper = parse_gripper(p.gripper);
    const EvalImage& image = dataset.images.at({p.scene_id, p.im_id});
    const double d = info->second.diameter;
    PickOutcome o;
    o.pick = p;
    o.right = h.gt_index >= 0 && h.translation_pct <= right.translation_pct &&
              h.rotation_deg <= right.rotation_deg;
    // The grasp in the frame of the true part (the one the detection matched): does its cup
    // seal there, as train's test of a generated grasp asks?
    Grasp g;
    g.kind = gripper.kind;
    g.size = gripper.kind == Grasp::Kind::suction ? gripper.a : p.width;
    const double touch = kTouchRatio * d;
    const SuctionGraspOptions cup = suction_grasp_options(d, PpfTrainParams{}.voxel_ratio * d, gripper.a);
    if (h.gt_index >= 0) {
      const Eigen::Isometry3d in_true =
          image.gt[std::size_t(h.gt_index)].model_to_camera.isometry().inverse() * p.grasp;
      g.point = in_true.translation();
      g.approach = in_true.linear().col(2);
      g.closing = in_true.linear().col(0);
      const double travel = kGraspPointRatio * d;
      if (gripper.kind == Grasp::Kind::parallel) {
        o.on_grasp = jaws_hold(surface->second, g, gripper, touch);
      } else {
        // One grid a part and cell, shared by its picks (the cell follows the cup).
        const float cell = std::max(cup_reach(cup), float(cup.cup_diameter / 2 + travel));
        auto& grid = grids[{p.obj_id, cell}];
        if (!grid) grid = std::make_unique<PointGrid>(surface->second, cell, 3);
        o.on_grasp = seals(surface->second, *grid, g, cup, travel);
      }
    }
    // The gripper at the planned grasp against every part at its true pose, and the bin.
    const std::vector<GripperSolid> solids = gripper.solids(g);
    const Eigen::Isometry3d to_grasp = p.grasp.inverse();
    const double reach = gripper.length() + g.size + gripper.a + d;
    for (std::size_t k = 0; k < image.gt.size() && o.collision.empty(); ++k) {
      const bop::GroundTruth& gt = image.gt[k];
      if ((gt.model_to_camera.t - p.grasp.translation()).norm() > reach + dataset.models.at(gt.obj_id).diameter)
        continue;
      const auto v = surfaces.find(gt.obj_id);
      if (v == surfaces.end()) continue;
      const bool own = int(k) == h.gt_index;
      for (const Eigen::Vector3f& m : v->second.points) {
        const Eigen::Vector3d q = to_grasp * (gt.model_to_camera.R * m.cast<double>() + gt.model_to_camera.t);
        // A cup's contact: the part's own face under it. Open jaws touch nothing of their part.
        if (own && gripper.kind == Grasp::Kind::suction && q.z() >= -kGraspPointRatio * d) continue;
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

// binpick.Detector and binpick.Detection: detection with one model or several in a numpy depth
// image or point cloud, as `binpick detect` does it in a dataset's images.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/detect/shared_scene.hpp"
#include "host/detect/verify/score.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "python/module/bindings.hpp"

namespace binpick::python {
namespace {

using DepthU16 = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>;
using FloatRows = py::array_t<float, py::array::c_style | py::array::forcecast>;

// A detection and the obj_id of the model that found it.
struct FoundPart {
  Detection detection;
  int obj_id = 1;
};

// A Detector per model, ascending by obj_id, and the models they point into (Python may drop its
// Model first).
struct PyDetector {
  struct One {
    std::shared_ptr<const PpfModel> model;
    int obj_id = 1;
    std::unique_ptr<Detector> detector;
  };
  std::vector<One> models;

  // Each model's detections (several: in one shared scene, as `detect` does), by obj_id then
  // score.
  template <class Detect>
  std::vector<FoundPart> run(Detect&& detect) {
    std::vector<FoundPart> found;
    SharedScene shared;
    for (One& one : models)
      for (Detection& d : detect(*one.detector, models.size() > 1 ? &shared : nullptr))
        found.push_back({std::move(d), one.obj_id});
    return found;
  }
};

// The keyword arguments as a --params file's JSON object ('_' stands for '-').
std::string params_text(const py::kwargs& kwargs) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (py::isinstance<py::bool_>(value))
      j[name] = value.cast<bool>();
    else if (py::isinstance<py::int_>(value))
      j[name] = value.cast<long long>();
    else if (py::isinstance<py::float_>(value))
      j[name] = value.cast<double>();
    else if (py::isinstance<py::str>(value))
      j[name] = value.cast<std::string>();
    else
      throw InputError("detection parameter " + name + ": not a bool, number or string");
  }
  return j.dump();
}

// The models as (obj_id, model): one Model (obj_id 1), a list (1, 2, ...) or a dict by obj_id.
std::map<int, std::shared_ptr<PpfModel>> models_of(const py::object& models) {
  std::map<int, std::shared_ptr<PpfModel>> out;
  if (py::isinstance<PpfModel>(models)) {
    out[1] = models.cast<std::shared_ptr<PpfModel>>();
  } else if (py::isinstance<py::dict>(models)) {
    for (const auto& [id, model] : models.cast<py::dict>()) {
      const int obj_id = id.cast<int>();
      if (obj_id < 1) throw InputError("models: obj_id " + std::to_string(obj_id) + " is not positive");
      out[obj_id] = model.cast<std::shared_ptr<PpfModel>>();
    }
  } else {
    int obj_id = 1;
    for (const auto& model : models.cast<py::list>())
      out[obj_id++] = model.cast<std::shared_ptr<PpfModel>>();
  }
  if (out.empty()) throw InputError("models: none given");
  return out;
}

// A 2-D depth image: uint16 read where it lies (depth_mm = raw * depth_scale), float32 (mm)
// stored in steps of 0.1 mm (BOP's usual depth_scale), coarser only where its largest value
// needs it to fit 16 bits.
struct DepthInput {
  std::uint32_t width = 0, height = 0;
  DepthU16 held;         // uint16: the caller's array, read in place
  DepthImage converted;  // float32: the image made of it
  double scale = 1;

  DepthView view() const {
    if (!converted.raw.empty()) return converted;
    return {width, height, {held.data(), std::size_t(width) * height}};
  }
};

DepthInput depth_input(const py::array& depth, double depth_scale) {
  if (depth.ndim() != 2) throw InputError("depth: a 2-D array (height, width) expected");
  const auto h = std::uint32_t(depth.shape(0)), w = std::uint32_t(depth.shape(1));
  if (w == 0 || h == 0) throw InputError("depth: the image is empty");
  DepthInput in;
  in.width = w;
  in.height = h;
  if (depth.dtype().is(py::dtype::of<std::uint16_t>())) {
    if (!(std::isfinite(depth_scale) && depth_scale > 0))
      throw InputError("depth_scale: a positive number expected");
    in.held = depth.cast<DepthU16>();  // the same memory when C-contiguous
    in.scale = depth_scale;
    return in;
  }
  if (!depth.dtype().is(py::dtype::of<float>()))
    throw InputError("depth: uint16 (with depth_scale) or float32 (mm) expected, not " +
                     std::string(py::str(depth.dtype())));
  const auto a = depth.cast<FloatRows>();
  float top = 0;
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    const float v = a.data()[i];
    if (!std::isfinite(v) || v < 0)
      throw InputError("depth: a value that is negative, NaN or infinite (0 is no depth)");
    top = std::max(top, v);
  }
  in.scale = std::max(0.1, double(top) / 65535.0);
  in.converted = DepthImage{w, h, std::vector<std::uint16_t>(std::size_t(w) * h)};
  for (std::size_t i = 0; i < in.converted.raw.size(); ++i)
    in.converted.raw[i] = std::uint16_t(std::lround(double(a.data()[i]) / in.scale));
  return in;
}

std::vector<Eigen::Vector3f> cloud_of(const FloatRows& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3) throw InputError(std::string(what) + ": an (N, 3) array expected");
  std::vector<Eigen::Vector3f> v(std::size_t(a.shape(0)));
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = Eigen::Vector3f(a.at(i, 0), a.at(i, 1), a.at(i, 2));
  return v;
}

py::dict factors_of(const Detection& d) {
  py::dict f;
  const auto rows = score_factors();
  for (std::size_t k = 0; k < rows.size(); ++k) f[rows[k].name] = d.breakdown.factor[k];
  return f;
}

}  // namespace

void bind_detector(py::module_& m) {
  py::class_<FoundPart>(m, "Detection", "A pose found around one highest point")
      .def_property_readonly("R", [](const FoundPart& f) { return f.detection.R; },
                             "rotation, model to camera")
      .def_property_readonly("t", [](const FoundPart& f) { return f.detection.t; },
                             "translation, model to camera, mm")
      .def_readonly("obj_id", &FoundPart::obj_id, "the obj_id of the model that found it")
      .def_property_readonly("score", [](const FoundPart& f) { return f.detection.score(); },
                             "the verified score, in [0, 1]: the ranking")
      .def_property_readonly("fit", [](const FoundPart& f) { return f.detection.fit_score(); },
                             "the score before the look-alike share")
      .def_property_readonly("factors", [](const FoundPart& f) { return factors_of(f.detection); },
                             "the score's factors by name")
      .def_property_readonly("votes", [](const FoundPart& f) { return f.detection.votes; })
      .def_property_readonly("hypothesis", [](const FoundPart& f) { return f.detection.index; },
                             "the highest point's rank by height (0 = highest)")
      .def_property_readonly("reason", [](const FoundPart& f) { return f.detection.reason; })
      .def_property_readonly(
          "pick",
          [](const FoundPart& f) -> py::object {
            const PlannedPick& p = f.detection.pick;
            if (!p.picked) return py::none();
            return py::dict(py::arg("order") = p.order, py::arg("grasp") = p.grasp,
                            py::arg("pose") = Eigen::Matrix4d(p.pose.matrix()),
                            py::arg("approach") = Eigen::Vector3d(p.pose.linear().col(2)),
                            py::arg("width") = p.width, py::arg("clearance") = p.clearance);
          },
          "with picks=True: the pick (order: 1 first; grasp: its index; pose: the grasp's frame "
          "in the camera frame, 4 x 4, mm; approach; width: the cup's diameter or the jaws' "
          "opening, mm; clearance, mm), or None")
      .def_property_readonly("pick_reason", [](const FoundPart& f) { return f.detection.pick.reason; },
                             "why the detection has no pick (picks=True), else \"\"")
      .def("__repr__", [](const FoundPart& f) {
        return "<binpick.Detection obj_id " + std::to_string(f.obj_id) + " score " +
               std::to_string(f.detection.score()) + " hypothesis " +
               std::to_string(f.detection.index) + ">";
      });

  py::class_<PyDetector>(m, "Detector",
                         "Detection with one model or several; keyword arguments are the command "
                         "line's detection parameters ('_' for '-', e.g. ref_ratio=0.2, bin='auto')")
      .def(py::init([](const py::object& models, const py::kwargs& kwargs) {
             DetectParams params;
             apply_params_text(params_text(kwargs), "keyword arguments", params);
             auto d = std::make_unique<PyDetector>();
             for (auto& [obj_id, model] : models_of(models)) {
               auto detector = std::make_unique<Detector>(*model, params);
               d->models.push_back({std::move(model), obj_id, std::move(detector)});
             }
             return d;
           }),
           py::arg("models"),
           "models: a Model (obj_id 1), a list of them (obj_ids 1, 2, ...) or a dict by obj_id")
      .def_property_readonly(
          "params",
          [](const PyDetector& d) {
            return py::module_::import("json").attr("loads")(
                params_json(d.models.front().detector->params()));
          },
          "every detection parameter, as a --params file has them")
      .def_property_readonly(
          "obj_ids",
          [](const PyDetector& d) {
            std::vector<int> ids;
            for (const auto& one : d.models) ids.push_back(one.obj_id);
            return ids;
          },
          "the models' obj_ids, ascending")
      .def(
          "detect",
          [](PyDetector& d, const py::array& depth, const Eigen::Matrix3d& K, double depth_scale) {
            const DepthInput in = depth_input(depth, depth_scale);
            if (!K.allFinite() || !(K(0, 0) > 0 && K(1, 1) > 0))
              throw InputError("K: a 3 x 3 camera matrix with positive focal lengths expected");
            const bp_camera cam = image_camera(K, in.scale, in.width, in.height);
            py::gil_scoped_release release;  // other Python threads run meanwhile
            const std::lock_guard<std::mutex> lock(device_mutex());
            return d.run([&](Detector& detector, SharedScene* shared) {
              return detector.detect(in.view(), cam, nullptr, nullptr, shared);
            });
          },
          py::arg("depth"), py::arg("K"), py::arg("depth_scale") = 1.0,
          "Detections in a depth image, by obj_id and best first: depth is uint16 (depth_mm = "
          "value * depth_scale, BOP's; read in place when C-contiguous) or float32 (mm), 0 where "
          "there is none; K the 3 x 3 camera matrix.")
      .def(
          "detect_cloud",
          [](PyDetector& d, const FloatRows& points, const std::optional<FloatRows>& normals) {
            PointCloud cloud;
            cloud.points = cloud_of(points, "points");
            if (normals) {
              cloud.normals = cloud_of(*normals, "normals");
              if (cloud.normals.size() != cloud.points.size())
                throw InputError("normals: one per point expected");
            }
            py::gil_scoped_release release;
            const std::lock_guard<std::mutex> lock(device_mutex());
            return d.run([&](Detector& detector, SharedScene*) { return detector.detect(cloud); });
          },
          py::arg("points"), py::arg("normals") = std::nullopt,
          "Detections in a point cloud in the camera frame (mm, z along the view: highest = "
          "smallest z), as `detect --cloud`; without normals they are estimated.");

  m.attr("RESULTS_CSV_HEADER") = bop::kResultsCsvHeader;
  m.def(
      "results_csv_row",
      [](int scene_id, int im_id, const FoundPart& f, double seconds) {
        const Detection& d = f.detection;
        return bop::format_result_row({scene_id, im_id, f.obj_id, d.score(), d.R, d.t, seconds});
      },
      py::arg("scene_id"), py::arg("im_id"), py::arg("detection"), py::arg("seconds"),
      "One line of BOP's results CSV (without its end), as `binpick detect` writes it.");
  m.def(
      "read_depth_png",
      [](const std::string& path) {
        const GrayImage<std::uint16_t> png = read_png16(path);
        py::array_t<std::uint16_t> out({py::ssize_t(png.height), py::ssize_t(png.width)});
        std::copy(png.pixels.begin(), png.pixels.end(), out.mutable_data());
        return out;
      },
      py::arg("path"), "A BOP depth PNG (16-bit) as a uint16 array (height, width).");
}

}  // namespace binpick::python

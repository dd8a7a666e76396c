// The `binpick` Python module: bindings over the same C++ as the command line, no logic of its
// own (docs/python.md). A model file in, a Detector with the command line's parameters (by the
// same names, from the one parameter table), detections out of a numpy depth image.
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <mutex>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "host/core/error.hpp"
#include "host/detect/batch/detect_batch.hpp"
#include "host/detect/detector.hpp"
#include "host/detect/params/params_file.hpp"
#include "host/detect/verify/score.hpp"
#include "host/formats/bop/png_image.hpp"
#include "host/formats/bop/results_csv.hpp"
#include "host/train/ppf_model_file.hpp"
#include "host/app/model_options.hpp"
#include "host/app/train_options.hpp"

namespace py = pybind11;
using namespace binpick;

namespace {

// A Detector and the model it points into: Python may drop its Model first.
struct PyDetector {
  std::shared_ptr<const PpfModel> model;
  std::unique_ptr<Detector> detector;
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

// A 2-D uint16 (raw, depth_mm = raw * depth_scale) or float32 (mm) array as the detector's image.
// Float depth is stored in steps of 0.1 mm (BOP's usual depth_scale), coarser only where its
// largest value needs it to fit 16 bits.
std::pair<DepthImage, double> depth_image(const py::array& depth, double depth_scale) {
  if (depth.ndim() != 2) throw InputError("depth: a 2-D array (height, width) expected");
  const auto h = std::uint32_t(depth.shape(0)), w = std::uint32_t(depth.shape(1));
  if (w == 0 || h == 0) throw InputError("depth: the image is empty");
  DepthImage image{w, h, std::vector<std::uint16_t>(std::size_t(w) * h)};
  if (depth.dtype().is(py::dtype::of<std::uint16_t>())) {
    if (!(std::isfinite(depth_scale) && depth_scale > 0))
      throw InputError("depth_scale: a positive number expected");
    const auto a = depth.cast<py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>>();
    std::copy(a.data(), a.data() + image.raw.size(), image.raw.begin());
    return {std::move(image), depth_scale};
  }
  if (!depth.dtype().is(py::dtype::of<float>()))
    throw InputError("depth: uint16 (with depth_scale) or float32 (mm) expected, not " +
                     std::string(py::str(depth.dtype())));
  const auto a = depth.cast<py::array_t<float, py::array::c_style | py::array::forcecast>>();
  float top = 0;
  for (std::size_t i = 0; i < image.raw.size(); ++i) {
    const float v = a.data()[i];
    if (!std::isfinite(v) || v < 0)
      throw InputError("depth: a value that is negative, NaN or infinite (0 is no depth)");
    top = std::max(top, v);
  }
  const double scale = std::max(0.1, double(top) / 65535.0);
  for (std::size_t i = 0; i < image.raw.size(); ++i)
    image.raw[i] = std::uint16_t(std::lround(double(a.data()[i]) / scale));
  return {std::move(image), scale};
}

// One detection at a time in the process: the detectors share the OpenCL device and its kernels
// (their arguments are set per launch).
std::mutex& device_mutex() {
  static std::mutex m;
  return m;
}

py::dict factors_of(const Detection& d) {
  py::dict f;
  const auto rows = score_factors();
  for (std::size_t k = 0; k < rows.size(); ++k) f[rows[k].name] = d.breakdown.factor[k];
  return f;
}

}  // namespace

PYBIND11_MODULE(binpick, m) {
  m.doc() = "binpick: 6D poses of parts in a bin from a depth image (point pair features)";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<PpfModel, std::shared_ptr<PpfModel>>(m, "Model",
                                                  "A trained point pair feature model (.ppfm)")
      .def_static(
          "load", [](const std::string& path) { return std::make_shared<PpfModel>(read_ppf_model(path)); },
          py::arg("path"), "Reads a model written by `binpick train`.")
      .def_static(
          "train",
          [](const std::string& part, double unit_scale, std::optional<double> diameter,
             double voxel_ratio, std::int64_t distance_steps, std::int64_t angle_steps) {
            const PpfTrainParams params =
                cli::train_params_of({voxel_ratio, distance_steps, angle_steps});
            ModelOptions options;
            options.unit_scale = unit_scale;
            options.diameter = diameter;
            const Mesh mesh = cli::load_part({part, options}).mesh;
            py::gil_scoped_release release;
            return std::make_shared<PpfModel>(train_ppf_model(mesh, params));
          },
          py::arg("part"), py::kw_only(), py::arg("unit_scale") = 1.0,
          py::arg("diameter") = std::nullopt, py::arg("voxel_ratio") = PpfTrainParams{}.voxel_ratio,
          py::arg("distance_steps") = std::int64_t(BP_PPF_DEFAULT_DIST_STEPS),
          py::arg("angle_steps") = std::int64_t(BP_PPF_DEFAULT_ANGLE_STEPS),
          "Trains the model of a part file (.gltf .glb .ply .stl .obj, mm unless unit_scale) or "
          "builtin:NAME, as `binpick train` does.")
      .def(
          "save", [](const PpfModel& model, const std::string& path) { write_ppf_model(path, model); },
          py::arg("path"), "Writes the model as `binpick train` does (.ppfm).")
      .def_readonly("diameter", &PpfModel::diameter, "mm")
      .def_readonly("voxel_size", &PpfModel::voxel_size, "mm, the subsampling voxel")
      .def_property_readonly(
          "lookalikes", [](const PpfModel& p) { return p.lookalikes.size(); },
          "how many look-alike poses the part has (a plate turned over)");

  py::class_<Detection>(m, "Detection", "A pose found around one highest point")
      .def_readonly("R", &Detection::R, "rotation, model to camera")
      .def_readonly("t", &Detection::t, "translation, model to camera, mm")
      .def_property_readonly("score", &Detection::score, "the verified score, in [0, 1]: the ranking")
      .def_property_readonly("fit", &Detection::fit_score, "the score before the look-alike share")
      .def_property_readonly("factors", &factors_of, "the score's factors by name")
      .def_readonly("votes", &Detection::votes)
      .def_readonly("hypothesis", &Detection::index, "the highest point's rank by height (0 = highest)")
      .def_readonly("reason", &Detection::reason)
      .def("__repr__", [](const Detection& d) {
        return "<binpick.Detection score " + std::to_string(d.score()) + " hypothesis " +
               std::to_string(d.index) + ">";
      });

  py::class_<PyDetector>(m, "Detector",
                         "Detection with one model; keyword arguments are the command line's "
                         "detection parameters ('_' for '-', e.g. ref_ratio=0.2, bin='auto')")
      .def(py::init([](std::shared_ptr<PpfModel> model, const py::kwargs& kwargs) {
             DetectParams params;
             apply_params_text(params_text(kwargs), "keyword arguments", params);
             auto d = std::make_unique<PyDetector>();
             d->model = model;
             d->detector = std::make_unique<Detector>(*d->model, params);
             return d;
           }),
           py::arg("model"))
      .def_property_readonly(
          "params",
          [](const PyDetector& d) {
            return py::module_::import("json").attr("loads")(params_json(d.detector->params()));
          },
          "every detection parameter, as a --params file has them")
      .def(
          "detect",
          [](PyDetector& d, const py::array& depth, const Eigen::Matrix3d& K, double depth_scale) {
            auto [image, scale] = depth_image(depth, depth_scale);
            if (!K.allFinite() || !(K(0, 0) > 0 && K(1, 1) > 0))
              throw InputError("K: a 3 x 3 camera matrix with positive focal lengths expected");
            const bp_camera cam = image_camera(K, scale, image.width, image.height);
            py::gil_scoped_release release;  // other Python threads run meanwhile
            const std::lock_guard<std::mutex> lock(device_mutex());
            return d.detector->detect(image, cam);
          },
          py::arg("depth"), py::arg("K"), py::arg("depth_scale") = 1.0,
          "Detections in a depth image, best first: depth is uint16 (depth_mm = value * "
          "depth_scale, BOP's) or float32 (mm), 0 where there is none; K the 3 x 3 camera matrix.")
      .def(
          "detect_cloud",
          [](PyDetector& d, const py::array_t<float, py::array::c_style | py::array::forcecast>& points,
             const std::optional<py::array_t<float, py::array::c_style | py::array::forcecast>>& normals) {
            const auto cloud_of = [](const auto& a, const char* what) {
              if (a.ndim() != 2 || a.shape(1) != 3)
                throw InputError(std::string(what) + ": an (N, 3) array expected");
              std::vector<Eigen::Vector3f> v(std::size_t(a.shape(0)));
              for (std::size_t i = 0; i < v.size(); ++i)
                v[i] = Eigen::Vector3f(a.at(i, 0), a.at(i, 1), a.at(i, 2));
              return v;
            };
            PointCloud cloud;
            cloud.points = cloud_of(points, "points");
            if (normals) {
              cloud.normals = cloud_of(*normals, "normals");
              if (cloud.normals.size() != cloud.points.size())
                throw InputError("normals: one per point expected");
            }
            py::gil_scoped_release release;
            const std::lock_guard<std::mutex> lock(device_mutex());
            return d.detector->detect(cloud);
          },
          py::arg("points"), py::arg("normals") = std::nullopt,
          "Detections in a point cloud in the camera frame (mm, z along the view: highest = "
          "smallest z), as `detect --cloud`; without normals they are estimated.");

  m.attr("RESULTS_CSV_HEADER") = bop::kResultsCsvHeader;
  m.def(
      "results_csv_row",
      [](int scene_id, int im_id, int obj_id, const Detection& d, double seconds) {
        return bop::format_result_row({scene_id, im_id, obj_id, d.score(), d.R, d.t, seconds});
      },
      py::arg("scene_id"), py::arg("im_id"), py::arg("obj_id"), py::arg("detection"),
      py::arg("seconds"),
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

// binpick.Model: a trained model (.ppfm), loaded, trained from a part file or arrays, saved.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "host/app/options/model_options.hpp"
#include "host/app/options/train_options.hpp"
#include "host/core/error.hpp"
#include "host/train/ppf_model_file.hpp"
#include "python/module/bindings.hpp"

namespace binpick::python {
namespace {

// vertices (N, 3) in the part's units, faces (M, 3) vertex indices, as a mesh (checked and
// completed as a model file is: normals, orientation, scale).
Mesh mesh_of_arrays(const py::array_t<double, py::array::c_style | py::array::forcecast>& vertices,
                    const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& faces) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3)
    throw InputError("vertices: an (N, 3) array expected");
  if (faces.ndim() != 2 || faces.shape(1) != 3) throw InputError("faces: an (M, 3) array expected");
  Mesh mesh;
  for (py::ssize_t i = 0; i < vertices.shape(0); ++i)
    mesh.positions.emplace_back(float(vertices.at(i, 0)), float(vertices.at(i, 1)),
                                float(vertices.at(i, 2)));
  for (py::ssize_t i = 0; i < faces.shape(0); ++i) {
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::int64_t v = faces.at(i, k);
      if (v < 0 || v >= vertices.shape(0))
        throw InputError("faces: vertex index " + std::to_string(v) + " of face " +
                         std::to_string(i) + " is not one of the " +
                         std::to_string(vertices.shape(0)) + " vertices");
      t[std::size_t(k)] = std::uint32_t(v);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

py::dict symmetries_of(const PartSymmetries& s) {
  py::list continuous, discrete;
  for (const auto& c : s.continuous)
    continuous.append(py::dict(py::arg("axis") = c.axis, py::arg("offset") = c.offset));
  for (const auto& d : s.discrete) discrete.append(d);
  return py::dict(py::arg("continuous") = continuous, py::arg("discrete") = discrete);
}

}  // namespace

void bind_model(py::module_& m) {
  py::class_<PpfModel, std::shared_ptr<PpfModel>>(m, "Model",
                                                  "A trained point pair feature model (.ppfm)")
      .def_static(
          "load", [](const std::string& path) { return std::make_shared<PpfModel>(read_ppf_model(path)); },
          py::arg("path"), "Reads a model written by `binpick train`.")
      .def_static(
          "train",
          [](std::optional<std::string> part, std::optional<py::array> vertices,
             std::optional<py::array> faces, double unit_scale, std::optional<double> diameter,
             double voxel_ratio, std::int64_t distance_steps, std::int64_t angle_steps,
             double cup_diameter) {
            if (part.has_value() == (vertices.has_value() || faces.has_value()) ||
                vertices.has_value() != faces.has_value())
              throw InputError("Model.train: a part file, or vertices and faces");
            const PpfTrainParams params =
                cli::train_params_of({voxel_ratio, distance_steps, angle_steps, cup_diameter});
            ModelOptions options;
            options.unit_scale = unit_scale;
            options.diameter = diameter;
            const Mesh mesh =
                part ? cli::load_part({*part, options}).mesh
                     : complete_model(mesh_of_arrays(*vertices, *faces), {}, "vertices and faces",
                                      options).mesh;
            py::gil_scoped_release release;
            const std::lock_guard<std::mutex> lock(device_mutex());
            return std::make_shared<PpfModel>(train_ppf_model(mesh, params));
          },
          py::arg("part") = std::nullopt, py::kw_only(), py::arg("vertices") = std::nullopt,
          py::arg("faces") = std::nullopt, py::arg("unit_scale") = 1.0,
          py::arg("diameter") = std::nullopt, py::arg("voxel_ratio") = PpfTrainParams{}.voxel_ratio,
          py::arg("distance_steps") = std::int64_t(BP_PPF_DEFAULT_DIST_STEPS),
          py::arg("angle_steps") = std::int64_t(BP_PPF_DEFAULT_ANGLE_STEPS),
          py::arg("cup_diameter") = 0.0,
          "Trains the model of a part as `binpick train` does: a part file (.gltf .glb .ply .stl "
          ".obj, mm unless unit_scale) or builtin:NAME, or vertices (N, 3) and faces (M, 3) "
          "(triangles, vertex indices).")
      .def(
          "save", [](const PpfModel& model, const std::string& path) { write_ppf_model(path, model); },
          py::arg("path"), "Writes the model as `binpick train` does (.ppfm).")
      .def_readonly("diameter", &PpfModel::diameter, "mm")
      .def_readonly("voxel_size", &PpfModel::voxel_size, "mm, the subsampling voxel")
      .def_property_readonly(
          "points",
          [](const PpfModel& p) {
            py::array_t<float> out({py::ssize_t(p.cloud.points.size()), py::ssize_t(3)});
            for (std::size_t i = 0; i < p.cloud.points.size(); ++i)
              for (int k = 0; k < 3; ++k) out.mutable_at(py::ssize_t(i), k) = p.cloud.points[i][k];
            return out;
          },
          "the subsampled surface points (N, 3), mm, model frame: what detection matches")
      .def_property_readonly(
          "symmetries", [](const PpfModel& p) { return symmetries_of(p.symmetries); },
          "the part's symmetries in the model frame: 'continuous' (axis and offset, mm, of each "
          "axis of revolution) and 'discrete' (4 x 4 transforms, mm, other than the identity)")
      .def_property_readonly(
          "lookalikes",
          [](const PpfModel& p) {
            py::list out;
            for (const auto& s : p.lookalikes) out.append(Eigen::Matrix4d(s.matrix()));
            return out;
          },
          "the look-alike poses (4 x 4, model frame, mm) that detection tells apart from the "
          "right one: a plate turned over");
}

}  // namespace binpick::python

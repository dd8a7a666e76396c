// The `binpick` Python module: bindings over the same C++ as the command line, no logic of its
// own (docs/python.md). A model in, a Detector with the command line's parameters (by the same
// names, from the one parameter table), detections out of a numpy depth image; the batch verbs
// with their command-line options.
#include "python/module/bindings.hpp"

#include "host/core/error.hpp"

namespace binpick::python {

std::mutex& device_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace binpick::python

PYBIND11_MODULE(binpick, m) {
  m.doc() = "binpick: 6D poses of parts in a bin from a depth image (point pair features)";
  pybind11::register_exception<binpick::InputError>(m, "InputError", PyExc_ValueError);
  binpick::python::bind_model(m);
  binpick::python::bind_detector(m);
  binpick::python::bind_commands(m);
}

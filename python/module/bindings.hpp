// The parts of the `binpick` Python module (docs/python.md), each binding one area of the C++
// the command line runs; no detection logic of their own.
#pragma once

#include <mutex>

#include <pybind11/pybind11.h>

namespace binpick::python {

namespace py = pybind11;

void bind_model(py::module_& m);     // Model: load, train, save, attributes
void bind_detector(py::module_& m);  // Detector, Detection, the results CSV row, depth PNGs
void bind_commands(py::module_& m);  // the batch verbs: synth, train, detect, eval, run, tune

// One device user at a time in the process: detectors and batch verbs share the OpenCL device
// and its kernels (their arguments are set per launch). Taken with the interpreter's lock
// released, so Python threads wait without blocking each other's Python.
std::mutex& device_mutex();

}  // namespace binpick::python

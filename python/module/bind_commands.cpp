// The batch verbs from Python: binpick.synth(out=..., bins=2), binpick.detect(...), ... run the
// command line's verb with the same options (keyword arguments by the options' names, '_' for
// '-'), its messages, and its progress to a callback instead of stderr.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include <pybind11/stl.h>

#include "host/app/command_line.hpp"
#include "host/core/error.hpp"
#include "host/core/progress.hpp"
#include "python/module/bindings.hpp"

namespace binpick::python {
namespace {

// A keyword argument as the option it names: True/False a flag; a list or tuple one value each;
// anything else (numbers, paths, text) as str() writes it. None: left out.
std::vector<cli::NamedOption> options_of(const py::kwargs& kwargs) {
  std::vector<cli::NamedOption> options;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (value.is_none()) continue;
    if (py::isinstance<py::bool_>(value)) {
      options.push_back({name, value.cast<bool>()});
      continue;
    }
    std::vector<std::string> values;
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
      for (const auto& v : value) values.push_back(py::str(v));
    } else {
      values.push_back(py::str(value));
    }
    options.push_back({name, values});
  }
  return options;
}

// Runs the command line on app with the interpreter's lock released; progress, if not None, is
// called as progress(label, done, total, status) with the lock held.
void run_line(CLI::App& app, const std::vector<std::string>& line, const py::object& progress) {
  ProgressListener listener;
  if (!progress.is_none())
    listener = [progress](const ProgressEvent& e) {
      py::gil_scoped_acquire acquire;  // its exception (Ctrl-C among them) stops the verb
      progress(std::string(e.label), e.done, e.total, std::string(e.status));
    };
  {
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(device_mutex());
    const ScopedProgressListener scoped(listener);
    cli::run_command_line(app, line);
    std::cout.flush();
  }
}

void run_verb(const std::string& verb, const py::object& progress, const py::kwargs& kwargs) {
  const auto app = cli::make_app();
  run_line(*app, cli::command_line_of(*app, verb, options_of(kwargs)), progress);
}

void def_verb(py::module_& m, const char* verb, const char* doc) {
  m.def(
      verb,
      [verb = std::string(verb)](const py::object& progress, const py::kwargs& kwargs) {
        run_verb(verb, progress, kwargs);
      },
      py::kw_only(), py::arg("progress") = py::none(), doc);
}

}  // namespace

void bind_commands(py::module_& m) {
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const std::filesystem::filesystem_error& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });
  m.def(
      "command",
      [](const std::string& verb, const py::object& progress, const py::kwargs& kwargs) {
        run_verb(verb, progress, kwargs);
      },
      py::arg("verb"), py::kw_only(), py::arg("progress") = py::none(),
      "Runs `binpick VERB --name value ...`: keyword arguments are the verb's options ('_' for "
      "'-'; True/False a flag on/off; a list gives the option once per value; None leaves it "
      "out). progress(label, done, total, status), if given, takes the progress bar's updates. "
      "ValueError with the command line's message for a bad option or input.");
  m.def(
      "command_line",
      [](const std::vector<std::string>& args, const py::object& progress) {
        run_line(*cli::make_app(), args, progress);
      },
      py::arg("args"), py::kw_only(), py::arg("progress") = py::none(),
      "Runs `binpick ARGS...` as the shell would (args: the words after `binpick`), for an order "
      "keywords cannot give (eval's --dataset A --results A.csv --dataset B --results B.csv).");
  def_verb(m, "synth", "`binpick synth`: synthetic bins as a BOP dataset (command's keywords)");
  def_verb(m, "detect", "`binpick detect`: detection over a dataset's images into a results CSV");
  def_verb(m, "eval", "`binpick eval`: a results CSV scored against the dataset's truth");
  def_verb(m, "run", "`binpick run`: the paper's experiment, synthesis to report");
  def_verb(m, "tune", "`binpick tune`: detection parameters searched on a dataset");
}

}  // namespace binpick::python

// The C++ libraries' errors as Python exceptions. Each mrsim exception
// derives from the built-in one a Python user would catch (ValueError for
// bad input, RuntimeError for a failing simulation), and ScenarioError
// carries the file, line and element path the C++ reader names.
#include <pybind11/pybind11.h>

#include <string>

#include "gait_controller/gait_file.h"
#include "logger/csv_columns.h"
#include "optimizer/genome.h"
#include "python/src/bindings.h"
#include "sim_core/checkpoint.h"
#include "sim_core/physics.h"
#include "sim_core/scenario_validate.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

// "file:line: path: message" -> file, or "" when what() has no line.
std::string FileOf(const ScenarioError& e) {
  if (e.line() <= 0) return "";
  const std::string what = e.what();
  const std::string mark = ":" + std::to_string(e.line()) + ":";
  const size_t at = what.find(mark);
  return at == std::string::npos ? "" : what.substr(0, at);
}

}  // namespace

void BindErrors(py::module_& m) {
  static py::exception<ScenarioError> scenario_error(m, "ScenarioError",
                                                     PyExc_ValueError);
  scenario_error.attr("__doc__") =
      "A scenario the C++ reader or validator refuses. str() is the reader's "
      "message 'file:line: Scenario/robot[1]/...: what was expected'; the "
      "attributes file, line (0 when unknown), path (the element path) and "
      "message (what was expected) hold its parts.";
  static py::exception<GaitFileError> gait_error(m, "GaitError",
                                                 PyExc_ValueError);
  gait_error.attr("__doc__") =
      "A bad gait file, an unknown gait name or gait parameters out of "
      "range; the message names the file, line or field.";
  static py::exception<CheckpointError> checkpoint_error(m, "CheckpointError",
                                                         PyExc_ValueError);
  checkpoint_error.attr("__doc__") =
      "A file that is not a readable checkpoint.";
  static py::exception<PhysicsError> physics_error(m, "PhysicsError",
                                                   PyExc_RuntimeError);
  physics_error.attr("__doc__") =
      "The simulation became unstable, or names a lock it does not have.";
  static py::exception<PlotInputError> log_error(m, "LogError",
                                                 PyExc_ValueError);
  log_error.attr("__doc__") = "A log or CSV file that cannot be read as one.";
  static py::exception<GenomeError> genome_error(m, "GenomeError",
                                                 PyExc_ValueError);
  genome_error.attr("__doc__") = "A bad genome file or genome.";

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ScenarioError& e) {
      py::object exc =
          py::reinterpret_borrow<py::object>(scenario_error)(e.what());
      exc.attr("file") = FileOf(e);
      exc.attr("line") = e.line();
      exc.attr("path") = e.path();
      exc.attr("message") = e.message();
      PyErr_SetObject(scenario_error.ptr(), exc.ptr());
    } catch (const GaitFileError& e) {
      gait_error(e.what());
    } catch (const CheckpointError& e) {
      checkpoint_error(e.what());
    } catch (const PhysicsError& e) {
      physics_error(e.what());
    } catch (const PlotInputError& e) {
      log_error(e.what());
    } catch (const GenomeError& e) {
      genome_error(e.what());
    }
  });
}

}  // namespace mrsim::python

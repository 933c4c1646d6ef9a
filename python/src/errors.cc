// The C++ libraries' errors as Python exceptions. Each mrsim exception
// derives from the built-in one a Python user would catch (ValueError for
// bad input, RuntimeError for a failing simulation), and ScenarioError
// carries the file, line and element path the C++ reader names;
// OverlapError (a ScenarioError) also the overlapping pairs.
#include <pybind11/pybind11.h>

#include <string>

#include "gait_controller/gait_file.h"
#include "logger/csv_columns.h"
#include "optimizer/search/genome.h"
#include "python/src/bindings.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/physics/physics.h"
#include "sim_core/scenario/scenario_validate.h"

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

struct FileLine {
  std::string file;
  int line = 0;
};

// "file:line: path: ..." (DescribeOverlap's first line) -> file, line;
// empty when the scenario came from no file.
FileLine FileLineOf(const std::string& what, const std::string& path) {
  const size_t end = what.find(": " + path + ": ");
  const size_t colon = end == std::string::npos || end == 0
                           ? std::string::npos
                           : what.rfind(':', end - 1);
  if (path.empty() || colon == std::string::npos) return {};
  try {
    return {what.substr(0, colon),
            std::stoi(what.substr(colon + 1, end - colon - 1))};
  } catch (const std::exception&) {
    return {};
  }
}

std::string AllowOverlapHint() {
  // mrsim-sim's words, with the keyword in place of its flag.
  std::string hint = kAllowOverlapHint;
  const std::string flag = "--allow-overlap";
  const size_t at = hint.find(flag);
  if (at != std::string::npos)
    hint.replace(at, flag.size(), "allow_overlap=True");
  return hint;
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
  static py::exception<OverlapError> overlap_error(m, "OverlapError",
                                                   scenario_error.ptr());
  overlap_error.attr("__doc__") =
      "Parts of a scenario overlap at the start (REQ-1.2.8), refused as "
      "mrsim-sim refuses them. str() is one line per overlapping pair, "
      "deepest first, as mrsim-sim prints them, then how to allow it "
      "(allow_overlap=True); overlaps is a list of dicts first, second "
      "(the parts' names), first_path, second_path (their element paths) "
      "and depth (m).";
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
    } catch (const OverlapError& e) {
      py::object exc = py::reinterpret_borrow<py::object>(overlap_error)(
          std::string(e.what()) + "\n" + AllowOverlapHint());
      py::list overlaps;
      for (const PartOverlap& o : e.overlaps()) {
        py::dict d;
        d["first"] = o.first;
        d["second"] = o.second;
        d["first_path"] = o.first_path;
        d["second_path"] = o.second_path;
        d["depth"] = o.depth;
        overlaps.append(d);
      }
      exc.attr("overlaps") = overlaps;
      // The deepest pair's place, as its line of what() gives it.
      const std::string first = e.overlaps().empty()
                                    ? std::string()
                                    : e.overlaps().front().first_path;
      const FileLine at = FileLineOf(e.what(), first);
      exc.attr("file") = at.file;
      exc.attr("line") = at.line;
      exc.attr("path") = first;
      exc.attr("message") = e.message();
      PyErr_SetObject(overlap_error.ptr(), exc.ptr());
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

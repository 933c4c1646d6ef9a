// mrsim.Gait: the gait library's presets, gait files, parameters and
// motions, and GaitController stepping by sim time (gait_object.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gait_controller/gait_file.h"
#include "gait_controller/gait_parameters.h"
#include "gait_controller/gait_presets.h"
#include "gait_controller/motion.h"
#include "python/src/bindings.h"
#include "python/src/gait_object.h"
#include "python/src/state_object.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

py::dict ParameterDict(const GaitParameters& p) {
  py::dict d;
  const auto values = p.ToArray();
  const auto& names = GaitParameterNames();
  for (size_t i = 0; i < values.size(); ++i) d[names[i]] = values[i];
  d["pitch_yaw_lag"] = p.pitch_yaw_lag;
  return d;
}

// Keeps `base`'s values, replaces those named in `values` (a dict of the
// seven names and pitch_yaw_lag, or a sequence of the seven).
GaitParameters MergeParameters(const GaitParameters& base,
                               const py::object& values) {
  GaitParameters p = base;
  if (!py::isinstance<py::dict>(values)) {
    const auto v = values.cast<std::vector<double>>();
    p = base.WithVector(v);
    ValidateGaitParameters(p);
    return p;
  }
  std::vector<double> vec = p.ToVector();
  const auto& names = GaitParameterNames();
  for (auto item : values.cast<py::dict>()) {
    const std::string key = item.first.cast<std::string>();
    const double value = item.second.cast<double>();
    if (key == "pitch_yaw_lag") {
      p.pitch_yaw_lag = value;
      continue;
    }
    size_t i = 0;
    while (i < names.size() && key != names[i]) ++i;
    if (i == names.size()) {
      std::string known;
      for (const char* n : names)
        known += std::string(known.empty() ? "" : ", ") + n;
      throw py::key_error("unknown gait parameter '" + key + "' (expected " +
                          known + ", pitch_yaw_lag)");
    }
    vec[i] = value;
  }
  p = p.WithVector(vec);
  ValidateGaitParameters(p);
  return p;
}

Motion MotionOf(const std::string& name) {
  const auto m = ParseMotion(name);
  if (!m) {
    throw std::invalid_argument(
        "motion: expected forward, backward, turn-left, turn-right, "
        "sidewind-left, sidewind-right, roll or stop, got '" +
        name + "'");
  }
  return *m;
}

GaitKind KindOf(const std::string& name) {
  const auto k = ParseGaitKind(name);
  if (!k) {
    throw std::invalid_argument(
        "kind: expected linear, sidewind or roll, got '" + name + "'");
  }
  return *k;
}

std::shared_ptr<GaitObject> MakeGait(Gait g,
                                     const std::optional<std::string>& axes) {
  auto obj = std::make_shared<GaitObject>(std::move(g));
  if (axes) obj->set_axes(*axes);
  return obj;
}

}  // namespace

void BindGait(py::module_& m) {
  m.def(
      "gait_presets",
      [] {
        std::vector<std::string> names;
        for (const Gait& g : GaitPresets()) names.push_back(g.name);
        return names;
      },
      "Names of the built-in gaits (forward, forward-strong, turn-wide, ...).");
  m.def(
      "gait_parameter_names",
      [] {
        std::vector<std::string> names;
        for (const char* n : GaitParameterNames()) names.emplace_back(n);
        return names;
      },
      "The seven gait parameters in vector order: A_pitch, A_yaw, phi_pitch, "
      "phi_yaw, T, offset_pitch, offset_yaw.");

  py::class_<GaitObject, std::shared_ptr<GaitObject>> c(m, "Gait", R"doc(
A sinusoid gait of the gait library, and the controller that runs it:
theta_i(t) = A_g sin(2 pi t / T + k_i phi_g) + o_g per joint group g.

gait.targets(t, state) returns the joint targets for sim time t, advancing
the controller exactly as mrsim-gait does when it answers a state of time t
(amplitudes ramp in from rest, the phase is integrated). Pass a Gait to
Simulation.run() or Simulation.set_controller() to drive a simulation.)doc");
  c.def(py::init([](const std::string& spec, std::optional<std::string> axes) {
          return MakeGait(ResolveGait(spec), axes);
        }),
        py::arg("gait") = "forward", py::arg("axes") = py::none(), R"doc(
A preset name (see gait_presets()), a gait file path or NAME with NAME.xml
in MRSIM_GAIT_PATH or ./gaits, as mrsim-gait --gait takes it.
axes: the robot's hinge axes ('pitch', 'yaw', 'pitch-yaw', 'yaw-pitch' or
one letter per joint, 'PYPYP'); default: those of the state (states of a
Simulation know them), else alternating pitch-yaw as mrsim-gait assumes.
Raises GaitError for an unknown name or a bad file.)doc");
  c.def_static(
      "from_parameters",
      [](const py::object& parameters, const std::string& kind,
         const std::string& name, std::optional<std::string> axes) {
        Gait g;
        g.name = name;
        g.kind = KindOf(kind);
        g.parameters = MergeParameters(GaitParameters{}, parameters);
        return MakeGait(g, axes);
      },
      py::arg("parameters"), py::arg("kind") = "linear",
      py::arg("name") = "custom", py::arg("axes") = py::none(), R"doc(
A gait from its parameters: a dict with the names of gait_parameter_names()
(and pitch_yaw_lag; missing ones are 0, T is 4 s) or a sequence of the
seven. kind: 'linear', 'sidewind' or 'roll'. Raises ValueError naming a
value out of range.)doc");
  c.def_static(
      "load",
      [](const std::string& path) { return MakeGait(ReadGaitFile(path), {}); },
      py::arg("path"), "Reads a gait file (docs/gait.md); raises GaitError.");
  c.def(
      "save",
      [](const GaitObject& g, const std::string& path) {
        WriteGaitFile(g.gait(), path);
      },
      py::arg("path"),
      "Writes the gait as a gait file mrsim-gait --gait reads.");
  c.def(
      "to_xml", [](const GaitObject& g) { return WriteGaitString(g.gait()); },
      "The gait file text.");
  c.def_property_readonly(
      "name", [](const GaitObject& g) { return g.gait().name; }, "Gait name.");
  c.def_property_readonly(
      "kind",
      [](const GaitObject& g) { return std::string(ToString(g.gait().kind)); },
      "'linear', 'sidewind' or 'roll'.");
  c.def_property_readonly(
      "parameters",
      [](const GaitObject& g) { return ParameterDict(g.gait().parameters); },
      "The seven parameters and pitch_yaw_lag as a dict.");
  c.def_property_readonly(
      "parameter_vector",
      [](const GaitObject& g) {
        const auto v = g.gait().parameters.ToArray();
        return py::array_t<double>(v.size(), v.data());
      },
      "The seven parameters in gait_parameter_names() order.");
  c.def(
      "with_parameters",
      [](const GaitObject& g, const py::kwargs& kw) {
        Gait copy = g.gait();
        copy.parameters = MergeParameters(copy.parameters, kw);
        copy.name = "custom";
        return MakeGait(copy, {});
      },
      "A new gait (at rest) with some parameters replaced, e.g. "
      "gait.with_parameters(T=3.0, A_pitch=0.8).");
  c.def(
      "set_parameters",
      [](GaitObject& g, const py::object& values) {
        g.SetParameters(MergeParameters(g.gait().parameters, values));
      },
      py::arg("values"),
      "Replaces parameters of the running gait (dict or the seven values); "
      "the controller ramps to them as mrsim-gait does.");
  c.def(
      "set_motion",
      [](GaitObject& g, const std::string& motion, double strength) {
        g.SetMotion(MotionOf(motion), strength);
      },
      py::arg("motion"), py::arg("strength") = 1.0,
      "forward, backward, turn-left, turn-right, sidewind-left, "
      "sidewind-right, roll or stop; strength in [-1, 1].");
  c.def("set_direction", &GaitObject::SetDirection, py::arg("forward"),
        py::arg("turn"),
        "Joystick inputs in [-1, 1]: forward speed and turn (> 0: left).");
  c.def(
      "targets",
      [](GaitObject& g, double t, const py::object& state,
         std::optional<int> joint_count) {
        std::vector<Axis> known;
        int n = 0;
        if (!state.is_none()) {
          const auto& s = state.cast<const StateObject&>();
          known = s.axes;
          n = static_cast<int>(s.state.joints.size());
        } else if (joint_count) {
          n = *joint_count;
        } else if (g.controller()) {
          n = g.controller()->joint_count();
        } else {
          throw std::invalid_argument(
              "targets: give the state (or joint_count) on the first call");
        }
        if (!g.controller() && !g.has_axes() &&
            static_cast<int>(known.size()) != n) {
          // As mrsim-gait without --scenario or --axes, said once.
          if (PyErr_WarnEx(PyExc_UserWarning,
                           "Gait.targets: the joint axes are not known; "
                           "assuming alternating pitch-yaw (give axes=...)",
                           1) != 0) {
            throw py::error_already_set();
          }
        }
        const std::vector<double>& t_out = g.TargetsAt(t, g.AxesFor(n, known));
        return py::array_t<double>(t_out.size(), t_out.data());
      },
      py::arg("t"), py::arg("state") = py::none(),
      py::arg("joint_count") = py::none(), R"doc(
Joint targets (rad, chain order) at sim time t (s) for the robot whose
state is given. The first call builds the controller for the state's
joints; each call advances it by the time since the previous call (a time
going back restarts from rest), as mrsim-gait answering states.)doc");
  c.def("reset", &GaitObject::Reset,
        "Back to rest: the next targets() starts the gait afresh.");
  c.def_property_readonly(
      "motion",
      [](const GaitObject& g) -> std::optional<std::string> {
        if (!g.controller()) return std::nullopt;
        return std::string(ToString(g.controller()->motion()));
      },
      "The motion running (None before the first targets()).");
  c.def_property_readonly(
      "time",
      [](const GaitObject& g) {
        return g.controller() ? g.controller()->time() : 0.0;
      },
      "Time the controller has run (s).");
  c.def("__repr__", [](const GaitObject& g) {
    return "<mrsim.Gait " + g.gait().name + " (" + ToString(g.gait().kind) +
           ")>";
  });
}

}  // namespace mrsim::python

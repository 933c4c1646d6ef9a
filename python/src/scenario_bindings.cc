// mrsim.Scenario: reading, generating, validating and writing scenarios
// through sim_core (scenario_xml.h, chain_builder.h, scenario_validate.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimizer/episode/task.h"
#include "python/src/bindings.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

FrameConvention ParseFrame(const std::string& frame) {
  if (frame == "z-up") return FrameConvention::kZUp;
  if (frame == "unity-y-up") return FrameConvention::kUnityYUp;
  throw std::invalid_argument("frame: expected 'z-up' or 'unity-y-up', got '" +
                              frame + "'");
}

ScenarioReadOptions ReadOptions(const std::optional<std::string>& frame,
                                double length_scale) {
  if (frame && *frame == "original") {
    if (length_scale != 1.0) {
      throw std::invalid_argument(
          "length_scale: frame='original' fixes it (0.01: centimetres)");
    }
    return kOriginalMrsimReadOptions;
  }
  ScenarioReadOptions options;
  if (frame) options.frame = ParseFrame(*frame);
  if (!(length_scale > 0)) {
    throw std::invalid_argument("length_scale: expected a number > 0");
  }
  options.length_scale = length_scale;
  return options;
}

ChainPattern ParsePattern(const std::string& pattern) {
  if (pattern == "pitch") return ChainPattern::kPitch;
  if (pattern == "yaw") return ChainPattern::kYaw;
  if (pattern == "pitch-yaw") return ChainPattern::kPitchYaw;
  throw std::invalid_argument(
      "pattern: expected 'pitch', 'yaw' or 'pitch-yaw', got '" + pattern + "'");
}

std::vector<int> SensorList(const py::object& sensors, int modules) {
  if (py::isinstance<py::str>(sensors)) {
    const std::string s = sensors.cast<std::string>();
    if (s == "none") return SensorsAfter(SensorPlacement::kNone, modules);
    if (s == "all") return SensorsAfter(SensorPlacement::kAll, modules);
    if (s == "between") return SensorsAfter(SensorPlacement::kBetween, modules);
    throw std::invalid_argument(
        "sensors: expected 'none', 'all', 'between' or a list of module "
        "indices, got '" +
        s + "'");
  }
  return sensors.cast<std::vector<int>>();
}

const Robot& RobotOf(const Scenario& s, const py::object& robot) {
  if (py::isinstance<py::int_>(robot)) {
    const int i = robot.cast<int>();
    if (i < 0 || i >= static_cast<int>(s.robots.size())) {
      throw py::index_error("robot " + std::to_string(i) +
                            ": the scenario has " +
                            std::to_string(s.robots.size()) + " robot(s)");
    }
    return s.robots[i];
  }
  const std::string name = robot.cast<std::string>();
  for (const Robot& r : s.robots) {
    if (r.name == name) return r;
  }
  std::string names;
  for (const Robot& r : s.robots) names += (names.empty() ? "" : ", ") + r.name;
  throw py::key_error("no robot '" + name +
                      "' in the scenario (robots: " + names + ")");
}

}  // namespace

void BindScenario(py::module_& m) {
  py::class_<Scenario> c(m, "Scenario", R"doc(
A scenario: robots, terrain, scene objects and contact materials, as one
MRSim XML file holds them. Read one with Scenario.load(path), generate a
chain with Scenario.chain(...), pass it to Simulation(scenario).
Reading and validating use the C++ reader: a bad file raises
mrsim.ScenarioError naming file, line and field.)doc");
  c.def(py::init<>(), "An empty scenario (no robots, flat ground).");
  c.def_static(
      "load",
      [](const std::string& path, std::optional<std::string> frame,
         double length_scale) {
        return ReadScenarioFile(path, ReadOptions(frame, length_scale));
      },
      py::arg("path"), py::arg("frame") = py::none(),
      py::arg("length_scale") = 1.0, R"doc(
Reads and validates a scenario file.

frame: the axis convention of a file that does not say ('z-up' or
'unity-y-up'), or 'original' for a file the original MRSim wrote (Unity
Y-up in centimetres). length_scale multiplies every length of the file.
Raises ScenarioError ("file:line: path: what was expected").)doc");
  c.def_static(
      "from_xml",
      [](const std::string& xml, const std::string& name,
         const std::string& base_dir, std::optional<std::string> frame,
         double length_scale) {
        return ReadScenarioString(xml, name, base_dir,
                                  ReadOptions(frame, length_scale));
      },
      py::arg("xml"), py::arg("name") = "<string>", py::arg("base_dir") = ".",
      py::arg("frame") = py::none(), py::arg("length_scale") = 1.0,
      "Reads and validates scenario XML from a string; `name` is used in "
      "error messages, `base_dir` resolves relative mesh and image paths.");
  c.def_static(
      "task",
      [](const std::string& name) {
        Task t = MakeTask(name);
        return t.scenario;
      },
      py::arg("name"),
      "The scenario of a task of the suite (docs/tasks.md): flat, slope, "
      "stairs, pegs, pipe, pole, rubble, water. ValueError for another "
      "name.");
  m.def(
      "task_info",
      [](const std::string& name) {
        const Task t = MakeTask(name);
        py::dict d;
        d["name"] = t.name;
        d["description"] = t.description;
        d["fitness"] = t.distance_mode;
        d["seconds"] = t.duration;
        d["gait"] = t.gait.name;
        return d;
      },
      py::arg("name"),
      "What a task scores (fitness: forward or up), over how many seconds, "
      "and the gait it starts from.");
  m.def(
      "task_names", [] { return TaskNames(); }, "The names of the task suite.");
  c.def_static(
      "chain",
      [](int modules, const std::string& pattern, const std::string& name,
         const py::object& sensors, bool force_sensors,
         bool front_distance_sensor, double friction,
         const std::string& material, const std::string& ground_material,
         double module_mass, double kp, double max_vel, double joint_limit) {
        ChainScenarioOptions o;
        o.chain.name = name;
        o.chain.modules = modules;
        o.chain.pattern = ParsePattern(pattern);
        o.chain.sensor_after = SensorList(sensors, modules);
        o.chain.force_sensors = force_sensors;
        o.chain.front_distance_sensor = front_distance_sensor;
        o.chain.material = material;
        o.chain.module_mass = module_mass;
        o.chain.kp = kp;
        o.chain.max_vel = max_vel;
        o.chain.joint_limit = joint_limit;
        o.ground_material = ground_material;
        o.friction = friction;
        Scenario s = MakeChainScenario(o);
        ValidateScenario(s);
        return s;
      },
      py::arg("modules") = 11, py::arg("pattern") = "pitch",
      py::arg("name") = "snake", py::arg("sensors") = "none",
      py::arg("force_sensors") = false,
      py::arg("front_distance_sensor") = false, py::arg("friction") = -1.0,
      py::arg("material") = "plastic", py::arg("ground_material") = "ground",
      py::arg("module_mass") = 0.1, py::arg("kp") = 10.0,
      py::arg("max_vel") = 3.0, py::arg("joint_limit") = 1.5708, R"doc(
Generates one chain robot on flat ground, as `mrsim-scenario new` does.

pattern: 'pitch', 'yaw' or 'pitch-yaw'. sensors: 'none', 'all', 'between'
or a list of module indices a sensor module follows (-1: in front of
module 0). friction >= 0 adds a robot-ground ContactFriction. Raises
ValueError on bad values.)doc");
  c.def(
      "validate", [](const Scenario& s) { ValidateScenario(s); },
      "Checks every rule the simulator needs; raises ScenarioError naming the "
      "element path and what was expected.");
  c.def(
      "to_xml",
      [](const Scenario& s, const std::string& frame) {
        return WriteScenarioString(s, ParseFrame(frame));
      },
      py::arg("frame") = "z-up",
      "The scenario as XML text (the layout Scenario.load reads).");
  c.def(
      "save",
      [](const Scenario& s, const std::string& path, const std::string& frame) {
        WriteScenarioFile(s, path, ParseFrame(frame));
      },
      py::arg("path"), py::arg("frame") = "z-up",
      "Writes the scenario to a file; raises RuntimeError naming the path "
      "when it cannot be written.");
  c.def_property_readonly(
      "robots",
      [](const Scenario& s) {
        std::vector<std::string> names;
        for (const Robot& r : s.robots) names.push_back(r.name);
        return names;
      },
      "Names of the robots, in scenario order.");
  c.def(
      "module_count",
      [](const Scenario& s, const py::object& robot) {
        return RobotOf(s, robot).modules.size();
      },
      py::arg("robot") = 0, "Number of modules of a robot (index or name).");
  c.def(
      "joint_axes",
      [](const Scenario& s, const py::object& robot) {
        std::vector<std::string> axes;
        for (const Module& mod : RobotOf(s, robot).modules) {
          if (mod.joint.type == JointType::kHinge) {
            axes.push_back(mod.axis == Axis::kPitch ? "pitch" : "yaw");
          }
        }
        return axes;
      },
      py::arg("robot") = 0,
      "The hinge axes of a robot in chain order: 'pitch' or 'yaw' each.");
  c.def_property(
      "timestep", [](const Scenario& s) { return s.settings.timestep; },
      [](Scenario& s, double dt) { s.settings.timestep = dt; },
      "Physics timestep (s).");
  c.def_property_readonly(
      "base_dir", [](const Scenario& s) { return s.base_dir; },
      "Directory relative mesh and image paths resolve against.");
  c.def("__eq__", [](const Scenario& a, const Scenario& b) { return a == b; });
  c.def("__copy__", [](const Scenario& s) { return Scenario(s); });
  c.def("__deepcopy__",
        [](const Scenario& s, const py::dict&) { return Scenario(s); });
  c.def("__repr__", [](const Scenario& s) {
    std::string names;
    for (const Robot& r : s.robots) {
      names += (names.empty() ? "" : ", ") + r.name + " (" +
               std::to_string(r.modules.size()) + " modules)";
    }
    return "<mrsim.Scenario robots: " + (names.empty() ? "none" : names) + ">";
  });
}

}  // namespace mrsim::python

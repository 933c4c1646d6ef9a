// mrsim.Simulation: sim_core's Physics (MuJoCo) with the GIL released while
// it steps, states as mrsim.State, checkpoints, and a controller (a Gait or
// any callable) run once per control period as mrsim-sim runs one in
// lockstep.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gait_controller/gait_runner.h"
#include "python/src/bindings.h"
#include "python/src/gait_object.h"
#include "python/src/simulation_cameras.h"
#include "python/src/state_object.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/physics/checkpoint.h"
#include "sim_core/physics/physics.h"
#include "sim_core/physics/scene_object_state.h"
#include "sim_core/scenario/scenario_xml.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

class Simulation {
 public:
  explicit Simulation(std::unique_ptr<Physics> physics)
      : physics_(std::move(physics)) {}

  Physics& physics() { return *physics_; }
  std::mutex& mutex() { return mutex_; }

  int Robot(const py::object& robot) const {
    const Physics& p = *physics_;
    if (py::isinstance<py::int_>(robot)) {
      const int i = robot.cast<int>();
      if (i < 0 || i >= p.robot_count()) {
        throw py::index_error("robot " + std::to_string(i) +
                              ": the simulation has " +
                              std::to_string(p.robot_count()) + " robot(s)");
      }
      return i;
    }
    const std::string name = robot.cast<std::string>();
    const int i = p.robot_index(name);
    if (i < 0) {
      std::string names;
      for (int k = 0; k < p.robot_count(); ++k) {
        names += (k ? ", " : "") + p.robot_name(k);
      }
      throw py::key_error("no robot '" + name + "' (robots: " + names + ")");
    }
    return i;
  }

  // Whose cameras `robot` names: a robot (index or name), or "loose" /
  // "scene" for the cameras on loose sensor modules / scene objects.
  std::string CameraOwner(const py::object& robot) const {
    if (py::isinstance<py::str>(robot)) {
      const std::string name = robot.cast<std::string>();
      if (physics_->robot_index(name) < 0 &&
          (name == kSceneOwnerName || name == kLooseOwnerName)) {
        return name;
      }
    }
    return physics_->robot_name(Robot(robot));
  }

  std::shared_ptr<StateObject> State(int robot) {
    auto s = std::make_shared<StateObject>();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      s->state = physics_->ReadRobotState(robot);
      s->locks = physics_->LockStates(physics_->robot_name(robot));
    }
    s->axes = Axes(robot);
    return s;
  }

  const std::vector<Axis>& Axes(int robot) {
    if (axes_.size() != static_cast<size_t>(physics_->robot_count())) {
      axes_.clear();
      for (int r = 0; r < physics_->robot_count(); ++r) {
        axes_.push_back(JointAxes(*physics_, r));
      }
    }
    return axes_[robot];
  }

  void Step(int n) {
    if (n < 0) throw std::invalid_argument("n: expected a count >= 0");
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    physics_->Step(n);
  }

  void SetTargets(int robot, const std::vector<double>& targets) {
    std::lock_guard<std::mutex> lock(mutex_);
    physics_->SetJointTargets(robot, targets);
  }

  // A controller run each control period (see Run).
  void SetController(py::object controller, int robot, double period) {
    const double dt = physics_->timestep();
    const double steps = period / dt;
    if (!(steps >= 1) || std::fabs(steps - std::round(steps)) > 1e-9) {
      throw std::invalid_argument(
          "period: expected a whole number (>= 1) of physics timesteps (" +
          std::to_string(dt) + " s)");
    }
    controller_ = std::move(controller);
    controller_robot_ = robot;
    steps_per_period_ = static_cast<int>(std::lround(steps));
  }

  // Runs `periods` control periods: each one asks the controller for the
  // targets of the current state, applies them and steps one period.
  void Run(int periods) {
    if (controller_.is_none()) {
      throw std::invalid_argument("run: no controller (set_controller first)");
    }
    const int robot = controller_robot_;
    const int steps = steps_per_period_;
    if (py::isinstance<GaitObject>(controller_)) {
      auto gait = controller_.cast<std::shared_ptr<GaitObject>>();
      const std::vector<Axis> known = Axes(robot);
      const std::vector<Axis> axes =
          gait->AxesFor(physics_->joint_count(robot), known);
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      for (int k = 0; k < periods; ++k) {
        physics_->SetJointTargets(robot,
                                  gait->TargetsAt(physics_->time(), axes));
        physics_->Step(steps);
      }
      return;
    }
    for (int k = 0; k < periods; ++k) {
      auto state = State(robot);
      const double t = state->state.time;
      py::object targets = controller_(t, state);
      SetTargets(robot, targets.cast<std::vector<double>>());
      Step(steps);
    }
  }

  int steps_per_period() const { return steps_per_period_; }

  // Seconds of one render of `owner`'s camera `camera` inside C++ (the
  // benchmark baseline of camera_image: no Python around it).
  double TimeCameraRender(const std::string& owner, int camera) {
    const int c = SimulationCameras::Resolve(physics_->scenario(), owner,
                                             camera, std::string());
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    const auto start = std::chrono::steady_clock::now();
    cameras_.Render(*physics_, owner, c, 0);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
        .count();
  }

  // `owner`'s camera (index, or MuJoCo name when it is a str) as an
  // (H, W, 3) uint8 array, rendered with the GIL released.
  py::array_t<std::uint8_t> CameraImage(const std::string& owner,
                                        const py::object& camera,
                                        const std::optional<int64_t>& seq) {
    const bool by_name = py::isinstance<py::str>(camera);
    const int c = SimulationCameras::Resolve(
        physics_->scenario(), owner, by_name ? 0 : camera.cast<int>(),
        by_name ? camera.cast<std::string>() : std::string());
    int width = 0, height = 0;
    for (const ScenarioCamera& rc :
         SimulationCameras::Of(physics_->scenario(), owner)) {
      if (rc.camera == c) width = rc.part.width, height = rc.part.height;
    }
    std::vector<std::uint8_t> rgb;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      // Without a seq the noise is keyed by the physics steps taken.
      const int64_t key =
          seq ? *seq : std::llround(physics_->time() / physics_->timestep());
      rgb = cameras_.Render(*physics_, owner, c, key);
    }
    py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(height),
                                   static_cast<py::ssize_t>(width),
                                   py::ssize_t{3}});
    std::copy(rgb.begin(), rgb.end(), out.mutable_data());
    return out;
  }

 private:
  std::unique_ptr<Physics> physics_;
  std::mutex mutex_;
  SimulationCameras cameras_;
  std::vector<std::vector<Axis>> axes_;
  py::object controller_ = py::none();
  int controller_robot_ = 0;
  int steps_per_period_ = 0;
};

// The physics of a Scenario or a file's path, refused as mrsim-sim
// refuses it when parts overlap at the start, unless `allow_overlap`: the
// check runs on the model just built (no second compile) and names a
// file's lines as the reader does.
std::unique_ptr<Physics> BuildPhysics(const py::object& scenario,
                                      bool allow_overlap) {
  ScenarioSource source;
  const bool from_file =
      py::isinstance<py::str>(scenario) || py::hasattr(scenario, "__fspath__");
  Scenario s;
  if (from_file) {
    ScenarioReadOptions read;
    read.source_out = &source;
    const py::object path = py::module_::import("os").attr("fspath")(scenario);
    s = ReadScenarioFile(path.cast<std::string>(), read);
  } else {
    s = scenario.cast<Scenario>();
  }
  auto physics = std::make_unique<Physics>(s);
  if (!allow_overlap) {
    RefuseOverlapsInModel(s, physics->model(), from_file ? &source : nullptr);
  }
  return physics;
}

py::array_t<double> ArrayOf(const std::vector<double>& v) {
  return py::array_t<double>(v.size(), v.data());
}

}  // namespace

void BindSimulation(py::module_& m) {
  py::class_<Simulation> c(m, "Simulation", R"doc(
A MuJoCo simulation of a scenario, in this process: the physics mrsim-sim
runs, stepped from Python. step(n) releases the GIL, so other Python
threads run meanwhile. Robots are given by index or name everywhere.)doc");
  c.def(py::init([](const py::object& scenario, bool allow_overlap) {
          return std::make_unique<Simulation>(
              BuildPhysics(scenario, allow_overlap));
        }),
        py::arg("scenario"), py::kw_only(), py::arg("allow_overlap") = false,
        R"doc(
Builds the physics of a Scenario (or of a scenario file's path). Raises
ScenarioError for a bad scenario, RuntimeError naming a part that cannot
be built. Parts that overlap at the start (two parts, a part and a scene
object, or anything and the terrain, deeper than 1 mm in the pose the
scenario gives) are refused as mrsim-sim refuses them: OverlapError (a
ScenarioError) naming each pair, unless allow_overlap=True (mrsim-sim's
--allow-overlap: the physics then pushes the parts apart at the first
step).)doc");
  c.def_static(
      "load_checkpoint",
      [](const std::string& path) {
        return std::make_unique<Simulation>(LoadCheckpoint(path));
      },
      py::arg("path"),
      "A simulation resumed from a checkpoint file (mrsim-sim "
      "--checkpoint-on-exit, mrsim-ctl save, save_checkpoint()); it continues "
      "bit for bit. Raises CheckpointError.");
  c.def_static(
      "from_checkpoint_string",
      [](const std::string& text, const std::string& name) {
        return std::make_unique<Simulation>(LoadCheckpointString(text, name));
      },
      py::arg("text"), py::arg("name") = "<string>",
      "As load_checkpoint, from the text checkpoint_string() gave.");
  c.def(
      "save_checkpoint",
      [](Simulation& s, const std::string& path) {
        std::lock_guard<std::mutex> lock(s.mutex());
        SaveCheckpoint(path, s.physics());
      },
      py::arg("path"),
      "Writes scenario and full state to a checkpoint file (atomically).");
  c.def(
      "checkpoint_string",
      [](Simulation& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return SaveCheckpointString(s.physics());
      },
      "The checkpoint as text.");
  c.def(
      "save_state",
      [](Simulation& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        const auto bytes = s.physics().SaveState();
        return py::bytes(reinterpret_cast<const char*>(bytes.data()),
                         bytes.size());
      },
      "The full physics state as bytes (no scenario); load_state() restores "
      "it so stepping continues bit for bit.");
  c.def(
      "load_state",
      [](Simulation& s, const py::bytes& data) {
        const std::string text = data;
        std::lock_guard<std::mutex> lock(s.mutex());
        s.physics().LoadState(
            std::vector<unsigned char>(text.begin(), text.end()));
      },
      py::arg("data"),
      "Restores save_state() bytes; raises ValueError for bytes of another "
      "scenario.");
  c.def("step", &Simulation::Step, py::arg("n") = 1,
        "Advances n physics timesteps with the GIL released. Raises "
        "PhysicsError when the simulation becomes unstable.");
  c.def(
      "reset",
      [](Simulation& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.physics().Reset();
      },
      "Back to the scenario's initial state, joint targets zero.");
  c.def_property_readonly(
      "time", [](Simulation& s) { return s.physics().time(); },
      "Simulation time (s).");
  c.def_property_readonly(
      "timestep", [](Simulation& s) { return s.physics().timestep(); },
      "Physics timestep (s).");
  c.def_property_readonly(
      "robots",
      [](Simulation& s) {
        std::vector<std::string> names;
        for (int r = 0; r < s.physics().robot_count(); ++r) {
          names.push_back(s.physics().robot_name(r));
        }
        return names;
      },
      "Robot names in scenario order.");
  c.def_property_readonly(
      "scenario", [](Simulation& s) { return s.physics().scenario(); },
      "A copy of the scenario simulated.");
  c.def(
      "joint_count",
      [](Simulation& s, const py::object& robot) {
        return s.physics().joint_count(s.Robot(robot));
      },
      py::arg("robot") = 0, "Number of hinge joints of a robot.");
  c.def(
      "joint_axes",
      [](Simulation& s, const py::object& robot) {
        std::vector<std::string> out;
        for (Axis a : s.Axes(s.Robot(robot))) {
          out.push_back(a == Axis::kPitch ? "pitch" : "yaw");
        }
        return out;
      },
      py::arg("robot") = 0, "Hinge axes, 'pitch' or 'yaw', chain order.");
  c.def(
      "joint_limits",
      [](Simulation& s, const py::object& robot) {
        const int r = s.Robot(robot);
        std::vector<double> lo, hi;
        for (int j = 0; j < s.physics().joint_count(r); ++j) {
          lo.push_back(s.physics().joint_lower_limit(r, j));
          hi.push_back(s.physics().joint_upper_limit(r, j));
        }
        return py::make_tuple(ArrayOf(lo), ArrayOf(hi));
      },
      py::arg("robot") = 0, "(lower, upper) joint limits (rad) as arrays.");
  c.def(
      "set_joint_targets",
      [](Simulation& s, const std::vector<double>& targets,
         const py::object& robot) { s.SetTargets(s.Robot(robot), targets); },
      py::arg("targets"), py::arg("robot") = 0,
      "Targets (rad) for every hinge, chain order; clamped to the joint "
      "limits. Raises ValueError on a wrong count or a non-finite value.");
  c.def(
      "joint_targets",
      [](Simulation& s, const py::object& robot) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return ArrayOf(s.physics().joint_targets(s.Robot(robot)));
      },
      py::arg("robot") = 0, "The targets in force (rad).");
  c.def(
      "state",
      [](Simulation& s, const py::object& robot) {
        return s.State(s.Robot(robot));
      },
      py::arg("robot") = 0,
      "The robot's state now (mrsim.State), exactly what mrsim-sim "
      "publishes.");
  c.def(
      "loose_state",
      [](Simulation& s) -> std::shared_ptr<StateObject> {
        auto state = std::make_shared<StateObject>();
        {
          std::lock_guard<std::mutex> lock(s.mutex());
          if (!s.physics().has_loose_parts()) return nullptr;
          state->state = s.physics().ReadLooseState();
          state->locks = s.physics().LockStates(kLooseOwnerName);
        }
        return state;
      },
      "The loose parts' state now (mrsim.State of the owner 'loose': "
      "frames one per loose frame, joints the loose hinges, sensor "
      "modules with their readings), what mrsim-sim publishes on "
      "<prefix>_STATE_loose; None when the scenario has no loose frame "
      "or sensor module.");
  c.def_property_readonly(
      "loose_servo_count",
      [](Simulation& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.physics().loose_servo_count();
      },
      "How many loose hinges have a servo (<servo>true</servo>): the "
      "targets set_loose_targets() takes.");
  c.def(
      "set_loose_targets",
      [](Simulation& s, const std::vector<double>& targets) {
        std::lock_guard<std::mutex> lock(s.mutex());
        s.physics().SetLooseTargets(targets);
      },
      py::arg("targets"),
      "Targets (rad) for the loose servos, one per loose hinge with a "
      "servo in the order loose_state() lists the loose hinges (passive "
      "ones skipped), as <prefix>_COMMAND_loose takes them; clamped to the "
      "limits. Raises ValueError on a wrong count or a non-finite value.");
  c.def(
      "loose_targets",
      [](Simulation& s) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return ArrayOf(s.physics().loose_targets());
      },
      "The loose servos' targets in force (rad).");
  c.def(
      "scene_objects",
      [](Simulation& s) {
        std::vector<SceneObjectState> objects;
        {
          std::lock_guard<std::mutex> lock(s.mutex());
          objects = ReadSceneObjects(s.physics());
        }
        std::vector<int> index;
        py::array_t<double> poses(
            {static_cast<py::ssize_t>(objects.size()), py::ssize_t{7}});
        double* d = poses.mutable_data();
        for (size_t i = 0; i < objects.size(); ++i) {
          index.push_back(objects[i].index);
          const Pose& p = objects[i].pose;
          const double row[7] = {p.position.x(),    p.position.y(),
                                 p.position.z(),    p.orientation.w(),
                                 p.orientation.x(), p.orientation.y(),
                                 p.orientation.z()};
          std::copy(row, row + 7, d + 7 * i);
        }
        return py::make_tuple(index, poses);
      },
      "(indices in the scenario's scene objects, poses (n, 7)) of the "
      "movable scene objects.");
  c.def(
      "locks",
      [](Simulation& s, const py::object& robot) {
        std::lock_guard<std::mutex> lock(s.mutex());
        return s.physics().LockStates(s.physics().robot_name(s.Robot(robot)));
      },
      py::arg("robot") = 0, "(name, attached) of every lock of a robot.");
  c.def(
      "detach",
      [](Simulation& s, const std::string& lock, const py::object& robot) {
        const std::string name = s.physics().robot_name(s.Robot(robot));
        std::lock_guard<std::mutex> guard(s.mutex());
        s.physics().SetLockAttached(name, lock, false);
      },
      py::arg("lock"), py::arg("robot") = 0,
      "Releases a lock (its guid or generated name, as locks() lists it). "
      "Raises PhysicsError when there is no such lock.");
  c.def(
      "attach",
      [](Simulation& s, const std::string& lock, const py::object& robot) {
        const std::string name = s.physics().robot_name(s.Robot(robot));
        std::lock_guard<std::mutex> guard(s.mutex());
        s.physics().SetLockAttached(name, lock, true);
      },
      py::arg("lock"), py::arg("robot") = 0,
      "Re-makes a released lock; it pulls its parts back to their pose in "
      "the scenario.");
  c.def(
      "cameras",
      [](Simulation& s, const py::object& robot) {
        py::list out;
        for (const ScenarioCamera& rc : SimulationCameras::Of(
                 s.physics().scenario(), s.CameraOwner(robot))) {
          py::dict d;
          d["camera"] = rc.camera;
          d["name"] = rc.name;
          d["owner"] = rc.owner;
          d["sensor_module"] = rc.sensor_module;
          d["scene_object"] = rc.scene_object;
          d["width"] = rc.part.width;
          d["height"] = rc.part.height;
          d["fovy"] = rc.part.fovy;
          d["rate"] = rc.part.rate;
          d["near"] = rc.part.near_clip;
          d["far"] = rc.part.far_clip;
          d["tilt"] = rc.part.tilt;
          d["noise"] = rc.part.noise;
          out.append(d);
        }
        return out;
      },
      py::arg("robot") = 0, R"doc(
The cameras of a robot (the <Camera> parts of its sensor modules), or with
robot="scene" those of the scene objects, with robot="loose" those of the
loose sensor modules, in the order camera_image() and camera_image_t
number them: dicts of camera (the index), name (MuJoCo's
"<robot>/sm<k>/camera<i>", "scene/obj<k>/camera<i>"), owner (the robot's
name, "scene" or "loose": camera_image_t's robot), sensor_module (-1 on a
scene object), scene_object (-1 on a sensor module), width, height (px),
fovy, tilt (deg), rate (Hz), near, far (m) and noise. Empty for an owner
without cameras.)doc");
  c.def(
      "camera_image",
      [](Simulation& s, const py::object& robot, const py::object& camera,
         std::optional<int64_t> seq) {
        if (!py::isinstance<py::int_>(camera) &&
            !py::isinstance<py::str>(camera)) {
          throw py::type_error("camera: expected an index or a camera name");
        }
        return s.CameraImage(s.CameraOwner(robot), camera, seq);
      },
      py::arg("robot") = 0, py::arg("camera") = 0, py::arg("seq") = py::none(),
      R"doc(
What a camera sees now: an (H, W, 3) uint8 array, RGB, top row first.
robot: a robot (index or name) whose camera it is, or "scene" (a scene
object's camera: sim.camera_image("scene", 0) is the first) or "loose" (a
loose sensor module's). Rendered in this process by the renderer
mrsim-camera uses (off-screen OpenGL: EGL, no display needed; made on the
first call) with the GIL released. camera: an index of cameras() or a camera's name. seq keys the
camera's pixel noise (default: the physics steps taken), so the same state
and seq give the same picture bit for bit. Raises IndexError naming the
robots or cameras that exist, RuntimeError naming what OpenGL could not
make. Any thread may call it; renders are serialised.)doc");
  c.def(
      "set_controller",
      [](Simulation& s, py::object controller, const py::object& robot,
         double period) {
        if (!py::isinstance<GaitObject>(controller) &&
            !PyCallable_Check(controller.ptr())) {
          throw py::type_error(
              "controller: expected a mrsim.Gait or a callable (t, state) -> "
              "targets");
        }
        s.SetController(std::move(controller), s.Robot(robot), period);
      },
      py::arg("controller"), py::arg("robot") = 0, py::arg("period") = 0.01,
      R"doc(
Attaches a controller run once per control period (period s, a whole
number of timesteps): a mrsim.Gait (run in C++ with the GIL released) or a
callable controller(t, state) -> targets. Each period: targets of the
current state, applied, then one period stepped: what mrsim-sim does in
lockstep with mrsim-gait.)doc");
  c.def(
      "run",
      [](Simulation& s, double seconds) {
        if (!(seconds >= 0) || !std::isfinite(seconds)) {
          throw std::invalid_argument("seconds: expected a time >= 0");
        }
        if (s.steps_per_period() == 0) {
          throw std::invalid_argument(
              "run: no controller (set_controller first)");
        }
        const double period = s.steps_per_period() * s.physics().timestep();
        s.Run(static_cast<int>(std::lround(seconds / period)));
      },
      py::arg("seconds"),
      "Runs the controller for round(seconds / period) control periods.");

  // The baseline of bench/python's python_step_ratio: the same Step(n) on
  // the same physics, timed inside C++ (no Python call around it).
  m.def(
      "_time_cpp_step",
      [](Simulation& s, int n) {
        if (n < 0) throw std::invalid_argument("n: expected a count >= 0");
        py::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(s.mutex());
        const auto start = std::chrono::steady_clock::now();
        s.physics().Step(n);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                             start)
            .count();
      },
      py::arg("simulation"), py::arg("n"),
      "Seconds of Physics::Step(n) on this simulation timed in C++ (the "
      "benchmark baseline of Simulation.step).");
  m.def(
      "_time_cpp_camera",
      [](Simulation& s, const py::object& robot, int camera) {
        return s.TimeCameraRender(s.CameraOwner(robot), camera);
      },
      py::arg("simulation"), py::arg("robot") = 0, py::arg("camera") = 0,
      "Seconds of one CameraImageRenderer::Render of a camera timed in C++ "
      "(the benchmark baseline of Simulation.camera_image).");
}

}  // namespace mrsim::python

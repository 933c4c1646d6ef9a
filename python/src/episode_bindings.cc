// mrsim.run_episode: one optimiser episode (optimizer/episode/episode.h) of a
// gait on a scenario, scored with the optimiser's fitness.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "optimizer/episode/episode.h"
#include "optimizer/episode/task.h"
#include "python/src/bindings.h"
#include "python/src/gait_object.h"
#include "sim_core/export/overlap_check.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

py::dict ResultDict(const EvalResult& r) {
  py::dict d;
  d["fitness"] = r.fitness;
  d["distance"] = r.distance;
  d["speed"] = r.speed;
  d["energy"] = r.energy;
  d["drift"] = r.drift;
  d["fell"] = r.fell;
  d["failed"] = r.failed;
  return d;
}

}  // namespace

void BindEpisode(py::module_& m) {
  m.def(
      "run_episode",
      [](const Scenario& scenario, const std::shared_ptr<GaitObject>& gait,
         double duration, double control_period, const std::string& robot,
         const std::string& distance_mode, double w_distance, double w_speed,
         double w_energy, double w_drift, double w_fall, bool allow_overlap) {
        Problem problem;
        problem.scenario = scenario;
        problem.genome.robot = robot;
        problem.episode.duration = duration;
        problem.episode.control_period = control_period;
        problem.episode.base_gait = gait->gait();
        problem.episode.allow_overlap = allow_overlap;
        FitnessSettings& f = problem.episode.fitness;
        f.distance_mode = ParseDistanceMode(distance_mode, "distance_mode");
        f.w_distance = w_distance;
        f.w_speed = w_speed;
        f.w_energy = w_energy;
        f.w_drift = w_drift;
        f.w_fall = w_fall;
        problem.episode.Validate();
        EvalResult r;
        {
          py::gil_scoped_release release;
          // As mrsim-opt refuses a scenario file: an overlap would score
          // the physics pushing the parts apart as distance.
          if (!allow_overlap) RefuseOverlaps(problem.scenario);
          r = RunEpisode(problem, Genome{});
        }
        return ResultDict(r);
      },
      py::arg("scenario"), py::arg("gait"), py::arg("duration") = 20.0,
      py::arg("control_period") = 0.01, py::arg("robot") = "",
      py::arg("distance_mode") = "forward", py::arg("w_distance") = 1.0,
      py::arg("w_speed") = 0.0, py::arg("w_energy") = 0.0,
      py::arg("w_drift") = 0.0, py::arg("w_fall") = 0.0, py::kw_only(),
      py::arg("allow_overlap") = false, R"doc(
Runs one optimiser episode: the gait on the scenario's robot (robot name,
default the first) for `duration` s of sim time at full speed, scored as
mrsim-opt scores it:
  fitness = distance*w_distance + speed*w_speed - energy*w_energy
            - drift*w_drift - fell*w_fall
Returns a dict with fitness, distance (m), speed (m/s), energy (J),
drift (m), fell (fraction of time upside down) and failed (unstable).
distance_mode: 'forward' (+x), 'net' or 'up' (+z). The GIL is released meanwhile.
A scenario whose parts overlap at the start raises OverlapError naming
them, as mrsim-opt refuses it, unless allow_overlap=True.)doc");
  m.def(
      "run_task",
      [](const std::string& task, const py::object& gait, double seconds) {
        const Task t = MakeTask(task);
        const Gait g = gait.is_none()
                           ? t.gait
                           : gait.cast<std::shared_ptr<GaitObject>>()->gait();
        EvalResult r;
        {
          py::gil_scoped_release release;
          r = EvaluateTask(t, g, seconds);
        }
        return ResultDict(r);
      },
      py::arg("task"), py::arg("gait") = py::none(), py::arg("seconds") = 0.0,
      R"doc(
Runs one episode of a task of the suite (docs/tasks.md), as
`mrsim tasks TASK --gait GAIT` does: the task's world and robot, the gait
(default: the task's own, task_info(task)["gait"]) for `seconds` s of sim
time (0: the task's episode length), scored by the task's fitness
(distance along +x, or the rise of the centre of mass on the pole).
Returns the dict of run_episode. ValueError for an unknown task naming
the known ones. The GIL is released meanwhile.)doc");
}

}  // namespace mrsim::python

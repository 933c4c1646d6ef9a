#include "launcher/run_summary.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/scenario/scene_object_name.h"

namespace mrsim {
namespace {

Eigen::Vector3d BodyPosition(const Physics& physics, const std::string& name) {
  const int id = mj_name2id(physics.model(), mjOBJ_BODY, name.c_str());
  if (id < 0) throw std::runtime_error("no body named " + name);
  const mjtNum* p = physics.data()->xpos + 3 * id;
  return Eigen::Vector3d(p[0], p[1], p[2]);
}

// To the printed millimetre, without a minus on a zero ("-0.000").
double Millimetres(double metres) {
  const double rounded = std::round(metres * 1000) / 1000;
  return rounded == 0 ? 0.0 : rounded;
}

}  // namespace

RunSummary SummarizeRun(const Physics& start, const Physics& end) {
  if (start.robot_count() != end.robot_count() ||
      start.scenario().scene_objects.size() !=
          end.scenario().scene_objects.size()) {
    throw std::invalid_argument(
        "not the end of a run of this scenario (its robots or scene "
        "objects differ); give the scenario the run started from, then its "
        "checkpoint");
  }
  RunSummary summary;
  summary.sim_time = end.time();
  for (int r = 0; r < start.robot_count(); ++r) {
    summary.robots.push_back(
        {start.robot_name(r), start.CenterOfMass(r), end.CenterOfMass(r)});
  }
  const auto& objects = start.scenario().scene_objects;
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].is_static) continue;
    const std::string body = mjcf_names::SceneObject(static_cast<int>(i));
    // As the user called it ("ball"), as the overlap check names it.
    summary.objects.push_back({SceneObjectLabel(objects[i], i),
                               BodyPosition(start, body),
                               BodyPosition(end, body)});
  }
  return summary;
}

std::string FormatRunSummary(const RunSummary& summary) {
  std::string line = fmt::format("{:.1f} s:", summary.sim_time);
  const char* sep = " ";
  for (const auto& r : summary.robots) {
    const Eigen::Vector3d d = r.end - r.start;
    line +=
        fmt::format("{}{} moved {:.3f} m (dx {:+.3f}, dy {:+.3f})", sep, r.name,
                    r.distance(), Millimetres(d.x()), Millimetres(d.y()));
    sep = "; ";
  }
  for (const auto& o : summary.objects) {
    const Eigen::Vector3d d = o.end - o.start;
    line += fmt::format("{}{} displaced {:.3f} m (dx {:+.3f}, dy {:+.3f})", sep,
                        o.name, o.distance(), Millimetres(d.x()),
                        Millimetres(d.y()));
  }
  return line;
}

}  // namespace mrsim

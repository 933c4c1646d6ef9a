#include "sim_core/scenario_tool/scenario_summary.h"

#include <fmt/format.h>

#include <map>

#include "sim_core/scenario/terrain.h"

namespace mrsim {

namespace {}  // namespace

double RobotMass(const Robot& robot) {
  double mass = 0;
  for (const Module& m : robot.modules) {
    for (const Frame& f : m.frames) mass += f.mass;
  }
  for (const SensorModule& s : robot.sensor_modules) {
    mass += s.mass;
    if (s.force_sensor) mass += s.force_sensor->mass;
    for (const DistanceSensor& d : s.distance_sensors) mass += d.mass;
  }
  return mass;
}

std::string SummarizeScenario(const Scenario& s) {
  std::string out = fmt::format("robots: {}\n", s.robots.size());
  for (const Robot& r : s.robots) {
    int pitch = 0, yaw = 0, force = 0, distance = 0;
    for (const Module& m : r.modules) (m.axis == Axis::kPitch ? pitch : yaw)++;
    for (const SensorModule& sm : r.sensor_modules) {
      force += sm.force_sensor ? 1 : 0;
      distance += static_cast<int>(sm.distance_sensors.size());
    }
    out += fmt::format(
        "  {}: {} ({} pitch, {} yaw), {}, {}, {}, {}, {}, mass {:.4g} kg\n",
        r.name, Counted(r.modules.size(), "module"), pitch, yaw,
        Counted(r.modules.size(), "hinge joint"),
        Counted(r.locks.size(), "lock"),
        Counted(r.sensor_modules.size(), "sensor module"),
        Counted(force, "force sensor"), Counted(distance, "distance sensor"),
        RobotMass(r));
  }
  std::map<std::string, int> shapes;
  for (const SceneObject& o : s.scene_objects) {
    shapes[std::string(ToString(o.shape)) + (o.is_static ? " (static)" : "")]++;
  }
  out += fmt::format("scene objects: {}", s.scene_objects.size());
  const char* sep = " (";
  for (const auto& [shape, count] : shapes) {
    out += fmt::format("{}{} {}", sep, count, shape);
    sep = ", ";
  }
  out += s.scene_objects.empty() ? "\n" : ")\n";
  if (s.scene.height_image.empty()) {
    out += fmt::format("terrain: flat ground at z = {}, material {}\n",
                       s.scene.position.z(), s.scene.material_name);
  } else {
    const TerrainImage image = LoadTerrainImage(s.scene, s.base_dir);
    out += fmt::format(
        "terrain: height field {} ({}x{} px), {:.4g} x {:.4g} m, height "
        "{} m, corner ({}, {}, {}), material {}\n",
        image.source, image.cols, image.rows,
        image.cols * s.scene.meters_per_pixel,
        image.rows * s.scene.meters_per_pixel, s.scene.height,
        s.scene.position.x(), s.scene.position.y(), s.scene.position.z(),
        s.scene.material_name);
  }
  out += fmt::format("contact frictions: {}\n", s.contact_frictions.size());
  for (const ContactFriction& f : s.contact_frictions) {
    out += fmt::format(
        "  {}/{}: friction {}, restitution {}, youngsModulus {}\n", f.material1,
        f.material2, f.friction, f.restitution, f.youngs_modulus);
  }
  out += fmt::format("fluid regions: {}\n", s.fluid_regions.size());
  if (!s.loose_frames.empty() || !s.loose_joints.empty() ||
      !s.loose_sensor_modules.empty()) {
    out += fmt::format("loose parts: {}, {}, {}\n",
                       Counted(s.loose_frames.size(), "frame"),
                       Counted(s.loose_joints.size(), "joint"),
                       Counted(s.loose_sensor_modules.size(), "sensor module"));
  }
  out += fmt::format("settings: timestep {} s, gravity ({}, {}, {})\n",
                     s.settings.timestep, s.settings.gravity.x(),
                     s.settings.gravity.y(), s.settings.gravity.z());
  return out;
}

std::string Counted(size_t n, const char* what) {
  return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s");
}

}  // namespace mrsim

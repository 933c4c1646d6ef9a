#include "foxglove/scene_model.h"

#include <algorithm>
#include <cmath>

namespace mrsim::foxglove {
namespace {

constexpr double kDefaultEdge = 0.05;    // m, a robot of one frame
constexpr double kObjectDiameter = 0.1;  // m
constexpr double kGroundSize = 20.0;     // m

struct Color {
  double r, g, b, a;
};
// Robots in turn: orange, blue, green, purple (the viewer's palette order).
constexpr Color kRobotColors[] = {{0.95, 0.55, 0.15, 1.0},
                                  {0.20, 0.45, 0.90, 1.0},
                                  {0.25, 0.70, 0.30, 1.0},
                                  {0.60, 0.35, 0.80, 1.0}};
constexpr Color kSensorColor = {0.85, 0.85, 0.20, 1.0};
constexpr Color kObjectColor = {0.60, 0.60, 0.65, 1.0};
constexpr Color kGroundColor = {0.45, 0.45, 0.45, 1.0};

void Time(JsonWriter& out, uint64_t ns) {
  out.Raw("{\"sec\":");
  out.Int(static_cast<int64_t>(ns / 1000000000u));
  out.Raw(",\"nsec\":");
  out.Int(static_cast<int64_t>(ns % 1000000000u));
  out.Raw("}");
}

void Vector(JsonWriter& out, double x, double y, double z) {
  out.Raw("{\"x\":");
  out.Double(x);
  out.Raw(",\"y\":");
  out.Double(y);
  out.Raw(",\"z\":");
  out.Double(z);
  out.Raw("}");
}

void Shape(JsonWriter& out, const char* kind, double sx, double sy, double sz,
           double z, const Color& c) {
  out.Raw(",\"");
  out.Raw(kind);
  out.Raw("\":[{\"pose\":{\"position\":");
  Vector(out, 0, 0, z);
  out.Raw(",\"orientation\":{\"x\":0,\"y\":0,\"z\":0,\"w\":1}},\"size\":");
  Vector(out, sx, sy, sz);
  out.Raw(",\"color\":{\"r\":");
  out.Double(c.r);
  out.Raw(",\"g\":");
  out.Double(c.g);
  out.Raw(",\"b\":");
  out.Double(c.b);
  out.Raw(",\"a\":");
  out.Double(c.a);
  out.Raw("}}]");
}

void EntityStart(JsonWriter& out, bool& first, uint64_t time_ns,
                 const std::string& id, const std::string& frame) {
  out.Raw(first ? "{" : ",{");
  first = false;
  out.Raw("\"timestamp\":");
  Time(out, time_ns);
  out.Raw(",\"frame_id\":");
  out.String(frame);
  out.Raw(",\"id\":");
  out.String(id);
  out.Raw(",\"frame_locked\":true");
}

void Transform(JsonWriter& out, bool& first, uint64_t time_ns,
               const std::string& child, const pose_t& pose) {
  out.Raw(first ? "{" : ",{");
  first = false;
  out.Raw("\"timestamp\":");
  Time(out, time_ns);
  out.Raw(",\"parent_frame_id\":\"world\",\"child_frame_id\":");
  out.String(child);
  out.Raw(",\"translation\":");
  Vector(out, pose.position[0], pose.position[1], pose.position[2]);
  // MuJoCo's quaternion is (w, x, y, z); Foxglove's has named fields.
  out.Raw(",\"rotation\":{\"x\":");
  out.Double(pose.orientation[1]);
  out.Raw(",\"y\":");
  out.Double(pose.orientation[2]);
  out.Raw(",\"z\":");
  out.Double(pose.orientation[3]);
  out.Raw(",\"w\":");
  out.Double(pose.orientation[0]);
  out.Raw("}}");
}

double Edge(const robot_state_t& s) {
  if (s.frames.size() < 2) return kDefaultEdge;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = s.frames[1].position[k] - s.frames[0].position[k];
    d2 += d * d;
  }
  const double d = std::sqrt(d2);
  if (!std::isfinite(d)) return kDefaultEdge;
  return std::clamp(d, 0.01, 0.5);
}

}  // namespace

std::string SceneModel::FrameName(const std::string& robot, int k) {
  return robot + "/frame_" + std::to_string(k);
}
std::string SceneModel::SensorName(const std::string& robot, int k) {
  return robot + "/sensor_" + std::to_string(k);
}
std::string SceneModel::ObjectName(int index) {
  return "scene/object_" + std::to_string(index);
}

bool SceneModel::OnRobotState(const robot_state_t& state) {
  auto it = robots_.find(state.robot);
  if (it == robots_.end()) {
    if (robots_.size() >= kMaxRobots) return false;
    it = robots_.emplace(state.robot, Robot{}).first;
    it->second.frames = -1;
  }
  Robot& r = it->second;
  const int frames = static_cast<int>(state.frames.size());
  const int sensors = static_cast<int>(state.sensor_modules.size());
  if (r.frames == frames && r.sensors == sensors) return false;
  r.frames = frames;
  r.sensors = sensors;
  r.edge = Edge(state);
  return true;
}

bool SceneModel::OnSceneState(const scene_state_t& state) {
  bool changed = false;
  for (const int32_t index : state.object_index) {
    if (objects_.size() >= 65536) break;
    changed |= objects_.emplace(index, true).second;
  }
  return changed;
}

std::string SceneModel::SceneUpdateJson(uint64_t time_ns) const {
  JsonWriter out;
  out.Raw("{\"deletions\":[{\"timestamp\":");
  Time(out, time_ns);
  out.Raw(",\"type\":1,\"id\":\"\"}],\"entities\":[");
  bool first = true;
  EntityStart(out, first, time_ns, "ground", "world");
  Shape(out, "cubes", kGroundSize, kGroundSize, 0.002, -0.001, kGroundColor);
  out.Raw("}");
  size_t robot_number = 0;
  for (const auto& [name, r] : robots_) {
    const Color& color =
        kRobotColors[robot_number++ % (sizeof(kRobotColors) / sizeof(Color))];
    for (int k = 0; k < r.frames; ++k) {
      const std::string frame = FrameName(name, k);
      EntityStart(out, first, time_ns, frame, frame);
      // A frame is half a module: a little less than the spacing, so
      // neighbours show as separate blocks.
      Shape(out, "cubes", 0.9 * r.edge, 0.9 * r.edge, 0.9 * r.edge, 0, color);
      out.Raw("}");
    }
    for (int k = 0; k < r.sensors; ++k) {
      const std::string frame = SensorName(name, k);
      EntityStart(out, first, time_ns, frame, frame);
      Shape(out, "cubes", 0.8 * r.edge, 0.8 * r.edge, 0.8 * r.edge, 0,
            kSensorColor);
      out.Raw("}");
    }
  }
  for (const auto& [index, unused] : objects_) {
    const std::string frame = ObjectName(index);
    EntityStart(out, first, time_ns, frame, frame);
    Shape(out, "spheres", kObjectDiameter, kObjectDiameter, kObjectDiameter, 0,
          kObjectColor);
    out.Raw("}");
  }
  out.Raw("]}");
  return std::string(out.view());
}

std::string_view SceneModel::FrameTransformsJson(const robot_state_t& state,
                                                 uint64_t time_ns) {
  json_.Clear();
  json_.Raw("{\"transforms\":[");
  bool first = true;
  for (size_t k = 0; k < state.frames.size(); ++k) {
    Transform(json_, first, time_ns,
              FrameName(state.robot, static_cast<int>(k)), state.frames[k]);
  }
  for (size_t k = 0; k < state.sensor_modules.size(); ++k) {
    Transform(json_, first, time_ns,
              SensorName(state.robot, static_cast<int>(k)),
              state.sensor_modules[k].pose);
  }
  json_.Raw("]}");
  return json_.view();
}

std::string_view SceneModel::FrameTransformsJson(const scene_state_t& state,
                                                 uint64_t time_ns) {
  json_.Clear();
  json_.Raw("{\"transforms\":[");
  bool first = true;
  const size_t n = std::min(state.object_index.size(), state.poses.size());
  for (size_t i = 0; i < n; ++i) {
    Transform(json_, first, time_ns, ObjectName(state.object_index[i]),
              state.poses[i]);
  }
  json_.Raw("]}");
  return json_.view();
}

}  // namespace mrsim::foxglove

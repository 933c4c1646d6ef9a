#include "studio/design/inspector_fields.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/scenario/sensor_kind.h"
#include "studio/design/inert_fields.h"

namespace mrsim::studio {
namespace {

// A group title from a name used inside messages ("front frame").
std::string Capitalised(std::string text) {
  if (!text.empty()) {
    text[0] =
        static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  }
  return text;
}

}  // namespace

std::vector<FieldGroup> InspectorFields(Scenario& s, const Selection& sel) {
  std::vector<FieldGroup> groups;
  auto robot_ok = [&]() {
    return sel.robot >= 0 && sel.robot < static_cast<int>(s.robots.size());
  };
  auto in = [](int i, size_t n) { return i >= 0 && i < static_cast<int>(n); };
  switch (sel.kind) {
    case SelectionKind::kRobot:
      if (robot_ok()) {
        groups.push_back({"", "Robot", FieldsOf(s.robots[sel.robot])});
      }
      break;
    case SelectionKind::kModule:
      if (robot_ok() && in(sel.index, s.robots[sel.robot].modules.size())) {
        Module& m = s.robots[sel.robot].modules[sel.index];
        groups.push_back({"", "Module", FieldsOf(m)});
        // A module's joint is its hinge: Lock would be refused, and a lock
        // never breaks there.
        groups.push_back(
            {"joint", "Joint", JointFields(m.joint, JointPlace::kModule)});
        groups.push_back({"frames[0]", Capitalised(FrameName(0)),
                          WithoutInert(FieldsOf(m.frames[0]), {"rotation"})});
        groups.push_back({"frames[1]", Capitalised(FrameName(1)),
                          WithoutInert(FieldsOf(m.frames[1]), {"rotation"})});
      }
      break;
    case SelectionKind::kSensorModule:
      if (robot_ok() &&
          in(sel.index, s.robots[sel.robot].sensor_modules.size())) {
        SensorModule& sm = s.robots[sel.robot].sensor_modules[sel.index];
        groups.push_back(
            {"", "Sensor module",
             WithoutInert(FieldsOf(sm), {"rotation", "forceLockPosition",
                                         "distanceLockPosition"})});
        // One group per sensor, named by its member in the scenario
        // ("force_sensor", "distance_sensors[1]", "imu") and titled by
        // its kind's label ("Force plate", "Distance sensor 1", "IMU").
        for (const SensorKind& kind : SensorKinds()) {
          if (kind.fields == nullptr) continue;
          for (int k = 0; k < kind.count(sm); ++k) {
            std::string id = kind.member;
            std::string title = kind.label;
            title[0] = static_cast<char>(std::toupper(title[0]));
            if (kind.many) {
              id += "[" + std::to_string(k) + "]";
              title += " " + std::to_string(k);
            }
            groups.push_back(
                {id, title,
                 WithoutInert(kind.fields(sm, k), kind.inert_fields)});
          }
        }
      }
      break;
    case SelectionKind::kSceneObject:
      if (in(sel.index, s.scene_objects.size())) {
        SceneObject& o = s.scene_objects[sel.index];
        groups.push_back(
            {"", "Scene object", WithoutInert(FieldsOf(o), {"rotation"})});
        // Its cameras, as a sensor module's: "cameras[k]", "Camera k".
        for (size_t k = 0; k < o.cameras.size(); ++k) {
          groups.push_back({"cameras[" + std::to_string(k) + "]",
                            "Camera " + std::to_string(k),
                            FieldsOf(o.cameras[k])});
        }
      }
      break;
    case SelectionKind::kScene:
      groups.push_back({"", "Terrain", TerrainFields(s.scene)});
      break;
    case SelectionKind::kFluidRegion:
      if (in(sel.index, s.fluid_regions.size())) {
        groups.push_back(
            {"", "Fluid region", FieldsOf(s.fluid_regions[sel.index])});
      }
      break;
    case SelectionKind::kContactFriction:
      if (in(sel.index, s.contact_frictions.size())) {
        groups.push_back(
            {"", "Contact material", FieldsOf(s.contact_frictions[sel.index])});
      }
      break;
    case SelectionKind::kSettings:
      groups.push_back({"", "Simulation", FieldsOf(s.settings)});
      break;
    case SelectionKind::kLock:
      if (robot_ok() && in(sel.index, s.robots[sel.robot].locks.size())) {
        groups.push_back({"", "Lock",
                          JointFields(s.robots[sel.robot].locks[sel.index],
                                      JointPlace::kRobotLock)});
      }
      break;
    case SelectionKind::kLooseFrame:
      if (in(sel.index, s.loose_frames.size())) {
        groups.push_back(
            {"", "Loose frame",
             WithoutInert(FieldsOf(s.loose_frames[sel.index]), {"rotation"})});
      }
      break;
    case SelectionKind::kLooseJoint:
      if (in(sel.index, s.loose_joints.size())) {
        groups.push_back(
            {"", "Loose joint",
             JointFields(s.loose_joints[sel.index], JointPlace::kLoose)});
      }
      break;
    case SelectionKind::kLooseSensorModule:
      if (in(sel.index, s.loose_sensor_modules.size())) {
        SensorModule& sm = s.loose_sensor_modules[sel.index];
        groups.push_back(
            {"", "Loose sensor module",
             WithoutInert(FieldsOf(sm), {"rotation", "forceLockPosition",
                                         "distanceLockPosition", "leftMod_Nr",
                                         "rightMod_Nr"})});
        for (size_t k = 0; k < sm.cameras.size(); ++k) {
          groups.push_back({"cameras[" + std::to_string(k) + "]",
                            "Camera " + std::to_string(k),
                            FieldsOf(sm.cameras[k])});
        }
      }
      break;
    case SelectionKind::kNone:
      break;
  }
  for (FieldGroup& group : groups) {
    group.fields = WithoutUnused(std::move(group.fields));
  }
  return groups;
}

const char* ToString(SelectionKind kind) {
  switch (kind) {
    case SelectionKind::kNone:
      return "none";
    case SelectionKind::kRobot:
      return "robot";
    case SelectionKind::kModule:
      return "module";
    case SelectionKind::kSensorModule:
      return "sensor_module";
    case SelectionKind::kSceneObject:
      return "object";
    case SelectionKind::kScene:
      return "terrain";
    case SelectionKind::kFluidRegion:
      return "fluid";
    case SelectionKind::kContactFriction:
      return "contact";
    case SelectionKind::kSettings:
      return "settings";
    case SelectionKind::kLock:
      return "lock";
    case SelectionKind::kLooseFrame:
      return "loose_frame";
    case SelectionKind::kLooseJoint:
      return "loose_joint";
    case SelectionKind::kLooseSensorModule:
      return "loose_sensor_module";
  }
  return "?";
}

std::string FieldLabel(const FieldInfo& info) {
  std::string label = info.label;
  if (*info.unit) label += std::string(" (") + info.unit + ")";
  return label;
}

std::string FieldTooltip(const FieldInfo& info) {
  std::string text =
      std::string(info.help) + "\nin the file: <" + info.xml + ">";
  const FieldLimits& l = info.limits;
  char buf[96] = "";
  if (std::isfinite(l.min) && std::isfinite(l.max)) {
    std::snprintf(buf, sizeof(buf), "%g .. %g", l.min, l.max);
  } else if (std::isfinite(l.min)) {
    std::snprintf(buf, sizeof(buf), "%s %g",
                  l.min_exclusive ? ">" : ">=", l.min);
  }
  if (*buf) text += std::string("\nlimits: ") + buf;
  return text;
}

std::string ShortNumbers(const std::string& text) {
  const auto numeric = [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) || c == '.' ||
           c == '-' || c == '+' || c == 'e' || c == 'E';
  };
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    if (!numeric(text[i])) {
      out += text[i++];
      continue;
    }
    size_t j = i;
    while (j < text.size() && numeric(text[j])) ++j;
    const std::string token = text.substr(i, j - i);
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    char buf[32];
    if (end == token.c_str() + token.size() && std::isfinite(value) &&
        std::snprintf(buf, sizeof buf, "%.10g", value) > 0 &&
        std::strlen(buf) < token.size()) {
      out += buf;
    } else {
      out += token;
    }
    i = j;
  }
  return out;
}

std::string ShapeSummary(const std::string& shape) {
  if (!IsEmbeddedMesh(shape)) return shape;
  // Sized from the base64 text: decoding a mesh every frame to draw its
  // name would cost more than the whole panel.
  const size_t prefix = std::string("base64:").size();
  const size_t name_at = shape.rfind(':');
  if (name_at < prefix) return "mesh (embedded, malformed)";
  const std::string name = shape.substr(name_at + 1);
  const size_t encoded = name_at - prefix;
  char size[32];
  std::snprintf(size, sizeof size, "%.1f kB", encoded * 3.0 / 4.0 / 1000.0);
  return (name.empty() ? std::string("mesh") : name) + " (embedded, " + size +
         ")";
}

}  // namespace mrsim::studio

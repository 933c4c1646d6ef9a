// TEMPORARY ADAPTER (see schema_adapter.h): deleted when the schema lands.
#include "studio/schema_adapter.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sim_core/scenario_xml.h"

namespace mrsim {
namespace {

FieldLimits Positive() {
  FieldLimits l;
  l.min = 0;
  l.min_exclusive = true;
  return l;
}
FieldLimits NonNegative() {
  FieldLimits l;
  l.min = 0;
  return l;
}
FieldLimits Range(double min, double max, const char* meaning = "") {
  FieldLimits l;
  l.min = min;
  l.max = max;
  l.meaning = meaning;
  return l;
}
FieldLimits NonEmpty() {
  FieldLimits l;
  l.nonempty = true;
  return l;
}
FieldLimits Any() { return {}; }

std::string Num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

double ParseNum(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == text.c_str() || *end != '\0' ||
      !std::isfinite(v)) {
    throw FieldError("expected a number, got '" + text + "'");
  }
  return v;
}

std::string CheckNumber(const FieldLimits& l, double v) {
  const bool low = l.min_exclusive ? !(v > l.min) : !(v >= l.min);
  if (low || !(v <= l.max)) {
    if (l.min_exclusive && l.min == 0 && std::isinf(l.max)) {
      return "expected a positive value, got " + Num(v);
    }
    if (std::isinf(l.max)) {
      return "expected a value >= " + Num(l.min) + ", got " + Num(v);
    }
    return "expected a value in [" + Num(l.min) + ", " + Num(l.max) + "]" +
           (*l.meaning ? std::string(" (") + l.meaning + ")" : "") + ", got " +
           Num(v);
  }
  return "";
}

template <typename E>
struct ChoiceNames;
template <>
struct ChoiceNames<Axis> {
  static std::vector<std::string> Get() { return {"Pitch", "Yaw"}; }
};
template <>
struct ChoiceNames<JointType> {
  static std::vector<std::string> Get() { return {"Hinge", "Lock"}; }
};
template <>
struct ChoiceNames<PrimitiveShape> {
  static std::vector<std::string> Get() {
    return {"Box", "Sphere", "Cylinder", "Capsule"};
  }
};
template <>
struct ChoiceNames<FluidKind> {
  static std::vector<std::string> Get() { return {"Water", "Air"}; }
};

struct Visitor {
  const FieldInfo& info;
  const std::string* text = nullptr;  // set: parse and store
  std::string out;

  void operator()(std::string* p) {
    if (!text) {
      out = *p;
      return;
    }
    if (info.limits.nonempty && text->empty()) {
      throw FieldError("expected a non-empty text");
    }
    *p = *text;
  }
  void operator()(double* p) {
    if (!text) {
      out = Num(*p);
      return;
    }
    const double v = ParseNum(*text);
    const std::string problem = CheckNumber(info.limits, v);
    if (!problem.empty()) throw FieldError(problem);
    *p = v;
  }
  void operator()(int* p) {
    if (!text) {
      out = std::to_string(*p);
      return;
    }
    const double v = ParseNum(*text);
    if (v != std::floor(v)) {
      throw FieldError("expected an integer, got '" + *text + "'");
    }
    const std::string problem = CheckNumber(info.limits, v);
    if (!problem.empty()) throw FieldError(problem);
    *p = static_cast<int>(v);
  }
  void operator()(bool* p) {
    if (!text) {
      out = *p ? "true" : "false";
      return;
    }
    if (*text != "true" && *text != "false") {
      throw FieldError("expected true or false, got '" + *text + "'");
    }
    *p = *text == "true";
  }
  void operator()(Eigen::Vector3d* p) {
    if (!text) {
      out = Num(p->x()) + " " + Num(p->y()) + " " + Num(p->z());
      return;
    }
    std::istringstream in(*text);
    std::string a, b, c, extra;
    in >> a >> b >> c;
    if (c.empty() || (in >> extra)) {
      throw FieldError("expected three numbers 'x y z', got '" + *text + "'");
    }
    const Eigen::Vector3d v(ParseNum(a), ParseNum(b), ParseNum(c));
    for (int i = 0; i < 3; ++i) {
      const std::string problem = CheckNumber(info.limits, v[i]);
      if (!problem.empty()) throw FieldError(problem);
    }
    *p = v;
  }
  void operator()(Eigen::Quaterniond* p) {
    if (!text) {
      out = Num(p->x()) + " " + Num(p->y()) + " " + Num(p->z()) + " " +
            Num(p->w());
      return;
    }
    std::istringstream in(*text);
    double x, y, z, w;
    if (!(in >> x >> y >> z >> w)) {
      throw FieldError("expected four numbers 'x y z w', got '" + *text + "'");
    }
    *p = Eigen::Quaterniond(w, x, y, z);
  }
  template <typename E>
  void Choice(E* p) {
    const auto names = ChoiceNames<E>::Get();
    if (!text) {
      out = names[static_cast<int>(*p)];
      return;
    }
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == *text) {
        *p = static_cast<E>(i);
        return;
      }
    }
    throw FieldError("expected one of the listed names, got '" + *text + "'");
  }
  void operator()(Axis* p) { Choice(p); }
  void operator()(JointType* p) { Choice(p); }
  void operator()(PrimitiveShape* p) { Choice(p); }
  void operator()(FluidKind* p) { Choice(p); }
};

}  // namespace

FieldType FieldRef::type() const {
  switch (value_.index()) {
    case 0:
      return FieldType::kText;
    case 1:
      return FieldType::kNumber;
    case 2:
      return FieldType::kInteger;
    case 3:
      return FieldType::kBool;
    case 4:
      return FieldType::kVector;
    case 5:
      return FieldType::kQuaternion;
    default:
      return FieldType::kChoice;
  }
}

std::vector<std::string> FieldRef::choices() const {
  if (std::get_if<Axis*>(&value_)) return ChoiceNames<Axis>::Get();
  if (std::get_if<JointType*>(&value_)) return ChoiceNames<JointType>::Get();
  if (std::get_if<PrimitiveShape*>(&value_)) {
    return ChoiceNames<PrimitiveShape>::Get();
  }
  if (std::get_if<FluidKind*>(&value_)) return ChoiceNames<FluidKind>::Get();
  return {};
}

std::string FieldRef::GetText() const {
  Visitor v{*info_, nullptr, {}};
  std::visit(v, value_);
  return v.out;
}

void FieldRef::SetText(const std::string& text) const {
  Visitor v{*info_, &text, {}};
  std::visit(v, value_);
}

std::string FieldRef::Check() const { return ""; }

#define F(xml, member, unit, limits, help) \
  static const FieldInfo k_##member{xml, #member, unit, limits, help};
#define REF(member) FieldRef(k_##member, &p.member)

std::vector<FieldRef> FieldsOf(Robot& p) {
  F("name", name, "", NonEmpty(), "Unique robot name, used in LCM channels");
  return {REF(name)};
}
std::vector<FieldRef> FieldsOf(Module& p) {
  F("axis", axis, "", Any(), "Pitch bends up/down, Yaw left/right");
  return {REF(axis)};
}
std::vector<FieldRef> FieldsOf(Frame& p) {
  F("shape", shape, "", NonEmpty(), "Box, or a mesh file (.obj/.stl)");
  F("scale", scale, "m", Positive(), "Box: full extents; mesh: scale");
  F("mass", mass, "kg", Positive(), "Mass of the frame");
  F("materialName", material_name, "", NonEmpty(), "Contact material");
  F("isStatic", is_static, "", Any(), "Fixed in the world");
  return {REF(shape), REF(scale), REF(mass), REF(material_name),
          REF(is_static)};
}
std::vector<FieldRef> FieldsOf(Joint& p) {
  F("lowerRangeLimit", lower_range_limit, "rad", Range(-3.1416, 3.1416),
    "Lower hinge limit");
  F("upperRangeLimit", upper_range_limit, "rad", Range(-3.1416, 3.1416),
    "Upper hinge limit");
  F("Kp", kp, "1/s", NonNegative(), "Position servo gain");
  F("velocity_gain", velocity_gain, "N m s/rad", Positive(),
    "Velocity loop gain");
  F("max_vel", max_vel, "rad/s", Positive(), "Speed limit");
  F("max_torque", max_torque, "N m", Positive(), "Stall torque");
  return {REF(lower_range_limit), REF(upper_range_limit), REF(kp),
          REF(velocity_gain),     REF(max_vel),           REF(max_torque)};
}
std::vector<FieldRef> FieldsOf(SensorModule& p) {
  F("size", size, "m", Positive(), "Full extents of the box");
  F("mass", mass, "kg", Positive(), "Mass");
  F("materialName", material_name, "", NonEmpty(), "Contact material");
  return {REF(size), REF(mass), REF(material_name)};
}
std::vector<FieldRef> FieldsOf(ForceSensor& p) {
  F("sensorPosition", sensor_position, "",
    Range(0, 3, "0 bottom, 1 left, 2 top, 3 right"), "Face the plate is on");
  F("mass", mass, "kg", Positive(), "Plate mass");
  return {REF(sensor_position), REF(mass)};
}
std::vector<FieldRef> FieldsOf(DistanceSensor& p) {
  F("sensorPosition", sensor_position, "",
    Range(0, 5, "0 bottom, 1 left, 2 top, 3 right, 4 front, 5 back"),
    "Face the sensor is on");
  F("max_rayDistance", max_ray_distance, "m", Positive(), "Range");
  F("ray_Direction", ray_direction, "", Any(), "Ray direction");
  return {REF(sensor_position), REF(max_ray_distance), REF(ray_direction)};
}
std::vector<FieldRef> FieldsOf(Scene& p) {
  F("height_Image", height_image, "", Any(), "Grey-scale height image");
  F("position", position, "m", Any(), "Terrain corner");
  F("materialName", material_name, "", NonEmpty(), "Ground material");
  F("height", height, "m", NonNegative(), "Height of the brightest pixel");
  F("meters_per_pixel", meters_per_pixel, "m", Positive(), "Pixel size");
  return {REF(height_image), REF(position), REF(material_name), REF(height),
          REF(meters_per_pixel)};
}
std::vector<FieldRef> FieldsOf(SceneObject& p) {
  F("size", size, "m", Positive(), "Extents (Sphere: x is the diameter)");
  F("position", position, "m", Any(), "Centre");
  F("rotation", rotation, "deg", Any(), "Euler angles");
  F("materialName", material_name, "", NonEmpty(), "Contact material");
  F("shape", shape, "", Any(), "Primitive");
  F("mass", mass, "kg", Positive(), "Mass");
  F("isStatic", is_static, "", Any(), "Fixed in the world");
  return {REF(size),  REF(position), REF(rotation), REF(material_name),
          REF(shape), REF(mass),     REF(is_static)};
}
std::vector<FieldRef> FieldsOf(ContactFriction& p) {
  F("material1", material1, "", NonEmpty(), "First material");
  F("material2", material2, "", NonEmpty(), "Second material");
  F("restitution", restitution, "", Range(0, 1), "Bounciness");
  F("friction", friction, "", NonNegative(), "Coulomb friction");
  F("youngsModulus", youngs_modulus, "Pa", Positive(), "Stiffness");
  return {REF(material1), REF(material2), REF(restitution), REF(friction),
          REF(youngs_modulus)};
}
std::vector<FieldRef> FieldsOf(FluidRegion& p) {
  F("kind", kind, "", Any(), "Water or Air");
  F("position", position, "m", Any(), "Centre");
  F("size", size, "m", Positive(), "Full extents");
  F("density", density, "kg/m^3", Positive(), "Density");
  F("viscosity", viscosity, "Pa s", NonNegative(), "Viscosity");
  F("velocity", velocity, "m/s", Any(), "Flow or wind");
  return {REF(kind),    REF(position),  REF(size),
          REF(density), REF(viscosity), REF(velocity)};
}
std::vector<FieldRef> FieldsOf(SimulationSettings& p) {
  F("timestep", timestep, "s", Positive(), "Physics step");
  F("gravity", gravity, "m/s^2", Any(), "Gravity");
  return {REF(timestep), REF(gravity)};
}
#undef F
#undef REF

void ValidateScenario(const Scenario& scenario) {
  ReadScenarioString(WriteScenarioString(scenario), "design",
                     scenario.base_dir.empty() ? "." : scenario.base_dir);
}

}  // namespace mrsim

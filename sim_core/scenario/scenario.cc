#include "sim_core/scenario/scenario.h"

#include <type_traits>
#include <variant>

#include "sim_core/scenario/scenario_schema_inl.h"

namespace mrsim {

std::string RobotName(const Scenario& scenario, int robot) {
  const std::string& name = scenario.robots.at(robot).name;
  return name.empty() ? "robot" + std::to_string(robot) : name;
}

const char* ToString(Axis axis) {
  return axis == Axis::kPitch ? "Pitch" : "Yaw";
}

const char* ToString(JointType type) {
  return type == JointType::kHinge ? "Hinge" : "Lock";
}

const char* ToString(PrimitiveShape shape) {
  switch (shape) {
    case PrimitiveShape::kBox:
      return "Box";
    case PrimitiveShape::kSphere:
      return "Sphere";
    case PrimitiveShape::kCylinder:
      return "Cylinder";
    case PrimitiveShape::kCapsule:
      return "Capsule";
  }
  return "Box";
}

const char* ToString(FluidKind kind) {
  return kind == FluidKind::kWater ? "Water" : "Air";
}

const char* ToString(FrameConvention frame) {
  return frame == FrameConvention::kZUp ? "z-up" : "unity-y-up";
}

}  // namespace mrsim

namespace mrsim {
namespace {

// Walks one part through the schema and keeps, in schema order, a pointer
// to each field and an equality test of each child: two parts are equal
// when their lists are.
class EqualityItems {
 public:
  struct ChildRef {
    const void* part;
    bool (*equal)(const void*, const void*);
  };

  template <typename T>
  void Field(const FieldInfo&, T& member) {
    fields.emplace_back(&member);
  }
  template <typename P>
  void Child(const ChildInfo&, P& part) {
    children.push_back({&part, &Equal<P>});
  }
  template <typename P>
  void Optional(const ChildInfo&, std::optional<P>& part) {
    children.push_back({&part, &Equal<std::optional<P>>});
  }
  template <typename P, size_t N>
  void Array(const ChildInfo&, std::array<P, N>& parts) {
    children.push_back({&parts, &Equal<std::array<P, N>>});
  }
  template <typename P>
  void List(const ChildInfo&, std::vector<P>& parts) {
    children.push_back({&parts, &Equal<std::vector<P>>});
  }
  void Unsupported(const ChildInfo&) {}

  std::vector<FieldPtr> fields;
  std::vector<ChildRef> children;

 private:
  template <typename P>
  static bool Equal(const void* a, const void* b) {
    return *static_cast<const P*>(a) == *static_cast<const P*>(b);
  }
};

bool FieldEqual(const FieldPtr& a, const FieldPtr& b) {
  if (a.index() != b.index()) return false;
  return std::visit(
      [&b](auto* pa) {
        using T = std::remove_pointer_t<decltype(pa)>;
        const T& vb = *std::get<T*>(b);
        if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
          return pa->coeffs() == vb.coeffs();
        } else {
          return *pa == vb;
        }
      },
      a);
}

template <typename P>
bool SchemaEqual(const P& a, const P& b) {
  // Describe takes a mutable part to serve readers too; nothing is written.
  EqualityItems ia;
  EqualityItems ib;
  schema::Describe(ia, const_cast<P&>(a));
  schema::Describe(ib, const_cast<P&>(b));
  for (size_t i = 0; i < ia.fields.size(); ++i) {
    if (!FieldEqual(ia.fields[i], ib.fields[i])) return false;
  }
  for (size_t i = 0; i < ia.children.size(); ++i) {
    if (!ia.children[i].equal(ia.children[i].part, ib.children[i].part)) {
      return false;
    }
  }
  return true;
}

}  // namespace

#define MRSIM_SCHEMA_EQUAL(Type) \
  bool operator==(const Type& a, const Type& b) { return SchemaEqual(a, b); }
MRSIM_SCHEMA_EQUAL(Frame)
MRSIM_SCHEMA_EQUAL(Joint)
MRSIM_SCHEMA_EQUAL(Module)
MRSIM_SCHEMA_EQUAL(ForceSensor)
MRSIM_SCHEMA_EQUAL(DistanceSensor)
MRSIM_SCHEMA_EQUAL(Imu)
MRSIM_SCHEMA_EQUAL(Camera)
MRSIM_SCHEMA_EQUAL(SensorModule)
MRSIM_SCHEMA_EQUAL(Robot)
MRSIM_SCHEMA_EQUAL(Scene)
MRSIM_SCHEMA_EQUAL(SceneObject)
MRSIM_SCHEMA_EQUAL(ContactFriction)
MRSIM_SCHEMA_EQUAL(FluidRegion)
MRSIM_SCHEMA_EQUAL(SimulationSettings)
MRSIM_SCHEMA_EQUAL(RunSettings)
MRSIM_SCHEMA_EQUAL(OptimizationSettings)
MRSIM_SCHEMA_EQUAL(Scenario)
#undef MRSIM_SCHEMA_EQUAL

void ConvertUnityToZUp(Scenario* scenario) {
  schema::GeometryMap m;
  m.swap_yz = true;
  schema::Describe(m, *scenario);
}

// Swapping y and z is its own inverse.
void ConvertZUpToUnity(Scenario* scenario) { ConvertUnityToZUp(scenario); }

void ScaleLengths(Scenario* scenario, double factor) {
  schema::GeometryMap m;
  m.scale = factor;
  schema::Describe(m, *scenario);
}

}  // namespace mrsim

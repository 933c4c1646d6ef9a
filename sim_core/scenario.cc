#include "sim_core/scenario.h"

namespace mrsim {

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

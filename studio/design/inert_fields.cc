#include "studio/design/inert_fields.h"

#include <algorithm>

namespace mrsim::studio {

std::vector<FieldRef> WithoutInert(std::vector<FieldRef> fields,
                                   const std::vector<std::string>& inert) {
  fields.erase(std::remove_if(fields.begin(), fields.end(),
                              [&](const FieldRef& f) {
                                for (const std::string& name : inert) {
                                  if (name == f.info().xml) {
                                    return true;
                                  }
                                }
                                return false;
                              }),
               fields.end());
  return fields;
}

std::vector<FieldRef> JointFields(Joint& joint, JointPlace place) {
  static const std::vector<std::string> kServo = {"Kp", "max_vel",
                                                  "velocityGain", "maxTorque"};
  static const std::vector<std::string> kHinge = {
      "lowerRangeLimit", "upperRangeLimit", "Kp",
      "max_vel",         "velocityGain",    "maxTorque"};
  std::vector<std::string> inert;
  switch (place) {
    case JointPlace::kModule:
      // Its servo is always on: the switch would do nothing.
      inert = {"type", "breakForce", "servo"};
      break;
    case JointPlace::kRobotLock:
      inert = kHinge;
      inert.push_back("type");
      inert.push_back("servo");
      break;
    case JointPlace::kLoose:
      if (joint.type == JointType::kLock) {
        inert = kHinge;
        inert.push_back("servo");
      } else {
        // A loose hinge turns freely unless its servo is on; the gains
        // mean something only then.
        if (!joint.servo) inert = kServo;
        inert.push_back("breakForce");
      }
      break;
  }
  return WithoutInert(FieldsOf(joint), inert);
}

std::vector<FieldRef> TerrainFields(Scene& scene) {
  if (!scene.height_image.empty()) return FieldsOf(scene);
  return WithoutInert(FieldsOf(scene), {"height", "metersPerPixel"});
}

std::vector<SizeComponent> SizeComponents(PrimitiveShape shape) {
  switch (shape) {
    case PrimitiveShape::kSphere:
      return {{0, "diameter"}};
    case PrimitiveShape::kCylinder:
    case PrimitiveShape::kCapsule:
      return {{0, "diameter"}, {2, "length"}};
    case PrimitiveShape::kBox:
      break;
  }
  return {{0, "x"}, {1, "y"}, {2, "z"}};
}

Eigen::Vector3d SizeFor(PrimitiveShape shape, const Eigen::Vector3d& size) {
  Eigen::Vector3d out = size;
  switch (shape) {
    case PrimitiveShape::kSphere:
      out = Eigen::Vector3d::Constant(size.x());
      break;
    case PrimitiveShape::kCylinder:
    case PrimitiveShape::kCapsule:
      out.y() = size.x();
      break;
    case PrimitiveShape::kBox:
      break;
  }
  return out;
}

std::vector<FieldRef> WithoutUnused(std::vector<FieldRef> fields) {
  auto is_true = [&](const std::string& xml) {
    for (const FieldRef& f : fields) {
      if (xml == f.info().xml) return f.GetText() == "true";
    }
    return false;
  };
  std::vector<FieldRef> kept;
  for (const FieldRef& f : fields) {
    const char* when = f.info().shown_when;
    if (when != nullptr) {
      const bool negated = when[0] == '!';
      if (is_true(negated ? when + 1 : when) == negated) continue;
    }
    kept.push_back(f);
  }
  return kept;
}

}  // namespace mrsim::studio

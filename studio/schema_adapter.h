// TEMPORARY ADAPTER, to be deleted when the scenario schema (branch `schema`,
// sim_core/scenario_schema.h) is merged: the same API (FieldInfo, FieldRef,
// FieldsOf) over the fields the studio's inspector shows, so the inspector
// code does not change when the real table replaces this one.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "sim_core/scenario.h"

namespace mrsim {

enum class FieldType {
  kText,
  kNumber,
  kInteger,
  kBool,
  kVector,
  kQuaternion,
  kChoice
};

struct FieldLimits {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool nonzero = false;
  bool nonempty = false;
  const char* meaning = "";
};

struct FieldInfo {
  const char* xml;
  const char* member;
  const char* unit;
  FieldLimits limits;
  const char* help;
};

using FieldPtr = std::variant<std::string*, double*, int*, bool*,
                              Eigen::Vector3d*, Eigen::Quaterniond*, Axis*,
                              JointType*, PrimitiveShape*, FluidKind*>;

class FieldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FieldRef {
 public:
  FieldRef(const FieldInfo& info, FieldPtr value)
      : info_(&info), value_(value) {}
  const FieldInfo& info() const { return *info_; }
  FieldType type() const;
  std::vector<std::string> choices() const;
  std::string GetText() const;
  void SetText(const std::string& text) const;
  std::string Check() const;
  const FieldPtr& value() const { return value_; }

 private:
  const FieldInfo* info_;
  FieldPtr value_;
};

std::vector<FieldRef> FieldsOf(Module& part);
std::vector<FieldRef> FieldsOf(Frame& part);
std::vector<FieldRef> FieldsOf(Joint& part);
std::vector<FieldRef> FieldsOf(SensorModule& part);
std::vector<FieldRef> FieldsOf(ForceSensor& part);
std::vector<FieldRef> FieldsOf(DistanceSensor& part);
std::vector<FieldRef> FieldsOf(Scene& part);
std::vector<FieldRef> FieldsOf(SceneObject& part);
std::vector<FieldRef> FieldsOf(ContactFriction& part);
std::vector<FieldRef> FieldsOf(FluidRegion& part);
std::vector<FieldRef> FieldsOf(SimulationSettings& part);
std::vector<FieldRef> FieldsOf(Robot& part);

// Stand-in for the schema branch's ValidateScenario: the file reader's
// checks, through a write/read round trip. Throws ScenarioError.
void ValidateScenario(const Scenario& scenario);

}  // namespace mrsim

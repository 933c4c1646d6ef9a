// mrsim.Gait's C++ side: a gait definition plus the GaitController that
// runs it, advanced by sim time exactly as mrsim-gait answers states (the
// first call advances by 0, each later one by the time since the last; a
// time going back starts again from rest), so a Python controller using it
// reproduces mrsim-gait's trajectory.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/gait_controller.h"
#include "gait_controller/motion.h"
#include "gait_controller/process/joint_axes_spec.h"
#include "sim_core/scenario/scenario.h"

namespace mrsim::python {

class GaitObject {
 public:
  // Throws std::invalid_argument on bad parameters.
  explicit GaitObject(Gait gait);

  const Gait& gait() const { return gait_; }
  // The hinge axes to use (JointAxesSpec: "pitch-yaw", "PYPYP", ...);
  // unset: those known from the state, else alternating pitch-yaw (what
  // mrsim-gait assumes without --scenario or --axes).
  void set_axes(const std::string& spec) { axes_.emplace(spec); }
  bool has_axes() const { return axes_.has_value(); }
  // The axes of a chain of joint_count hinges whose axes may be `known`.
  std::vector<Axis> AxesFor(int joint_count,
                            const std::vector<Axis>& known) const;

  void SetMotion(Motion motion, double strength);
  void SetDirection(double forward, double turn);
  void SetParameters(const GaitParameters& parameters);

  // The targets at sim time t for a chain whose axes are `axes` (used when
  // the controller is built: on the first call or after Reset). Throws
  // std::invalid_argument on a bad time or a joint count that changed.
  const std::vector<double>& TargetsAt(double t, const std::vector<Axis>& axes);
  // Back to rest; the next call starts the gait afresh.
  void Reset();

  // Null until the first TargetsAt.
  const GaitController* controller() const { return controller_.get(); }

 private:
  Gait gait_;
  std::optional<JointAxesSpec> axes_;
  std::optional<std::pair<Motion, double>> motion_;
  std::optional<std::pair<double, double>> direction_;
  std::unique_ptr<GaitController> controller_;
  bool have_last_ = false;
  double last_time_ = 0;
};

}  // namespace mrsim::python

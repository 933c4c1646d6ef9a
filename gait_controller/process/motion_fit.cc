#include "gait_controller/process/motion_fit.h"

#include <algorithm>

namespace mrsim {

std::string MotionFitWarning(Motion motion, const std::vector<Axis>& axes) {
  const bool pitch =
      std::find(axes.begin(), axes.end(), Axis::kPitch) != axes.end();
  const bool yaw =
      std::find(axes.begin(), axes.end(), Axis::kYaw) != axes.end();
  const std::string name = ToString(motion);
  const std::string hint =
      "; use a pitch-yaw robot such as scenarios/case_study.xml";
  switch (motion) {
    case Motion::kForward:
    case Motion::kBackward:
      if (!pitch) {
        return name +
               " has no effect: the robot has no pitch joints (the linear "
               "gait is a pitch wave)" +
               hint;
      }
      return "";
    case Motion::kTurnLeft:
    case Motion::kTurnRight:
      if (!yaw) {
        return name +
               " cannot turn this robot: it has no yaw joints (a turn is a "
               "yaw offset), it only crawls straight" +
               hint;
      }
      return "";
    case Motion::kSidewindLeft:
    case Motion::kSidewindRight:
    case Motion::kRoll:
      if (!pitch || !yaw) {
        return name + " needs pitch and yaw joints; this robot has only " +
               (pitch ? "pitch" : "yaw") + " joints" + hint;
      }
      return "";
    case Motion::kStop:
      return "";
  }
  return "";
}

}  // namespace mrsim

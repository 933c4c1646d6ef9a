// The seven numbers of a sinusoid gait (domain.md section 4), plus the
// pitch-to-yaw lag and optional per-joint overrides. The seven are also the
// optimiser's genome: ToVector/FromVector keep the documented order.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Replaces the group's value for one joint (chain index among the hinges).
// phase replaces that joint's whole phase shift (k * phi_g [+ lag]).
struct JointOverride {
  int joint = 0;
  std::optional<double> amplitude;  // rad
  std::optional<double> phase;      // rad
  std::optional<double> offset;     // rad
};

// theta_i(t) = A_g sin(2 pi t / T + k_i phi_g [+ lag if yaw]) + o_g, with g
// the joint's group (pitch or yaw) and k_i its index within the group.
struct GaitParameters {
  static constexpr int kVectorSize = 7;

  double amplitude_pitch = 0.0;  // A_pitch, rad
  double amplitude_yaw = 0.0;    // A_yaw, rad
  double phase_pitch = 0.0;   // phi_pitch, rad between consecutive pitch joints
  double phase_yaw = 0.0;     // phi_yaw, rad between consecutive yaw joints
  double period = 4.0;        // T, s
  double offset_pitch = 0.0;  // o_pitch, rad
  double offset_yaw = 0.0;    // o_yaw, rad
  // Extra phase of every yaw joint (phi_py of the 5-module pitch-yaw form).
  double pitch_yaw_lag = 0.0;
  // Linear change of every amplitude along the body (conical sidewinding,
  // docs/gait.md): joint i of N gets A_g * (1 + taper * u_i), u_i running
  // from +1 at the head (joint 0) to -1 at the tail; 0: no change.
  double amplitude_taper = 0.0;
  std::vector<JointOverride> overrides;

  // [A_pitch, A_yaw, phi_pitch, phi_yaw, T, offset_pitch, offset_yaw].
  std::array<double, kVectorSize> ToArray() const;
  std::vector<double> ToVector() const;
  // The seven values in that order; lag 0 and no overrides. Throws
  // std::invalid_argument when the size is not 7 (values are not checked:
  // use ValidateGaitParameters).
  static GaitParameters FromVector(const std::vector<double>& values);
  // Keeps this gait's lag, taper and overrides, replaces the seven.
  GaitParameters WithVector(const std::vector<double>& values) const;
};

bool operator==(const JointOverride& a, const JointOverride& b);
bool operator==(const GaitParameters& a, const GaitParameters& b);
inline bool operator!=(const GaitParameters& a, const GaitParameters& b) {
  return !(a == b);
}

// Names of the seven values in vector order: "A_pitch", "A_yaw",
// "phi_pitch", "phi_yaw", "T", "offset_pitch", "offset_yaw".
const std::array<const char*, GaitParameters::kVectorSize>&
GaitParameterNames();

// Accepted ranges (checked by ValidateGaitParameters).
inline constexpr double kMaxGaitAmplitude = 3.14159265358979323846;  // rad
inline constexpr double kMaxGaitPhase = 2 * 3.14159265358979323846;  // |phi|
inline constexpr double kMinGaitPeriod = 0.1;                        // s
inline constexpr double kMaxGaitPeriod = 60.0;                       // s
inline constexpr double kMaxGaitOffset = 3.14159265358979323846;     // |o|
inline constexpr double kMaxGaitTaper = 1.0;  // |amplitude_taper|

// Throws std::invalid_argument naming the field and the accepted range when
// a value is not finite or out of range, or an override names a joint
// outside [0, joint_count) (joint_count < 0: not checked).
void ValidateGaitParameters(const GaitParameters& parameters,
                            int joint_count = -1);

// One joint's sinusoid: target = amplitude * sin(phase + shift) + offset.
struct JointWave {
  double amplitude = 0.0;
  double shift = 0.0;
  double offset = 0.0;
};

// Per-joint waves of a chain whose hinge axes are `axes` (chain order):
// group index k counts the joints of the same axis before this one; yaw
// joints add the lag; overrides replace the group values.
std::vector<JointWave> JointWaves(const GaitParameters& parameters,
                                  const std::vector<Axis>& axes);

}  // namespace mrsim

// The settings of a central pattern generator (docs/gait.md, "CPG
// gaits"): how strongly neighbouring oscillators pull each other to the
// designed phase lags, how fast amplitudes, offsets and frequency follow
// their goals, and how much the robot's sensors bend the rhythm. A gait
// that carries them runs on coupled oscillators instead of one sinusoid.
#pragma once

namespace mrsim {

struct CpgParameters {
  // w (rad/s): each oscillator's pull towards its neighbours' phase minus
  // the designed lag. Larger: faster convergence, stiffer rhythm.
  double coupling = 4.0;
  // a (1/s): gain of the critically damped second-order dynamics that
  // amplitudes, offsets and the frequency follow (Ijspeert 2007's
  // amplitude equation); the settling time is about 8 / a.
  double convergence = 10.0;
  // sigma (rad/s): feedback gain; theta_i' gets -sigma s_i cos(theta_i),
  // s_i in [0, 1] the sensor input of joint i (0: open loop).
  double feedback_gain = 0.0;
  // N: a force sensor reading of this much (or more) is input 1.
  double force_scale = 1.0;
  // m: a distance sensor reading d gives input max(0, 1 - d / range).
  double distance_range = 0.3;
};

bool operator==(const CpgParameters& a, const CpgParameters& b);
inline bool operator!=(const CpgParameters& a, const CpgParameters& b) {
  return !(a == b);
}

// Accepted ranges (ValidateCpgParameters).
inline constexpr double kMaxCpgCoupling = 100.0;     // rad/s
inline constexpr double kMinCpgConvergence = 0.1;    // 1/s
inline constexpr double kMaxCpgConvergence = 100.0;  // 1/s
inline constexpr double kMaxCpgFeedbackGain = 100.0;

// Throws std::invalid_argument naming the field ("cpg coupling: ...") and
// the accepted range: coupling in [0, 100], convergence in [0.1, 100],
// feedback_gain in [-100, 100], force_scale and distance_range > 0, all
// finite.
void ValidateCpgParameters(const CpgParameters& parameters);

}  // namespace mrsim

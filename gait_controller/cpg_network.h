// A chain of coupled phase oscillators, one per joint (Ijspeert et al.,
// Science 2007, with nearest-neighbour coupling), plus sensory feedback
// into each phase (Owaki et al. 2013's "Tegotae" term). Plain numbers in,
// joint targets out; the gait controller runs one for a CPG gait. The
// equations are in docs/gait.md ("CPG gaits"):
//
//   theta_i' = 2 pi nu + w sum_{j = i +- 1} sin(theta_j - theta_i - phi_ij)
//              - sigma s_i cos(theta_i)
//   r_i''    = a (a/4 (R_i - r_i) - r_i')     (the same for o_i and nu)
//   x_i      = r_i sin(theta_i) + o_i
//
// with phi_ij = psi_j - psi_i the designed lag (psi: the sine gait's
// per-joint phase shift), R_i, O_i the goal amplitude and offset, and nu's
// goal the drive over the period. Amplitude, offset and frequency are
// second-order, so a jump of any goal leaves x and x' continuous.
#pragma once

#include <vector>

#include "gait_controller/cpg_parameters.h"
#include "gait_controller/gait_parameters.h"

namespace mrsim {

class CpgNetwork {
 public:
  // joints >= 1; starts at rest: phases 0, amplitudes, offsets and
  // frequency 0 and still.
  explicit CpgNetwork(int joints);

  // Puts the oscillators at these phases, amplitudes and offsets, still
  // (derivatives 0), at frequency nu (Hz): how the controller hands over
  // from a sinusoid without a jump. Sizes must match joints().
  void Seed(const std::vector<double>& phases,
            const std::vector<JointWave>& waves, double frequency);
  // Replaces the phases only (tests start from random ones). Throws
  // std::invalid_argument on a wrong size or a non-finite value.
  void SetPhases(const std::vector<double>& phases);

  // Integrates dt seconds (sub-steps of at most 1 ms) towards the goal
  // waves (amplitude R_i, shift psi_i, offset O_i) at goal frequency
  // `frequency` (Hz, signed: negative runs the waves backwards), with
  // sensor inputs `feedback` (one per joint, clamped to [0, 1]; empty: all
  // 0). Throws std::invalid_argument on wrong sizes or a bad dt.
  void Step(double dt, const std::vector<JointWave>& goal, double frequency,
            const CpgParameters& parameters,
            const std::vector<double>& feedback = {});

  int joints() const { return static_cast<int>(theta_.size()); }
  // x_i, rad.
  double output(int joint) const;
  // dx_i/dt, rad/s (analytic, from the current state).
  double output_rate(int joint) const;
  // theta_i in [0, 2 pi).
  const std::vector<double>& phases() const { return theta_; }
  const std::vector<double>& amplitudes() const { return r_; }
  const std::vector<double>& offsets() const { return o_; }
  double frequency() const { return nu_; }

  // The state as numbers (phase, amplitude, its rate, offset, its rate,
  // phase speed per joint, then frequency and its rate), for SaveState;
  // FromNumbers throws std::invalid_argument on a wrong count.
  std::vector<double> ToNumbers() const;
  void FromNumbers(const std::vector<double>& numbers);

 private:
  std::vector<double> theta_, r_, dr_, o_, do_;
  double nu_ = 0.0;
  double dnu_ = 0.0;
  std::vector<double> dtheta_;  // scratch, reused
};

}  // namespace mrsim

#include "gait_controller/cpg_network.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrsim {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;
// Sub-step: a = 100 (the largest convergence) has poles at -50/s; 1 ms
// keeps semi-implicit Euler well inside its stable region.
constexpr double kMaxSubstep = 0.001;

void CheckSize(const char* what, size_t got, size_t expected) {
  if (got != expected) {
    throw std::invalid_argument(fmt::format(
        "cpg network: {} has {} values, expected {}", what, got, expected));
  }
}

}  // namespace

CpgNetwork::CpgNetwork(int joints) {
  if (joints < 1) {
    throw std::invalid_argument("cpg network: needs at least one joint");
  }
  const size_t n = static_cast<size_t>(joints);
  theta_.assign(n, 0.0);
  r_.assign(n, 0.0);
  dr_.assign(n, 0.0);
  o_.assign(n, 0.0);
  do_.assign(n, 0.0);
  dtheta_.assign(n, 0.0);
}

void CpgNetwork::Seed(const std::vector<double>& phases,
                      const std::vector<JointWave>& waves, double frequency) {
  CheckSize("phases", phases.size(), theta_.size());
  CheckSize("waves", waves.size(), theta_.size());
  SetPhases(phases);
  for (size_t i = 0; i < waves.size(); ++i) {
    r_[i] = waves[i].amplitude;
    o_[i] = waves[i].offset;
    dr_[i] = 0;
    do_[i] = 0;
  }
  nu_ = frequency;
  dnu_ = 0;
}

void CpgNetwork::SetPhases(const std::vector<double>& phases) {
  CheckSize("phases", phases.size(), theta_.size());
  for (size_t i = 0; i < phases.size(); ++i) {
    if (!std::isfinite(phases[i])) {
      throw std::invalid_argument("cpg network: phase not finite");
    }
    theta_[i] = std::fmod(phases[i], kTwoPi);
    if (theta_[i] < 0) theta_[i] += kTwoPi;
  }
}

void CpgNetwork::Step(double dt, const std::vector<JointWave>& goal,
                      double frequency, const CpgParameters& p,
                      const std::vector<double>& feedback) {
  if (!std::isfinite(dt) || dt < 0) {
    throw std::invalid_argument(fmt::format(
        "cpg network: time step must be finite and >= 0, got {}", dt));
  }
  const size_t n = theta_.size();
  CheckSize("goal", goal.size(), n);
  if (!feedback.empty()) CheckSize("feedback", feedback.size(), n);
  if (dt == 0) return;
  const int substeps = static_cast<int>(std::ceil(dt / kMaxSubstep));
  const double h = dt / substeps;
  const double a = p.convergence;
  for (int s = 0; s < substeps; ++s) {
    // Frequency, amplitudes and offsets: velocities first, then values
    // (semi-implicit Euler).
    dnu_ += h * a * (a / 4 * (frequency - nu_) - dnu_);
    nu_ += h * dnu_;
    for (size_t i = 0; i < n; ++i) {
      dr_[i] += h * a * (a / 4 * (goal[i].amplitude - r_[i]) - dr_[i]);
      r_[i] += h * dr_[i];
      do_[i] += h * a * (a / 4 * (goal[i].offset - o_[i]) - do_[i]);
      o_[i] += h * do_[i];
    }
    // Phases: all derivatives from the same state, then one update.
    for (size_t i = 0; i < n; ++i) {
      double d = kTwoPi * nu_;
      if (i > 0) {
        const double lag = goal[i - 1].shift - goal[i].shift;
        d += p.coupling * std::sin(theta_[i - 1] - theta_[i] - lag);
      }
      if (i + 1 < n) {
        const double lag = goal[i + 1].shift - goal[i].shift;
        d += p.coupling * std::sin(theta_[i + 1] - theta_[i] - lag);
      }
      if (!feedback.empty() && p.feedback_gain != 0) {
        const double s = std::clamp(feedback[i], 0.0, 1.0);
        d -= p.feedback_gain * s * std::cos(theta_[i]);
      }
      dtheta_[i] = d;
    }
    for (size_t i = 0; i < n; ++i) {
      theta_[i] = std::fmod(theta_[i] + h * dtheta_[i], kTwoPi);
      if (theta_[i] < 0) theta_[i] += kTwoPi;
    }
  }
  // Keep the last phase speeds for output_rate.
}

double CpgNetwork::output(int joint) const {
  const size_t i = static_cast<size_t>(joint);
  return r_.at(i) * std::sin(theta_[i]) + o_[i];
}

double CpgNetwork::output_rate(int joint) const {
  const size_t i = static_cast<size_t>(joint);
  return dr_.at(i) * std::sin(theta_[i]) +
         r_[i] * std::cos(theta_[i]) * dtheta_[i] + do_[i];
}

std::vector<double> CpgNetwork::ToNumbers() const {
  std::vector<double> v;
  v.reserve(theta_.size() * 6 + 2);
  for (size_t i = 0; i < theta_.size(); ++i) {
    v.insert(v.end(), {theta_[i], r_[i], dr_[i], o_[i], do_[i], dtheta_[i]});
  }
  v.push_back(nu_);
  v.push_back(dnu_);
  return v;
}

void CpgNetwork::FromNumbers(const std::vector<double>& v) {
  CheckSize("state", v.size(), theta_.size() * 6 + 2);
  for (size_t i = 0; i < theta_.size(); ++i) {
    const double* s = &v[i * 6];
    theta_[i] = s[0];
    r_[i] = s[1];
    dr_[i] = s[2];
    o_[i] = s[3];
    do_[i] = s[4];
    dtheta_[i] = s[5];
  }
  nu_ = v[v.size() - 2];
  dnu_ = v.back();
}

}  // namespace mrsim

#include "gait_controller/gait_parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrsim {

std::array<double, GaitParameters::kVectorSize> GaitParameters::ToArray()
    const {
  return {amplitude_pitch, amplitude_yaw, phase_pitch, phase_yaw,
          period,          offset_pitch,  offset_yaw};
}

std::vector<double> GaitParameters::ToVector() const {
  const auto a = ToArray();
  return std::vector<double>(a.begin(), a.end());
}

GaitParameters GaitParameters::FromVector(const std::vector<double>& values) {
  return GaitParameters().WithVector(values);
}

GaitParameters GaitParameters::WithVector(
    const std::vector<double>& values) const {
  if (values.size() != static_cast<size_t>(kVectorSize)) {
    throw std::invalid_argument(
        fmt::format("gait parameters: expected {} values (A_pitch, A_yaw, "
                    "phi_pitch, phi_yaw, T, offset_pitch, offset_yaw), got {}",
                    kVectorSize, values.size()));
  }
  GaitParameters p = *this;
  p.amplitude_pitch = values[0];
  p.amplitude_yaw = values[1];
  p.phase_pitch = values[2];
  p.phase_yaw = values[3];
  p.period = values[4];
  p.offset_pitch = values[5];
  p.offset_yaw = values[6];
  return p;
}

bool operator==(const JointOverride& a, const JointOverride& b) {
  return a.joint == b.joint && a.amplitude == b.amplitude &&
         a.phase == b.phase && a.offset == b.offset;
}

bool operator==(const GaitParameters& a, const GaitParameters& b) {
  return a.ToArray() == b.ToArray() && a.pitch_yaw_lag == b.pitch_yaw_lag &&
         a.amplitude_taper == b.amplitude_taper && a.overrides == b.overrides;
}

const std::array<const char*, GaitParameters::kVectorSize>&
GaitParameterNames() {
  static const std::array<const char*, GaitParameters::kVectorSize> kNames = {
      "A_pitch", "A_yaw",        "phi_pitch", "phi_yaw",
      "T",       "offset_pitch", "offset_yaw"};
  return kNames;
}

namespace {

void CheckRange(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw std::invalid_argument(
        fmt::format("gait parameter {}: expected a number in [{}, {}], got {}",
                    field, lo, hi, value));
  }
}

}  // namespace

void ValidateGaitParameters(const GaitParameters& p, int joint_count) {
  CheckRange("A_pitch", p.amplitude_pitch, 0.0, kMaxGaitAmplitude);
  CheckRange("A_yaw", p.amplitude_yaw, 0.0, kMaxGaitAmplitude);
  CheckRange("phi_pitch", p.phase_pitch, -kMaxGaitPhase, kMaxGaitPhase);
  CheckRange("phi_yaw", p.phase_yaw, -kMaxGaitPhase, kMaxGaitPhase);
  CheckRange("T", p.period, kMinGaitPeriod, kMaxGaitPeriod);
  CheckRange("offset_pitch", p.offset_pitch, -kMaxGaitOffset, kMaxGaitOffset);
  CheckRange("offset_yaw", p.offset_yaw, -kMaxGaitOffset, kMaxGaitOffset);
  CheckRange("pitch_yaw_lag", p.pitch_yaw_lag, -kMaxGaitPhase, kMaxGaitPhase);
  CheckRange("amplitude_taper", p.amplitude_taper, -kMaxGaitTaper,
             kMaxGaitTaper);
  for (size_t n = 0; n < p.overrides.size(); ++n) {
    const JointOverride& o = p.overrides[n];
    const std::string where =
        fmt::format("joint override {} (joint {})", n, o.joint);
    if (o.joint < 0 || (joint_count >= 0 && o.joint >= joint_count)) {
      throw std::invalid_argument(fmt::format(
          "gait parameter {}: joint index out of range [0, {})", where,
          joint_count >= 0 ? std::to_string(joint_count) : "joints"));
    }
    if (o.amplitude) {
      CheckRange(where + " amplitude", *o.amplitude, 0.0, kMaxGaitAmplitude);
    }
    if (o.phase) {
      CheckRange(where + " phase", *o.phase, -kMaxGaitPhase * 16,
                 kMaxGaitPhase * 16);
    }
    if (o.offset) {
      CheckRange(where + " offset", *o.offset, -kMaxGaitOffset, kMaxGaitOffset);
    }
  }
}

std::vector<JointWave> JointWaves(const GaitParameters& p,
                                  const std::vector<Axis>& axes) {
  std::vector<JointWave> waves(axes.size());
  int pitch_index = 0;
  int yaw_index = 0;
  for (size_t j = 0; j < axes.size(); ++j) {
    JointWave& w = waves[j];
    if (axes[j] == Axis::kPitch) {
      w.amplitude = p.amplitude_pitch;
      w.shift = pitch_index * p.phase_pitch;
      w.offset = p.offset_pitch;
      ++pitch_index;
    } else {
      w.amplitude = p.amplitude_yaw;
      w.shift = yaw_index * p.phase_yaw + p.pitch_yaw_lag;
      w.offset = p.offset_yaw;
      ++yaw_index;
    }
  }
  if (p.amplitude_taper != 0 && waves.size() > 1) {
    const double last = static_cast<double>(waves.size() - 1);
    for (size_t j = 0; j < waves.size(); ++j) {
      const double u = 1.0 - 2.0 * static_cast<double>(j) / last;
      waves[j].amplitude = std::min(
          kMaxGaitAmplitude,
          waves[j].amplitude * std::max(0.0, 1.0 + p.amplitude_taper * u));
    }
  }
  for (const JointOverride& o : p.overrides) {
    if (o.joint < 0 || o.joint >= static_cast<int>(waves.size())) continue;
    JointWave& w = waves[o.joint];
    if (o.amplitude) w.amplitude = *o.amplitude;
    if (o.phase) w.shift = *o.phase;
    if (o.offset) w.offset = *o.offset;
  }
  return waves;
}

}  // namespace mrsim

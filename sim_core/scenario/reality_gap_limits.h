// The reality gap's typical values and allowed maxima, in one place: the
// physics' RealityGap (sim_core/physics/reality_gap.h: Typical, Validate)
// and the design file's <optimization> gap fields (the schema's rows and
// their defaults) both take them from here, so a file can never hold a gap
// the physics refuses. Here because the scenario room is below physics.
// Every value's minimum is 0 (docs/physics.md, "The reality gap").
#pragma once

namespace mrsim {

// Per step.
inline constexpr double kGapTypicalSensorNoise = 0.05;  // share of reading
inline constexpr double kGapMaxSensorNoise = 1;
inline constexpr double kGapTypicalSensorBias = 0.05;  // share, whole run
inline constexpr double kGapMaxSensorBias = 0.99;
inline constexpr double kGapTypicalJointNoise = 0.01;  // rad
inline constexpr double kGapMaxJointNoise = 1;
inline constexpr double kGapTypicalMotorNoise = 0.1;  // rad/s
inline constexpr double kGapMaxMotorNoise = 100;
inline constexpr double kGapTypicalLatency = 0.02;  // s
inline constexpr double kGapMaxLatency = 1;
inline constexpr double kGapTypicalBacklash = 0.02;  // rad
inline constexpr double kGapMaxBacklash = 0.5;
inline constexpr double kGapTypicalMaxAccel = 100;  // rad/s^2; 0 none
inline constexpr double kGapMaxMaxAccel = 1e6;
// Per episode: each value x U(1 - r, 1 + r); r < 1 keeps a factor positive.
inline constexpr double kGapTypicalFrictionRange = 0.3;
inline constexpr double kGapTypicalMassRange = 0.1;
inline constexpr double kGapTypicalGainRange = 0.2;
inline constexpr double kGapTypicalTerrainRange = 0.2;
inline constexpr double kGapMaxRange = 0.99;

}  // namespace mrsim

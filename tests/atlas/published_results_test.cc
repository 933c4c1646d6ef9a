// Published results a rigid-body simulator of these robots should
// reproduce, each with its source. Only the qualitative claims are encoded:
// the papers' robots (servos, sizes, friction) are not this one, so their
// figures are not ours to match (docs/physics.md, "Gait atlas").
//
// [CLAWAR 2005] J. Gonzalez-Gomez, E. Boemo, "Motion of minimal
//   configurations of a modular robot: sinusoidal, lateral rolling and
//   lateral shift", Proc. 8th Int. Conf. on Climbing and Walking Robots
//   (CLAWAR 2005), London, 2005.
// [Hirose 1993] S. Hirose, Biologically Inspired Robots: Snake-Like
//   Locomotors and Manipulators, Oxford University Press, 1993.
#include <gtest/gtest.h>

#include <cmath>

#include "gait_controller/gait_atlas.h"
#include "gait_controller/gait_trial.h"

namespace mrsim {
namespace {

GaitOutcome RunLine(const std::string& line, double amplitude_scale = 1.0) {
  const AtlasEntry& e = FindAtlasEntry(line);
  return MeasureGait(ScaleAmplitudes(e.gait, amplitude_scale), e.trial);
}

// [CLAWAR 2005]: two pitch modules move in a straight line, forward or
// backward; the phase difference of their two sinusoids decides whether
// and which way. In phase the body only arches: it must not go anywhere.
TEST(PublishedResults, PitchPitchMovesOnlyWithAPhaseDifferenceItsSignTheWay) {
  const GaitOutcome in_phase = RunLine("pp-phase-0");
  const GaitOutcome forward = RunLine("pp-phase-110");
  const GaitOutcome backward = RunLine("pp-phase-minus-110");
  EXPECT_GT(forward.displacement.x(), 0.0);
  EXPECT_LT(backward.displacement.x(), 0.0);
  EXPECT_LT(in_phase.speed, 0.1 * forward.speed);
  EXPECT_LT(in_phase.speed, 0.1 * backward.speed);
  EXPECT_LT(std::abs(forward.drift), 0.1 * forward.speed);
}

// [CLAWAR 2005]: "the speed is controlled modifying the amplitude".
TEST(PublishedResults, PitchPitchGoesFasterWithALargerAmplitude) {
  EXPECT_GT(RunLine("pp-phase-110").speed, RunLine("pp-phase-110", 0.5).speed);
}

// [CLAWAR 2005]: pitch-yaw-pitch with its yaw joint at 0 moves like
// pitch-pitch, in a straight line, but covers less at the same amplitude
// (its pitch modules are further apart).
TEST(PublishedResults, PitchYawPitchWithItsYawStillGoesStraightLessFar) {
  const GaitOutcome pyp = RunLine("pyp-straight-110");
  EXPECT_GT(pyp.displacement.x(), 0.0);
  EXPECT_LT(std::abs(pyp.drift), 0.1 * pyp.speed);
  EXPECT_LT(pyp.speed, RunLine("pp-phase-110").speed);
}

// [CLAWAR 2005]: with equal waves, lateral shift and lateral rolling
// "differ only on the amplitude range": below 40 degrees the robot shifts
// sideways, from 60 degrees it rolls.
TEST(PublishedResults, PitchYawPitchShiftsSidewaysBelow40DegreesRollsFrom60) {
  const GaitOutcome shift = RunLine("pyp-lateral-shift-30");
  const GaitOutcome roll = RunLine("pyp-lateral-rolling-70");
  EXPECT_LT(std::abs(shift.roll_deg), 90.0);
  EXPECT_GT(std::abs(shift.drift), 0.7 * shift.speed) << "mostly sideways";
  EXPECT_GT(std::abs(roll.roll_deg), 360.0) << "at least one whole turn";
  EXPECT_GT(std::abs(roll.drift), 0.7 * roll.speed) << "mostly sideways";
}

// [Hirose 1993]: lateral undulation needs more friction across the body
// than along it; on passive wheels the serpenoid moves head first, on
// isotropic friction hardly at all.
TEST(PublishedResults, SerpenoidMovesHeadFirstOnWheelsAndHardlyWithout) {
  const GaitOutcome wheels = RunLine("serpenoid-wheels");
  const GaitOutcome plain = RunLine("serpenoid");
  EXPECT_GT(wheels.displacement.x(), 0.0);
  EXPECT_GT(wheels.speed, 4.0 * plain.speed);
}

}  // namespace
}  // namespace mrsim

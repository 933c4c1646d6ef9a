#include "gait_controller/gait_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "gait_controller/gait_presets.h"
#include "gait_controller/motion.h"

namespace mrsim {
namespace {

TEST(GaitParameters, VectorKeepsTheDocumentedOrder) {
  const std::vector<double> v = {1.1, 2.2, 3.3, 4.4, 5.5, 0.6, -0.7};
  const GaitParameters p = GaitParameters::FromVector(v);
  EXPECT_EQ(p.amplitude_pitch, 1.1);
  EXPECT_EQ(p.amplitude_yaw, 2.2);
  EXPECT_EQ(p.phase_pitch, 3.3);
  EXPECT_EQ(p.phase_yaw, 4.4);
  EXPECT_EQ(p.period, 5.5);
  EXPECT_EQ(p.offset_pitch, 0.6);
  EXPECT_EQ(p.offset_yaw, -0.7);
  EXPECT_EQ(p.ToVector(), v);
  const auto& names = GaitParameterNames();
  EXPECT_STREQ(names[0], "A_pitch");
  EXPECT_STREQ(names[4], "T");
  EXPECT_STREQ(names[6], "offset_yaw");
}

TEST(GaitParameters, FromVectorRejectsWrongSize) {
  EXPECT_THROW(GaitParameters::FromVector({1, 2, 3}), std::invalid_argument);
}

TEST(GaitParameters, WithVectorKeepsLagAndOverrides) {
  GaitParameters p;
  p.pitch_yaw_lag = 0.4;
  p.overrides.push_back({2, 0.1, std::nullopt, std::nullopt});
  const GaitParameters q = p.WithVector({1, 1, 1, 1, 2, 0, 0});
  EXPECT_EQ(q.pitch_yaw_lag, 0.4);
  EXPECT_EQ(q.overrides, p.overrides);
  EXPECT_EQ(q.period, 2);
}

TEST(GaitParameters, PresetsMatchTheDomainTable) {
  const auto& presets = GaitPresets();
  ASSERT_GE(presets.size(), 8u);
  EXPECT_EQ(presets[7].name, "sidewind");
  const std::vector<std::pair<std::string, std::vector<double>>> table = {
      {"forward", {1, 0, 2.5, 0, 4, 0, 0}},
      {"forward-strong", {2, 0, 2.5, 0, 4, 0, 0}},
      {"turn-wide", {0.5, 0, 2.5, 0, 4, 0, 0.3}},
      {"turn-sharp", {0.5, 0, 2.5, 0, 4, 0, 0.8}},
      {"sidewind-1", {0.5, 0.5, 2.5, 2.5, 4, 0, 0}},
      {"sidewind-2", {1, 1, 2, 2, 4, 0, 0}},
      {"rolling", {0.5, 0.5, 1, 0.5, 4, 0, 0}},
  };
  for (size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(presets[i].name, table[i].first);
    EXPECT_EQ(presets[i].parameters.ToVector(), table[i].second)
        << presets[i].name;
    EXPECT_NO_THROW(ValidateGaitParameters(presets[i].parameters));
  }
  EXPECT_EQ(FindGaitPreset("sidewind_2")->name, "sidewind-2");
  EXPECT_EQ(FindGaitPreset("sidewind-2")->kind, GaitKind::kSidewind);
  EXPECT_EQ(FindGaitPreset("rolling")->kind, GaitKind::kRoll);
  EXPECT_EQ(FindGaitPreset("turn-sharp")->kind, GaitKind::kLinear);
  EXPECT_FALSE(FindGaitPreset("moonwalk"));
}

TEST(GaitParameters, WavesStepThePhaseWithinEachGroup) {
  GaitParameters p =
      GaitParameters::FromVector({1, 0.5, 0.3, 0.7, 4, 0.1, -0.2});
  p.pitch_yaw_lag = 0.25;
  const std::vector<Axis> axes = {Axis::kPitch, Axis::kYaw, Axis::kPitch,
                                  Axis::kYaw, Axis::kPitch};
  const auto w = JointWaves(p, axes);
  ASSERT_EQ(w.size(), 5u);
  // The 5-module pitch-yaw form: pitch joints (i-1)*phi/2, yaw joints
  // (i-2)*phi/2 + phi_py with i counted from 1.
  EXPECT_DOUBLE_EQ(w[0].shift, 0.0);
  EXPECT_DOUBLE_EQ(w[2].shift, 0.3);
  EXPECT_DOUBLE_EQ(w[4].shift, 0.6);
  EXPECT_DOUBLE_EQ(w[1].shift, 0.25);
  EXPECT_DOUBLE_EQ(w[3].shift, 0.7 + 0.25);
  EXPECT_EQ(w[0].amplitude, 1);
  EXPECT_EQ(w[1].amplitude, 0.5);
  EXPECT_EQ(w[2].offset, 0.1);
  EXPECT_EQ(w[3].offset, -0.2);
}

TEST(GaitParameters, OverridesReplaceOneJoint) {
  GaitParameters p = GaitParameters::FromVector({1, 0, 2.5, 0, 4, 0, 0});
  p.overrides.push_back({1, 0.2, 3.0, 0.05});
  p.overrides.push_back({2, std::nullopt, std::nullopt, -0.1});
  const auto w = JointWaves(p, std::vector<Axis>(4, Axis::kPitch));
  EXPECT_EQ(w[1].amplitude, 0.2);
  EXPECT_EQ(w[1].shift, 3.0);
  EXPECT_EQ(w[1].offset, 0.05);
  EXPECT_EQ(w[2].amplitude, 1);
  EXPECT_DOUBLE_EQ(w[2].shift, 5.0);
  EXPECT_EQ(w[2].offset, -0.1);
  EXPECT_DOUBLE_EQ(w[3].shift, 7.5);
}

TEST(GaitParameters, ValidationNamesTheField) {
  auto message = [](const GaitParameters& p, int joints = -1) {
    try {
      ValidateGaitParameters(p, joints);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const GaitParameters p = FindGaitPreset("forward")->parameters;
  GaitParameters bad = p;
  bad.period = 0;
  EXPECT_NE(message(bad).find("T"), std::string::npos);
  bad = p;
  bad.amplitude_yaw = std::nan("");
  EXPECT_NE(message(bad).find("A_yaw"), std::string::npos);
  bad = p;
  bad.amplitude_pitch = -1;
  EXPECT_NE(message(bad).find("A_pitch"), std::string::npos);
  bad = p;
  bad.offset_pitch = 4;
  EXPECT_NE(message(bad).find("offset_pitch"), std::string::npos);
  bad = p;
  bad.overrides.push_back({11, 0.1, std::nullopt, std::nullopt});
  EXPECT_NE(message(bad, 11).find("joint 11"), std::string::npos);
  EXPECT_EQ(message(bad, 12), "no error");
}

TEST(GaitMotion, NamesRoundTrip) {
  for (Motion m : {Motion::kForward, Motion::kBackward, Motion::kTurnLeft,
                   Motion::kTurnRight, Motion::kSidewindLeft,
                   Motion::kSidewindRight, Motion::kRoll, Motion::kStop}) {
    EXPECT_EQ(ParseMotion(ToString(m)), m);
  }
  EXPECT_EQ(ParseMotion("turn_left"), Motion::kTurnLeft);
  EXPECT_FALSE(ParseMotion("jump"));
}

}  // namespace
}  // namespace mrsim

// The live view's distance rays: from the sensor's site where the state
// puts it, along the sensor's direction, as long as the reading.
#include "studio/ui/view/live_rays.h"

#include <gtest/gtest.h>

#include "sim_core/mjcf/mjcf_names.h"
#include "sim_core/physics/physics.h"
#include "tests/viewer/viewer_test_util.h"

namespace mrsim::studio {
namespace {

class StudioLiveRays : public ::testing::Test {
 protected:
  StudioLiveRays()
      : scenario_(mrsim::testing::ViewerTestScenario()),
        sim_(scenario_),
        view_(scenario_),
        mapper_(view_.model(), scenario_),
        site_(mj_name2id(view_.model(), mjOBJ_SITE,
                         mjcf_names::DistanceSite("snake", 0, 0).c_str())) {}

  // Poses the view from `state` and returns its rays.
  std::vector<Ray> Show(const RobotState* state) {
    mapper_.Apply({state}, view_.mutable_data());
    return MeasuredRays(mapper_, {state}, view_.data());
  }
  Eigen::Vector3d SitePosition() const {
    return Eigen::Vector3d(view_.data()->site_xpos + 3 * site_);
  }
  Eigen::Vector3d SiteAxis() const {
    const mjtNum* x = view_.data()->site_xmat + 9 * site_;
    return Eigen::Vector3d(x[0], x[3], x[6]);
  }

  Scenario scenario_;
  Physics sim_;   // the running simulation
  Physics view_;  // the studio's model, posed from states only
  StatePoseMapper mapper_;
  int site_;
};

// The design view draws each ray as far as the simulator would read it in
// the design's pose (it ran the full range past the ball).
TEST_F(StudioLiveRays, ADesignRayEndsWhereTheSimulatorWouldRead) {
  ASSERT_GE(site_, 0);
  mj_kinematics(view_.model(), view_.mutable_data());
  const double max = scenario_.robots[0]
                         .sensor_modules[0]
                         .distance_sensors[0]
                         .max_ray_distance;
  const Ray ray = CastSiteRay(view_.model(), view_.data(), site_, max);
  const double reading = sim_.ReadRobotState(0).sensor_modules[0].distances[0];
  ASSERT_LT(reading, max);  // the box is in front
  EXPECT_TRUE(ray.hit);
  EXPECT_NEAR((ray.to - ray.from).norm(), reading, 1e-9);
  EXPECT_TRUE(ray.from.isApprox(SitePosition()));
  // Nothing within a short range: the full length, no hit.
  const Ray short_ray = CastSiteRay(view_.model(), view_.data(), site_, 0.01);
  EXPECT_FALSE(short_ray.hit);
  EXPECT_NEAR((short_ray.to - short_ray.from).norm(), 0.01, 1e-12);
}

TEST_F(StudioLiveRays, AReadingGivesARayOfThatLengthFromItsSiteAlongIt) {
  ASSERT_GE(site_, 0);
  RobotState state = sim_.ReadRobotState(0);
  ASSERT_EQ(state.sensor_modules.size(), 1u);
  ASSERT_EQ(state.sensor_modules[0].distances.size(), 1u);
  const double max = scenario_.robots[0]
                         .sensor_modules[0]
                         .distance_sensors[0]
                         .max_ray_distance;
  // The box is in front: the simulator measured less than the maximum.
  const double measured = state.sensor_modules[0].distances[0];
  EXPECT_LT(measured, max);
  for (const double reading : {measured, 0.125}) {
    state.sensor_modules[0].distances[0] = reading;
    const std::vector<Ray> rays = Show(&state);
    ASSERT_EQ(rays.size(), 1u);
    EXPECT_TRUE(rays[0].hit);
    EXPECT_NEAR((rays[0].from - SitePosition()).norm(), 0, 1e-9);
    EXPECT_NEAR((rays[0].to - rays[0].from).norm(), reading, 1e-9);
    EXPECT_NEAR((rays[0].to - rays[0].from).normalized().dot(SiteAxis()), 1,
                1e-9);
  }
}

TEST_F(StudioLiveRays, NothingInRangeDrawsTheDesignedLengthAsAMiss) {
  RobotState state = sim_.ReadRobotState(0);
  const double max = scenario_.robots[0]
                         .sensor_modules[0]
                         .distance_sensors[0]
                         .max_ray_distance;
  state.sensor_modules[0].distances[0] = max;  // the simulator's "no hit"
  const std::vector<Ray> rays = Show(&state);
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_FALSE(rays[0].hit);
  EXPECT_NEAR((rays[0].to - rays[0].from).norm(), max, 1e-9);
}

TEST_F(StudioLiveRays, TheRayStartsWhereTheStatePutsTheSensor) {
  RobotState state = sim_.ReadRobotState(0);
  const Eigen::Vector3d designed = Show(&state)[0].from;
  // The whole robot one metre to the left.
  const Eigen::Vector3d shift(0, 1, 0);
  for (Pose& p : state.frames) p.position += shift;
  for (Pose& p : state.modules) p.position += shift;
  for (SensorModuleState& sm : state.sensor_modules) sm.pose.position += shift;
  const std::vector<Ray> rays = Show(&state);
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_NEAR((rays[0].from - (designed + shift)).norm(), 0, 1e-9);
  EXPECT_NEAR((rays[0].from - SitePosition()).norm(), 0, 1e-9);
}

TEST_F(StudioLiveRays, ARobotWithoutAStateHasNoMeasuredRays) {
  EXPECT_TRUE(Show(nullptr).empty());
}

}  // namespace
}  // namespace mrsim::studio

// Roll, pitch and yaw in degrees as the inspector shows them, and the
// quaternion the scenario keeps: one is the other.
#include "studio/design/euler_degrees.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mrsim::studio {
namespace {

// The same rotation: q and -q turn alike.
bool SameTurn(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::abs(std::abs(a.normalized().dot(b.normalized())) - 1) < 1e-12;
}

TEST(StudioEulerDegrees, NinetyInYawTurnsAboutZ) {
  const Eigen::Quaterniond q =
      QuaternionFromEulerDegrees(Eigen::Vector3d(0, 0, 90));
  EXPECT_NEAR(q.w(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.z(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(q.x(), 0, 1e-12);
  EXPECT_NEAR(q.y(), 0, 1e-12);
  // x turns to y.
  EXPECT_TRUE(
      (q * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
}

TEST(StudioEulerDegrees, AboutXThenYThenZ) {
  // Roll first: y turns to z, then pitch 90 turns z to x.
  const Eigen::Quaterniond q =
      QuaternionFromEulerDegrees(Eigen::Vector3d(90, 90, 0));
  EXPECT_TRUE(
      (q * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitX()));
}

TEST(StudioEulerDegrees, DegreesRoundTripThroughTheQuaternion) {
  for (double roll = -175; roll <= 180; roll += 35) {
    for (double pitch = -85; pitch <= 85; pitch += 17) {
      for (double yaw = -170; yaw <= 180; yaw += 34) {
        const Eigen::Vector3d rpy(roll, pitch, yaw);
        const Eigen::Vector3d back =
            EulerDegreesFromQuaternion(QuaternionFromEulerDegrees(rpy));
        EXPECT_LT((back - rpy).norm(), 1e-9)
            << rpy.transpose() << " came back " << back.transpose();
      }
    }
  }
}

TEST(StudioEulerDegrees, QuaternionsRoundTripThroughDegrees) {
  std::srand(7);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Quaterniond q(Eigen::Vector4d::Random());  // not unit
    const Eigen::Quaterniond back =
        QuaternionFromEulerDegrees(EulerDegreesFromQuaternion(q));
    EXPECT_TRUE(SameTurn(q, back)) << q.coeffs().transpose();
  }
  // Straight up: roll and yaw share one turn; the rotation survives.
  const Eigen::Quaterniond up =
      QuaternionFromEulerDegrees(Eigen::Vector3d(30, 90, 10));
  EXPECT_TRUE(
      SameTurn(up, QuaternionFromEulerDegrees(EulerDegreesFromQuaternion(up))));
}

TEST(StudioEulerDegrees, AFileWithoutARotationReadsAsNoTurn) {
  EXPECT_EQ(EulerDegreesFromQuaternion(Eigen::Quaterniond(0, 0, 0, 0)),
            Eigen::Vector3d::Zero());
  EXPECT_EQ(EulerDegreesFromQuaternion(Eigen::Quaterniond::Identity()),
            Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace mrsim::studio

#include "sim_core/mesh/box_union.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mrsim {
namespace {

using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;

OrientedBox Box(const Vector3d& center, const Vector3d& half,
                const Quaterniond& quat = Quaterniond::Identity()) {
  OrientedBox b;
  b.center = center;
  b.half = half;
  b.quat = quat;
  return b;
}

// Two 5 cm cubes of a snake, front to back along x.
const Vector3d kHalf(0.025, 0.025, 0.025);

TEST(FlushBoxUnion, TwoFramesFaceToFaceFillOneBox) {
  const auto u = FlushBoxUnion(Box({-0.025, 0, 0.027}, kHalf),
                               Box({-0.075, 0, 0.027}, kHalf));
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->center.isApprox(Vector3d(-0.05, 0, 0.027), 1e-12));
  EXPECT_TRUE(u->half.isApprox(Vector3d(0.05, 0.025, 0.025), 1e-12));
  // Either order gives the same box.
  const auto v = FlushBoxUnion(Box({-0.075, 0, 0.027}, kHalf),
                               Box({-0.025, 0, 0.027}, kHalf));
  ASSERT_TRUE(v);
  EXPECT_TRUE(v->center.isApprox(u->center, 1e-12));
  EXPECT_TRUE(v->half.isApprox(u->half, 1e-12));
}

TEST(FlushBoxUnion, UnequalLengthsAndTiltedPairsStillJoin) {
  // A 2 cm and a 6 cm long box in a chain turned 30 deg about z and
  // pitched 10 deg: the union spans both, in the first box's axes.
  const Quaterniond q = AngleAxisd(M_PI / 6, Vector3d::UnitZ()) *
                        AngleAxisd(0.17, Vector3d::UnitY());
  const Vector3d a_half(0.01, 0.02, 0.015), b_half(0.03, 0.02, 0.015);
  const Vector3d a_center(1, 2, 0.5);
  const Vector3d b_center = a_center + q * Vector3d(0.04, 0, 0);
  const auto u =
      FlushBoxUnion(Box(a_center, a_half, q), Box(b_center, b_half, q));
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->half.isApprox(Vector3d(0.04, 0.02, 0.015), 1e-12));
  EXPECT_TRUE(u->center.isApprox(a_center + q * Vector3d(0.03, 0, 0), 1e-12));
}

TEST(FlushBoxUnion, AQuarterTurnOfASquareSectionIsTheSameBox) {
  // A yaw module's frame turned 90 deg about the chain's axis.
  const Quaterniond quarter(AngleAxisd(M_PI / 2, Vector3d::UnitX()));
  const auto u = FlushBoxUnion(Box({0, 0, 0}, {0.02, 0.03, 0.03}),
                               Box({0.05, 0, 0}, {0.03, 0.03, 0.03}, quarter));
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->half.isApprox(Vector3d(0.05, 0.03, 0.03), 1e-12));
}

TEST(FlushBoxUnion, BoxesThatDoNotFillOneBoxStayApart) {
  const OrientedBox a = Box({0, 0, 0}, kHalf);
  // A gap of 1 mm, an overlap of 1 mm, offset sideways, another section,
  // turned 45 deg, and turned 90 deg where the section is not square.
  EXPECT_FALSE(FlushBoxUnion(a, Box({0.051, 0, 0}, kHalf)));
  EXPECT_FALSE(FlushBoxUnion(a, Box({0.049, 0, 0}, kHalf)));
  EXPECT_FALSE(FlushBoxUnion(a, Box({0.05, 0.001, 0}, kHalf)));
  EXPECT_FALSE(FlushBoxUnion(a, Box({0.05, 0, 0}, {0.025, 0.03, 0.025})));
  EXPECT_FALSE(FlushBoxUnion(
      a, Box({0.05, 0, 0}, kHalf,
             Quaterniond(AngleAxisd(M_PI / 4, Vector3d::UnitX())))));
  EXPECT_FALSE(
      FlushBoxUnion(Box({0, 0, 0}, {0.025, 0.02, 0.03}),
                    Box({0.05, 0, 0}, {0.025, 0.02, 0.03},
                        Quaterniond(AngleAxisd(M_PI / 2, Vector3d::UnitX())))));
  // Degenerate boxes never merge.
  EXPECT_FALSE(FlushBoxUnion(Box({0, 0, 0}, Vector3d::Zero()),
                             Box({0, 0, 0}, Vector3d::Zero())));
}

}  // namespace
}  // namespace mrsim

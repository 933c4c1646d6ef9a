// The network controller: its shape fixes the weight count (the genome
// size), and its targets stay in range and are the same for the same
// weights and state.
#include "nn_controller/mlp_network.h"

#include <gtest/gtest.h>

#include <cmath>

#include "nn_controller/network_genes.h"

namespace mrsim {
namespace {

MlpShape Shape(int joints, std::vector<int> hidden) {
  MlpShape s;
  s.joints = joints;
  s.hidden = std::move(hidden);
  return s;
}

std::vector<double> Weights(long n, double scale = 0.7) {
  std::vector<double> w(static_cast<size_t>(n));
  for (size_t i = 0; i < w.size(); ++i) w[i] = scale * std::sin(1.7 * i + 0.3);
  return w;
}

NnObservation Observation(int joints, double t) {
  NnObservation o;
  o.time = t;
  for (int j = 0; j < joints; ++j) {
    o.angles.push_back(0.1 * j);
    o.speeds.push_back(-0.2 * j);
  }
  return o;
}

TEST(MlpShape, WeightCountFollowsJointsAndHiddenLayers) {
  // 11 joints: 22 joint inputs + sin/cos = 24; 24*8+8 + 8*11+11.
  EXPECT_EQ(Shape(11, {8}).WeightCount(), 24 * 8 + 8 + 8 * 11 + 11);
  EXPECT_EQ(Shape(11, {8, 4}).WeightCount(),
            24 * 8 + 8 + 8 * 4 + 4 + 4 * 11 + 11);
  MlpShape imu = Shape(3, {2});
  imu.imu = true;
  imu.sensors = 5;
  EXPECT_EQ(imu.InputCount(), 6 + 2 + 7 + 5);
  EXPECT_EQ(NetworkGeneNames(Shape(11, {8})).size(), 299u + 1);
  EXPECT_EQ(NetworkGeneNames(Shape(11, {8}))[0], "period");
  EXPECT_EQ(NetworkGeneNames(Shape(11, {8}))[1], "w0");
}

TEST(MlpShape, HiddenLayersParseAndRefuseNonsense) {
  EXPECT_EQ(ParseHiddenLayers("8", "mlp"), (std::vector<int>{8}));
  EXPECT_EQ(ParseHiddenLayers("16,4", "mlp"), (std::vector<int>{16, 4}));
  for (const char* bad :
       {"", "0", "8,", ",8", "-1", "x", "99999", "1,1,1,1,1"}) {
    EXPECT_THROW(ParseHiddenLayers(bad, "mlp"), std::invalid_argument) << bad;
  }
}

TEST(MlpNetwork, TargetsStayWithinTheRangeAndRepeatBitForBit) {
  const MlpShape shape = Shape(5, {6, 3});
  MlpNetwork a(shape, Weights(shape.WeightCount(), 5.0), 2.0);
  MlpNetwork b(shape, Weights(shape.WeightCount(), 5.0), 2.0);
  for (double t : {0.0, 0.37, 1.2, 7.9}) {
    const std::vector<double> ta = a.Evaluate(Observation(5, t));
    const std::vector<double>& tb = b.Evaluate(Observation(5, t));
    EXPECT_EQ(ta, tb);
    for (double v : ta) EXPECT_LE(std::abs(v), shape.output_range);
  }
  // The clock moves the targets.
  const std::vector<double> t0 = a.Evaluate(Observation(5, 0.0));
  EXPECT_NE(t0, a.Evaluate(Observation(5, 0.5)));
}

TEST(MlpNetwork, RefusesWrongWeightsPeriodAndJointCount) {
  const MlpShape shape = Shape(4, {3});
  const long n = shape.WeightCount();
  EXPECT_THROW(MlpNetwork(shape, Weights(n - 1), 2.0), std::invalid_argument);
  std::vector<double> nan = Weights(n);
  nan[3] = std::nan("");
  EXPECT_THROW(MlpNetwork(shape, nan, 2.0), std::invalid_argument);
  EXPECT_THROW(MlpNetwork(shape, Weights(n), 0.0), std::invalid_argument);
  MlpNetwork net(shape, Weights(n), 2.0);
  EXPECT_THROW(net.Evaluate(Observation(5, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace mrsim

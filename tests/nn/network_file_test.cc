// Network files: a network read back has the same weights bit for bit, and
// a broken or hostile file is refused naming its line and field.
#include "nn_controller/network_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "tests/common/child_process.h"

namespace mrsim {
namespace {

MlpNetwork Net() {
  MlpShape s;
  s.joints = 3;
  s.hidden = {4, 2};
  s.imu = true;
  s.sensors = 2;
  std::vector<double> w(static_cast<size_t>(s.WeightCount()));
  // Numbers whose decimal forms are long: 1/3, pi, tiny, huge, -0.
  for (size_t i = 0; i < w.size(); ++i) {
    w[i] = std::pow(-1.0, static_cast<double>(i)) * M_PI / (i + 3.0);
  }
  w[0] = -0.0;
  w[1] = std::numeric_limits<double>::denorm_min();
  w[2] = 1e300;
  w[3] = 1.0 / 3.0;
  return MlpNetwork(s, w, 2.0 / 3.0);
}

// One joint, no clock: 2 inputs, a hidden layer of 3, one output:
// (2+1)*3 + (3+1)*1 = 13 weights.
std::string Valid(const std::string& weights, const std::string& count) {
  return "<network name=\"n\" joints=\"1\" hidden=\"3\" clock=\"0\" imu=\"0\" "
         "sensors=\"0\" range=\"1\" period=\"2\">\n"
         "  <weights count=\"" +
         count + "\">\n" + weights + "\n  </weights>\n</network>\n";
}

TEST(NetworkFile, WeightsRoundTripBitForBit) {
  const MlpNetwork net = Net();
  const std::string dir = testing::TempDir("network_file_round_trip");
  WriteNetworkFile(net, dir + "/net.xml", "my <net>");
  const NetworkFile back = ReadNetworkFile(dir + "/net.xml");
  EXPECT_EQ(back.name, "my <net>");
  EXPECT_TRUE(back.network.shape() == net.shape());
  EXPECT_EQ(back.network.period(), net.period());
  ASSERT_EQ(back.network.weights().size(), net.weights().size());
  for (size_t i = 0; i < net.weights().size(); ++i) {
    const double a = back.network.weights()[i], b = net.weights()[i];
    EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << i;  // -0 stays -0
  }
  EXPECT_EQ(WriteNetworkString(back.network, back.name),
            WriteNetworkString(net, "my <net>"));
}

TEST(NetworkFile, AValidFileReads) {
  std::string w = "1 2 3 4 5 6 7 8 9 10 11 12 13";
  const NetworkFile f = ReadNetworkString(Valid(w, "13"), "n.xml");
  EXPECT_EQ(f.network.weights().size(), 13u);
  EXPECT_EQ(f.network.weights()[12], 13.0);
}

// Each malformed file is refused with the file, the line and the field.
TEST(NetworkFile, MalformedFilesAreRefusedNamingTheField) {
  const std::string w13 = "1 2 3 4 5 6 7 8 9 10 11 12 13";
  struct Case {
    std::string xml;
    std::string expected;
  };
  std::string no_joints = Valid(w13, "13");
  no_joints.replace(no_joints.find("joints=\"1\""), 10, "");
  std::string huge = Valid(w13, "13");
  huge.replace(huge.find("joints=\"1\" hidden=\"3\""), 21,
               "joints=\"1024\" hidden=\"1024,1024,1024,1024\"");
  const Case cases[] = {
      {"<gait/>", "n.xml:1: expected the root element <network>"},
      {"<network", "n.xml:1: malformed XML"},
      {no_joints, "n.xml:1: network/@joints: missing"},
      {Valid(w13, "12"), "n.xml:2: network/weights/@count: this shape has 13"},
      {Valid("1 2 3 4 5 6 7 8 9 10 11 12 x", "13"),
       "n.xml:3: network/weights[12]: expected a finite number, got 'x'"},
      {Valid("1 2 3 4 5 6 7 8 9 10 11 12\n13 14", "13"),
       "n.xml:4: network/weights[13]: more weights than count"},
      {Valid("1 2 3\n4 inf", "13"),
       "n.xml:4: network/weights[4]: expected a finite number, got 'inf'"},
      {Valid("1 2", "13"), "network/weights: 2 numbers"},
      {huge, "n.xml:1: network: weights:"},
  };
  for (const Case& c : cases) {
    try {
      ReadNetworkString(c.xml, "n.xml");
      ADD_FAILURE() << "accepted:\n" << c.xml;
    } catch (const NetworkFileError& e) {
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos)
          << e.what() << "\nexpected: " << c.expected;
    }
  }
}

TEST(NetworkFile, AMissingFileIsNamed) {
  try {
    ReadNetworkFile("/nonexistent/net.xml");
    ADD_FAILURE();
  } catch (const NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/net.xml"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace mrsim

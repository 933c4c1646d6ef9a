// The seven gait parameters through a gait command and a gait status: the
// values keep their documented order both ways.
#include "gait_controller/process/gait_parameters_message.h"

#include <gtest/gtest.h>

#include <vector>

namespace mrsim {
namespace {

GaitParameters Sample() {
  GaitParameters p;
  p.amplitude_pitch = 0.8;
  p.amplitude_yaw = 0.3;
  p.phase_pitch = 2.1;
  p.phase_yaw = -1.2;
  p.period = 3.5;
  p.offset_pitch = 0.05;
  p.offset_yaw = -0.07;
  return p;
}

TEST(GaitParametersMessage, CommandRoundTripKeepsEveryValue) {
  gait_command_t command{};
  WriteGaitParameters(Sample(), command.parameters);
  EXPECT_EQ(GaitParametersFromMessage(command.parameters), Sample());
}

TEST(GaitParametersMessage, StatusCarriesTheValuesInDocumentedOrder) {
  gait_status_t status{};
  WriteGaitParameters(Sample(), status.parameters);
  EXPECT_EQ(GaitParameterValues(status.parameters),
            (std::vector<double>{0.8, 0.3, 2.1, -1.2, 3.5, 0.05, -0.07}));
}

}  // namespace
}  // namespace mrsim

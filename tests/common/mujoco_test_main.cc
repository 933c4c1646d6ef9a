// gtest main for binaries whose plain TEST()s run MuJoCo: every test fails
// on a MuJoCo warning it did not expect (see mujoco_test.h).
#include <gtest/gtest.h>

#include "tests/common/mujoco_test.h"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  mrsim::testing::InstallMujocoWarningGuard();
  return RUN_ALL_TESTS();
}

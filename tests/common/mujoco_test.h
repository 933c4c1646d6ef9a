// Fails the running test on a MuJoCo warning it did not expect, as MuJoCo's
// own test/fixture.h does: a test that passes while MuJoCo reports an
// unstable state passes by accident.
#pragma once

#include <gtest/gtest.h>

namespace mrsim::testing {

// Installs the guard for the rest of the process (idempotent): a MuJoCo
// warning outside an ExpectMujocoWarnings scope is a test failure naming
// the warning; MuJoCo errors throw MujocoError as in the library.
void InstallMujocoWarningGuard();

// Fixture for tests that run MuJoCo: TEST_F(MyTest, ...) with
// `using MyTest = MujocoTest;`.
class MujocoTest : public ::testing::Test {
 protected:
  MujocoTest() { InstallMujocoWarningGuard(); }
};

// Within its lifetime (on any thread), MuJoCo warnings are expected (a test
// of an exploding model) and only counted.
class ExpectMujocoWarnings {
 public:
  ExpectMujocoWarnings();
  ~ExpectMujocoWarnings();
  ExpectMujocoWarnings(const ExpectMujocoWarnings&) = delete;
  ExpectMujocoWarnings& operator=(const ExpectMujocoWarnings&) = delete;
  // Warnings seen since this scope began.
  long count() const;

 private:
  long start_;
};

}  // namespace mrsim::testing

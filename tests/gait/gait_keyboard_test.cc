// RawKeyboard on a pseudo-terminal: raw mode while it lives, arrows
// decoded, the terminal restored afterwards.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>

#include "gait_controller/process/keyboard.h"

namespace mrsim {
namespace {

// Puts a pty slave on stdin for the test's lifetime.
class PtyStdin {
 public:
  PtyStdin() {
    if (openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) {
      throw std::runtime_error("openpty failed");
    }
    saved_ = dup(STDIN_FILENO);
    dup2(slave_, STDIN_FILENO);
  }
  ~PtyStdin() {
    dup2(saved_, STDIN_FILENO);
    close(saved_);
    close(slave_);
    close(master_);
  }
  // Writes to the terminal and returns once the program side can read all
  // of it (the pty passes input on asynchronously).
  void Type(const std::string& bytes) {
    ASSERT_EQ(write(master_, bytes.data(), bytes.size()),
              static_cast<ssize_t>(bytes.size()));
    const auto end =
        std::chrono::steady_clock::now() + std::chrono::seconds(10);
    int ready = 0;
    while (ioctl(slave_, FIONREAD, &ready) == 0 &&
           ready < static_cast<int>(bytes.size()) &&
           std::chrono::steady_clock::now() < end) {
      pollfd p{slave_, POLLIN, 0};
      poll(&p, 1, 100);
    }
    ASSERT_EQ(ready, static_cast<int>(bytes.size()));
  }
  tcflag_t lflag() const {
    struct termios t;
    tcgetattr(slave_, &t);
    return t.c_lflag;
  }

 private:
  int master_ = -1;
  int slave_ = -1;
  int saved_ = -1;
};

TEST(GaitKeyboard, RawModeDecodesArrowsAndIsRestored) {
  PtyStdin pty;
  const tcflag_t before = pty.lflag();
  ASSERT_TRUE(before & ICANON);
  {
    RawKeyboard keys;
    EXPECT_FALSE(pty.lflag() & ICANON);
    EXPECT_FALSE(pty.lflag() & ECHO);
    EXPECT_TRUE(pty.lflag() & ISIG);  // Ctrl-C still stops the program
    EXPECT_FALSE(keys.Poll());
    pty.Type(
        "\x1b[A\x1b[D"
        "a ");
    auto k = keys.Poll();
    ASSERT_TRUE(k);
    EXPECT_EQ(k->code, KeyCode::kUp);
    k = keys.Poll();
    ASSERT_TRUE(k);
    EXPECT_EQ(k->code, KeyCode::kLeft);
    k = keys.Poll();
    ASSERT_TRUE(k);
    EXPECT_EQ(k->code, KeyCode::kChar);
    EXPECT_EQ(k->ch, 'a');
    k = keys.Poll();
    ASSERT_TRUE(k);
    EXPECT_EQ(k->ch, ' ');
    EXPECT_FALSE(keys.Poll());
  }
  EXPECT_EQ(pty.lflag(), before);
}

TEST(GaitKeyboard, RefusesANonTerminal) {
  const int saved = dup(STDIN_FILENO);
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  dup2(fds[0], STDIN_FILENO);
  EXPECT_THROW(RawKeyboard(), std::runtime_error);
  dup2(saved, STDIN_FILENO);
  close(saved);
  close(fds[0]);
  close(fds[1]);
}

}  // namespace
}  // namespace mrsim

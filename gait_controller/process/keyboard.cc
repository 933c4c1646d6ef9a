#include "gait_controller/process/keyboard.h"

#include <poll.h>
#include <unistd.h>

#include <stdexcept>

namespace mrsim {

RawKeyboard::RawKeyboard() {
  if (!isatty(STDIN_FILENO) || tcgetattr(STDIN_FILENO, &saved_) != 0) {
    throw std::runtime_error("--keyboard: stdin is not a terminal");
  }
  struct termios raw = saved_;
  // Keep ISIG so Ctrl-C still sends SIGINT and the stop handler runs.
  raw.c_lflag &= ~(ICANON | ECHO);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  if (tcsetattr(STDIN_FILENO, TCSANOW, &raw) != 0) {
    throw std::runtime_error("--keyboard: cannot set the terminal to raw mode");
  }
}

RawKeyboard::~RawKeyboard() { tcsetattr(STDIN_FILENO, TCSANOW, &saved_); }

int RawKeyboard::ReadByte(int timeout_ms) {
  struct pollfd p = {STDIN_FILENO, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0) return -1;
  unsigned char c = 0;
  if (read(STDIN_FILENO, &c, 1) != 1) return -1;
  return c;
}

std::optional<Key> RawKeyboard::Poll() {
  const int c = ReadByte(0);
  if (c < 0) return std::nullopt;
  if (c != 0x1b) return Key{KeyCode::kChar, static_cast<char>(c)};
  // ESC [ A..D (or ESC O A..D): the arrows. A lone ESC is a key of its own.
  const int c2 = ReadByte(20);
  if (c2 != '[' && c2 != 'O') return Key{KeyCode::kChar, 0x1b};
  switch (ReadByte(20)) {
    case 'A':
      return Key{KeyCode::kUp, 0};
    case 'B':
      return Key{KeyCode::kDown, 0};
    case 'C':
      return Key{KeyCode::kRight, 0};
    case 'D':
      return Key{KeyCode::kLeft, 0};
    default:
      return Key{KeyCode::kChar, 0x1b};
  }
}

}  // namespace mrsim

// Keyboard input for mrsim-gait when stdin is a terminal: puts the terminal
// in raw mode (no echo, no line buffering) and restores it on destruction,
// and decodes the arrow keys' escape sequences.
#pragma once

#include <termios.h>

#include <optional>
#include <string>

namespace mrsim {

enum class KeyCode { kUp, kDown, kLeft, kRight, kChar };

struct Key {
  KeyCode code = KeyCode::kChar;
  char ch = 0;  // for kChar
};

class RawKeyboard {
 public:
  // Throws std::runtime_error when stdin is not a terminal.
  RawKeyboard();
  ~RawKeyboard();
  RawKeyboard(const RawKeyboard&) = delete;
  RawKeyboard& operator=(const RawKeyboard&) = delete;

  // The next key if one is waiting (never blocks).
  std::optional<Key> Poll();

 private:
  int ReadByte(int timeout_ms);

  struct termios saved_;
};

}  // namespace mrsim

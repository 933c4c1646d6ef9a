#include "common/printable.h"

#include <gtest/gtest.h>

#include <string>

namespace mrsim {
namespace {

TEST(Printable, TerminalEscapesArriveAsText) {
  // A forged name that would clear the screen and retitle the terminal.
  const std::string forged = "w1\x1b[2J\x1b]0;owned\x07\r\nfake line";
  const std::string shown = Printable(forged);
  EXPECT_EQ(shown, "w1\\x1b[2J\\x1b]0;owned\\x07\\x0d\\x0afake line");
  for (const char c : shown) {
    EXPECT_TRUE(c == '\t' || (c >= 0x20 && c != 0x7f)) << int(c);
  }
}

TEST(Printable, OrdinaryTextAndUtf8PassUnchanged) {
  EXPECT_EQ(Printable("gen 3/10\tbest 0.42 \xc2\xb0"),
            "gen 3/10\tbest 0.42 \xc2\xb0");
  // A backslash is doubled, so "\x1b" typed by someone is not taken for an
  // escaped one.
  EXPECT_EQ(Printable("a\\x1b"), "a\\\\x1b");
  EXPECT_EQ(Printable(std::string("nul\0!", 5)), "nul\\x00!");
}

}  // namespace
}  // namespace mrsim

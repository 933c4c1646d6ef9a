// ShellQuote against a real /bin/sh: what --dry-run prints pastes back.
#include "launcher/shell_quote.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace mrsim {
namespace {

TEST(ShellQuote, AShellReadsEveryWordBackAsItWas) {
  const std::vector<std::string> words = {
      "--plot", "MRSIM_STATE_x:y=a,b:title=Front distance sensor:../f.png",
      "it's",   "$HOME",
      "a\"b",   "",
      "*",      "plain/path-1.xml"};
  std::string command = "printf '%s\\n'";
  for (const std::string& w : words) command += " " + ShellQuote(w);
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, pipe) != nullptr) out += buf;
  ASSERT_EQ(::pclose(pipe), 0) << command;
  std::string expected;
  for (const std::string& w : words) expected += w + "\n";
  EXPECT_EQ(out, expected) << command;
  // Words a shell leaves alone stay unquoted, so the line stays readable.
  EXPECT_EQ(ShellQuote("plain/path-1.xml"), "plain/path-1.xml");
  EXPECT_EQ(ShellQuote("--rate=100"), "--rate=100");
}

}  // namespace
}  // namespace mrsim

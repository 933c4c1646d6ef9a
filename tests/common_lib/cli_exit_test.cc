// How every program answers a refused command line (common/cli_exit.h).
#include "common/cli_exit.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "common/edit_distance.h"

namespace mrsim {
namespace {

struct Answer {
  int code = -1;
  std::string out, err;
};

Answer ParseWith(std::vector<std::string> args) {
  CLI::App app{"test program"};
  int modules = 0;
  app.add_option("--modules", modules);
  app.add_subcommand("new", "a subcommand")->add_option("--pattern", modules);
  args.insert(args.begin(), "/usr/bin/mrsim-test");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  Answer answer;
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    std::ostringstream out, err;
    answer.code = CliParseExit(app, e, out, err);
    answer.out = out.str();
    answer.err = err.str();
  }
  return answer;
}

TEST(CliParseExit, AnUnknownOptionIsNamedAsTypedWithTheNearestOne) {
  const Answer a = ParseWith({"--modlues", "5"});
  EXPECT_EQ(a.code, 2);
  EXPECT_EQ(a.err,
            "mrsim-test: unexpected arguments: --modlues 5\n"
            "  --modlues: did you mean --modules?\n"
            "Run with --help for more information.\n");
  // In a subcommand too, and nothing suggested when nothing is close.
  EXPECT_NE(
      ParseWith({"new", "--patern=yaw"}).err.find("did you mean --pattern?"),
      std::string::npos);
  EXPECT_EQ(ParseWith({"--zzzzzzzz"}).err.find("did you mean"),
            std::string::npos);
}

// Nearest as meant, not fewest edits: "--gate" is one change from
// "--rate" but was "--gait" (a shared beginning counts).
TEST(CliParseExit, TheSuggestionIsTheOptionMeantNotTheFewestEdits) {
  CLI::App app{"gait"};
  std::string text;
  app.add_option("--rate", text);
  app.add_option("--gait", text);
  app.add_option("--name", text);
  EXPECT_EQ(NearestOption(app, "--gate"), "--gait");
  EXPECT_EQ(NearestOption(app, "-gait"), "--gait");
  EXPECT_EQ(NearestOption(app, "--rat=5"), "--rate");
  EXPECT_EQ(NearestWord("pase", {"pause", "resume", "status", "gait"}),
            "pause");
  EXPECT_EQ(NearestWord("xyzzy", {"pause", "resume", "status", "gait"}), "");
}

// A word where a subcommand belongs suggests the nearest subcommand.
TEST(CliParseExit, AMistypedSubcommandSuggestsTheNearest) {
  CLI::App app{"test program"};
  app.require_subcommand(1);
  std::string file;
  app.add_subcommand("validate", "")->add_option("FILE", file);
  app.add_subcommand("convert", "")->add_option("IN", file);
  const std::vector<const char*> argv = {"mrsim-test", "valdate", "a.xml"};
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
    FAIL() << "parsed";
  } catch (const CLI::ParseError& e) {
    std::ostringstream out, err;
    EXPECT_EQ(CliParseExit(app, e, out, err), 2);
    EXPECT_NE(err.str().find("valdate: did you mean validate?"),
              std::string::npos)
        << err.str();
  }
}

TEST(CliParseExit, HelpIsZeroAndOtherRefusalsAreTwo) {
  const Answer help = ParseWith({"--help"});
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.out.find("test program"), std::string::npos);
  const Answer missing = ParseWith({"--modules"});
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("--modules"), std::string::npos);
}

}  // namespace
}  // namespace mrsim

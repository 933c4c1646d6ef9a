// An enum's one table of words: parse and print through it, and a flag
// built on it refuses a bad word naming the flag and every valid word.
#include "common/enum_table.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/enum_option.h"

namespace mrsim {
namespace {

enum class Colour { kRed, kGreen, kBlue };

const EnumTable<Colour>& Colours() {
  static const EnumTable<Colour> kColours("colour", {{Colour::kRed, "red"},
                                                     {Colour::kGreen, "green"},
                                                     {Colour::kBlue, "blue"}});
  return kColours;
}

TEST(EnumTable, ParseAndPrintRoundTripEveryWord) {
  for (const std::string& name : Colours().Names()) {
    EXPECT_EQ(Colours().Name(Colours().Parse(name)), name);
  }
  EXPECT_STREQ(Colours().Name(static_cast<Colour>(9)), "?");
  EXPECT_EQ(Colours().Choices(), "red, green or blue");
  EXPECT_EQ(Colours().Choices(" | "), "red | green | blue");
}

TEST(EnumTable, BadWordNamesTheFieldAndListsEveryWord) {
  try {
    Colours().Parse("purple");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "colour: expected red, green or blue, got 'purple'");
  }
  try {
    Colours().Parse("", "--paint");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--paint: expected red, green or blue, got ''");
  }
}

TEST(EnumOption, FlagTakesAWordAndRefusesAnotherNamingTheFlag) {
  Colour colour = Colour::kGreen;
  CLI::App app;
  AddEnumOption(app, "--paint", &colour, Colours(), "what to paint with");
  EXPECT_NE(app.help().find("red | green | blue: what to paint with"),
            std::string::npos)
      << app.help();
  EXPECT_NE(app.help().find("green"), std::string::npos);
  app.parse(std::vector<std::string>{"blue", "--paint"});
  EXPECT_EQ(colour, Colour::kBlue);
  try {
    app.parse(std::vector<std::string>{"purple", "--paint"});
    FAIL();
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--paint"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("red, green or blue"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace mrsim

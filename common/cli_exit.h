// How every mrsim program answers a command line CLI11 refused: the same
// exit codes everywhere, and an unexpected argument named as typed, with
// the option it was probably meant to be.
#pragma once

#include <CLI/CLI.hpp>
#include <ostream>
#include <string>

namespace mrsim {

// For --help and --version: prints them and returns 0. Otherwise prints
// what was wrong to `err` and returns 2 (bad usage). Unexpected arguments
// are listed in the order given ("--modlues 5", where CLI11 says "5
// --modlues"), each unknown option with the nearest known one, and a word
// where a subcommand was expected with the nearest subcommand.
int CliParseExit(const CLI::App& app, const CLI::ParseError& error,
                 std::ostream& out = std::cout, std::ostream& err = std::cerr);

// The known option nearest to `typed` ("--modlues" -> "--modules") among
// `app`'s and its subcommands' options, or "" when none is close.
std::string NearestOption(const CLI::App& app, const std::string& typed);

// The subcommand of `app` nearest to `typed`, or "" when none is close.
std::string NearestSubcommand(const CLI::App& app, const std::string& typed);

}  // namespace mrsim

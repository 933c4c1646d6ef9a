// Parses `args` (without the program name) with `app` as a program named
// `program` would be run: the way tests give a tool's flags to its
// command-line class without starting the tool.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace mrsim::testing {

inline void ParseFlags(CLI::App& app, const std::string& program,
                       const std::vector<std::string>& args) {
  std::vector<const char*> argv = {program.c_str()};
  for (const std::string& a : args) argv.push_back(a.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
}

}  // namespace mrsim::testing

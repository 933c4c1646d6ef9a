// gait_atlas: measures the gait atlas (docs/physics.md, "Gait atlas") and
// writes docs/gait_atlas.csv, or checks a build against it as ctest -L
// atlas does.
//
//   gait_atlas [--write FILE]          every line, 13 runs each
//   gait_atlas --check FILE            exit 1 when a line moved too far
//   gait_atlas ... --line NAME...      only these lines
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/gait/task_atlas.h"
#include "common/cli_exit.h"
#include "gait_controller/atlas_deviation.h"
#include "gait_controller/gait_atlas.h"

int main(int argc, char** argv) {
  CLI::App app{"gait_atlas: measure or check the gait atlas"};
  std::string write;
  std::string check;
  std::vector<std::string> only;
  app.add_option("--write", write, "Write the table to this file");
  app.add_option("--check", check, "Compare with this table")
      ->excludes(app.get_option("--write"));
  app.add_option("--line", only, "Only these lines");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return mrsim::CliParseExit(app, err);
  }
  try {
    const auto table = check.empty() ? std::vector<mrsim::AtlasLine>{}
                                     : mrsim::ReadAtlasTable(check);
    std::vector<mrsim::AtlasLine> lines;
    bool moved = false;
    for (const mrsim::AtlasEntry& e : mrsim::AllAtlasEntries()) {
      if (!only.empty() &&
          std::find(only.begin(), only.end(), e.name) == only.end()) {
        continue;
      }
      fmt::print(stderr, "gait_atlas: {} ...\n", e.name);
      if (check.empty()) {
        lines.push_back(mrsim::MeasureAtlasLine(e));
        continue;
      }
      const mrsim::AtlasLine& l = mrsim::FindAtlasLine(table, e.name);
      const auto d =
          mrsim::CompareAtlasLine(l, mrsim::MeasureAtlasValues(e, l.samples));
      moved = moved || mrsim::AnyBeyond(d);
      fmt::print("{}", mrsim::DescribeAtlasDeviations(d));
    }
    if (!check.empty()) return moved ? 1 : 0;
    const std::string text = mrsim::FormatAtlasTable(lines);
    if (write.empty()) {
      fmt::print("{}", text);
    } else if (!(std::ofstream(write) << text)) {
      throw std::runtime_error("cannot write " + write);
    }
    return 0;
  } catch (const std::exception& err) {
    fmt::print(stderr, "gait_atlas: {}\n", err.what());
    return 1;
  }
}

#include "gait_controller/atlas_table.h"

#include <fmt/format.h>

#include <fstream>
#include <optional>
#include <sstream>

#include "common/exact_number.h"

namespace mrsim {

namespace {

constexpr int kFixedColumns = 3;  // line, robot, samples
constexpr int kColumns = kFixedColumns + 3 * kAtlasQuantities;

std::vector<std::string> SplitCsv(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream ss(row);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!row.empty() && row.back() == ',') cells.emplace_back();
  return cells;
}

double ParseNumber(const std::string& cell, const std::string& where) {
  const std::optional<double> v = ParseWholeNumber(cell);
  if (!v) {
    throw AtlasTableError(
        fmt::format("{}: expected a number, got '{}'", where, cell));
  }
  return *v;
}

}  // namespace

const char* AtlasQuantityName(AtlasQuantity q) {
  switch (q) {
    case AtlasQuantity::kSpeed:
      return "speed";
    case AtlasQuantity::kDrift:
      return "drift";
    case AtlasQuantity::kRise:
      return "rise";
    case AtlasQuantity::kHeading:
      return "heading";
    case AtlasQuantity::kRoll:
      return "roll";
  }
  return "?";
}

const char* AtlasQuantityUnit(AtlasQuantity q) {
  return q == AtlasQuantity::kHeading || q == AtlasQuantity::kRoll ? "deg"
                                                                   : "bl/s";
}

std::string FormatAtlasTable(const std::vector<AtlasLine>& lines) {
  std::string text =
      "# The gait atlas: what every gait does on flat ground (docs/physics.md,"
      " \"Gait atlas\").\n"
      "# Generated, never typed: build/bench/gait/gait_atlas --write "
      "docs/gait_atlas.csv\n"
      "# Checked by ctest -L atlas; a line that moves beyond its tolerance "
      "fails until\n"
      "# this file is regenerated and docs/physics.md says what moved and "
      "why.\n"
      "line,robot,samples";
  for (int q = 0; q < kAtlasQuantities; ++q) {
    const std::string n = AtlasQuantityName(static_cast<AtlasQuantity>(q));
    const std::string u = AtlasQuantityUnit(static_cast<AtlasQuantity>(q));
    text += fmt::format(",{0}_{1},{0}_spread,{0}_tolerance", n,
                        u == "deg" ? "deg" : "bl_s");
  }
  text += "\n";
  for (const AtlasLine& l : lines) {
    text += fmt::format("{},{},{}", l.name, l.robot, l.samples);
    for (const AtlasValue& v : l.values) {
      text +=
          fmt::format(",{:.6g},{:.6g},{:.6g}", v.value, v.spread, v.tolerance);
    }
    text += "\n";
  }
  return text;
}

std::vector<AtlasLine> ParseAtlasTable(const std::string& text,
                                       const std::string& origin) {
  std::vector<AtlasLine> lines;
  std::stringstream in(text);
  std::string row;
  int number = 0;
  bool header = true;
  while (std::getline(in, row)) {
    ++number;
    if (row.empty() || row[0] == '#') continue;
    if (header) {  // the column names, checked by count only
      header = false;
      if (SplitCsv(row).size() != kColumns) {
        throw AtlasTableError(
            fmt::format("{}:{}: header has {} columns, not {}", origin, number,
                        SplitCsv(row).size(), kColumns));
      }
      continue;
    }
    const std::vector<std::string> cells = SplitCsv(row);
    const std::string where = fmt::format("{}:{}", origin, number);
    if (cells.size() != kColumns) {
      throw AtlasTableError(fmt::format("{}: {} columns, expected {}", where,
                                        cells.size(), kColumns));
    }
    AtlasLine line;
    line.name = cells[0];
    line.robot = cells[1];
    line.samples = static_cast<int>(ParseNumber(cells[2], where + ": samples"));
    if (line.name.empty() || line.samples < 1) {
      throw AtlasTableError(where + ": a line needs a name and samples >= 1");
    }
    for (int q = 0; q < kAtlasQuantities; ++q) {
      const std::string field =
          where + ": " + AtlasQuantityName(static_cast<AtlasQuantity>(q));
      AtlasValue& v = line.values[q];
      v.value = ParseNumber(cells[kFixedColumns + 3 * q], field);
      v.spread = ParseNumber(cells[kFixedColumns + 3 * q + 1], field);
      v.tolerance = ParseNumber(cells[kFixedColumns + 3 * q + 2], field);
    }
    lines.push_back(line);
  }
  return lines;
}

std::vector<AtlasLine> ReadAtlasTable(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw AtlasTableError("cannot read the gait atlas " + path);
  std::stringstream text;
  text << file.rdbuf();
  return ParseAtlasTable(text.str(), path);
}

const AtlasLine& FindAtlasLine(const std::vector<AtlasLine>& lines,
                               const std::string& name) {
  for (const AtlasLine& l : lines) {
    if (l.name == name) return l;
  }
  throw AtlasTableError("the gait atlas has no line '" + name + "'");
}

}  // namespace mrsim

// Reads back the CSV files the logger writes (no quoted cells in them).
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mrsim::testing {

struct CsvFile {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string text;  // the whole file

  int Column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
  }
};

inline std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  return cells;
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline CsvFile ReadCsvFile(const std::string& path) {
  CsvFile f;
  f.text = ReadText(path);
  std::istringstream in(f.text);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    if (first) {
      f.header = SplitCsvLine(line);
      first = false;
    } else {
      f.rows.push_back(SplitCsvLine(line));
    }
  }
  return f;
}

}  // namespace mrsim::testing

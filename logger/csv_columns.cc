#include "logger/csv_columns.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace mrsim {
namespace {

// Reads one record, which may span lines inside quotes. False at the end.
bool ReadRecord(std::istream& in, std::string* record, int* line) {
  record->clear();
  std::string part;
  bool quoted = false;
  bool any = false;
  while (std::getline(in, part)) {
    any = true;
    ++*line;
    if (!record->empty() || quoted) record->push_back('\n');
    record->append(part);
    for (char c : part) {
      if (c == '"') quoted = !quoted;
    }
    if (!quoted) break;
  }
  if (!record->empty() && record->back() == '\r') record->pop_back();
  return any;
}

// NaN for an empty cell or one that is not a number (`*bad` set).
double ParseNumber(const std::string& cell, bool* bad) {
  double v = std::numeric_limits<double>::quiet_NaN();
  if (cell.empty()) return v;
  const char* begin = cell.data();
  const char* end = begin + cell.size();
  if (*begin == '+') ++begin;
  const auto r = std::from_chars(begin, end, v);
  if (r.ec != std::errc() || r.ptr != end) {
    *bad = true;
    return std::numeric_limits<double>::quiet_NaN();
  }
  return v;
}

std::string Similar(const std::vector<std::string>& header,
                    const std::string& name) {
  // Columns sharing the first path component, else the first few.
  const std::string stem = name.substr(0, name.find('.'));
  std::vector<std::string> out;
  for (const std::string& h : header) {
    if (h.rfind(stem, 0) == 0) out.push_back(h);
  }
  if (out.empty()) out = header;
  std::string text;
  const size_t n = std::min<size_t>(out.size(), 12);
  for (size_t i = 0; i < n; ++i) text += (i ? ", " : "") + out[i];
  if (out.size() > n) text += ", ...";
  return text;
}

}  // namespace

std::vector<std::string> SplitCsvRecord(const std::string& record) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (size_t i = 0; i < record.size(); ++i) {
    const char c = record[i];
    if (quoted) {
      if (c == '"' && i + 1 < record.size() && record[i + 1] == '"') {
        cell.push_back('"');
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell.push_back(c);
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(std::move(cell));
      cell.clear();
    } else {
      cell.push_back(c);
    }
  }
  cells.push_back(std::move(cell));
  return cells;
}

CsvColumns ReadCsvColumns(const std::string& path,
                          const std::vector<std::string>& wanted) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw PlotInputError(path + ": is a folder, not a CSV file");
  }
  std::ifstream in(path);
  if (!in) {
    throw PlotInputError(path + ": cannot open the file (" +
                         std::strerror(errno) + ")");
  }
  std::string record;
  int line = 0;
  if (!ReadRecord(in, &record, &line)) {
    throw PlotInputError(path + ": empty file, expected a header line");
  }
  // An XML file (a scenario, a genome) or anything else that is not a
  // table: named as such, not searched for columns.
  if (record.rfind("<?xml", 0) == 0 || record.rfind("<", 0) == 0 ||
      record.rfind("\x89PNG", 0) == 0) {
    throw PlotInputError(path +
                         ": not a CSV file (expected a header line of "
                         "column names, as mrsim-log and mrsim-opt write)");
  }
  const std::vector<std::string> header = SplitCsvRecord(record);
  CsvColumns out;
  out.names = wanted;
  out.values.resize(wanted.size());
  std::vector<size_t> index;
  for (const std::string& name : wanted) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) {
      throw PlotInputError(path + ": no column '" + name +
                           "'; columns include: " + Similar(header, name));
    }
    index.push_back(static_cast<size_t>(it - header.begin()));
  }
  std::vector<size_t> cells_at;
  // Left out of the plot, counted so the user hears of them.
  const auto parse = [&](const std::string& cell, size_t k) {
    bool bad = false;
    const double v = ParseNumber(cell, &bad);
    if (bad && out.not_numbers++ == 0) {
      out.first_not_number = path + ":" + std::to_string(line) + ": column '" +
                             wanted[k] + "': '" + cell + "'";
    }
    return v;
  };
  while (ReadRecord(in, &record, &line)) {
    if (record.empty()) continue;
    if (record.find('"') == std::string::npos) {
      // Fast path for the usual all-number rows: find cell bounds only.
      cells_at.assign(header.size() + 1, 0);
      size_t n = 0;
      cells_at[n++] = 0;
      for (size_t i = 0; i < record.size() && n <= header.size(); ++i) {
        if (record[i] == ',') cells_at[n++] = i + 1;
      }
      if (n != header.size()) {
        throw PlotInputError(path + ":" + std::to_string(line) + ": expected " +
                             std::to_string(header.size()) + " cells, found " +
                             std::to_string(n));
      }
      cells_at.resize(n);
      cells_at.push_back(record.size() + 1);
      for (size_t k = 0; k < index.size(); ++k) {
        const size_t b = cells_at[index[k]];
        const size_t e = cells_at[index[k] + 1] - 1;
        out.values[k].push_back(parse(record.substr(b, e - b), k));
      }
      ++out.rows;
      continue;
    }
    const std::vector<std::string> cells = SplitCsvRecord(record);
    if (cells.size() != header.size()) {
      throw PlotInputError(path + ":" + std::to_string(line) + ": expected " +
                           std::to_string(header.size()) + " cells, found " +
                           std::to_string(cells.size()));
    }
    for (size_t k = 0; k < index.size(); ++k) {
      out.values[k].push_back(parse(cells[index[k]], k));
    }
    ++out.rows;
  }
  return out;
}

}  // namespace mrsim

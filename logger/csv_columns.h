// Chosen columns of a CSV file (as mrsim-log writes them) read as numbers,
// for plotting without loading every column of a large log.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace mrsim {

// Bad plot input: a missing file or column, a malformed CSV. Programs exit
// with status 2 on it.
class PlotInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct CsvColumns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // values[i] is column names[i]
  size_t rows = 0;
  size_t not_numbers = 0;        // cells neither empty nor a number
  std::string first_not_number;  // "FILE:LINE: column 'c': 'text'"
};

// Reads the columns `wanted` (in that order) of the CSV at `path`. Cells
// that are not numbers read as NaN. Throws PlotInputError naming the file,
// the line, or the missing column (and columns with a similar name).
CsvColumns ReadCsvColumns(const std::string& path,
                          const std::vector<std::string>& wanted);

// Splits one CSV record (RFC 4180 quoting) into cells.
std::vector<std::string> SplitCsvRecord(const std::string& record);

}  // namespace mrsim

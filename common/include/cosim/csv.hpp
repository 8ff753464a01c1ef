#pragma once
// Reading small CSV tables (reference data, study tables): a header line, then
// rows; fields separated by commas, a field in double quotes may hold commas
// and "" for a quote; lines starting with '#' and blank lines are skipped.
#include <string>
#include <vector>

namespace cosim {

struct CsvTable {
  std::string file;
  std::vector<std::string> header;
  struct Row {
    int line = 0;  // 1-based line in the file, for messages
    std::vector<std::string> fields;
  };
  std::vector<Row> rows;

  // Column index of `name`; throws cosim::Error naming the file if absent.
  std::size_t column(const std::string& name) const;
  // The field of `row` in column `name` ("" if the row is short).
  const std::string& field(const Row& row, const std::string& name) const;
  // "FILE:LINE: field NAME" for a message about a row's field.
  std::string where(const Row& row, const std::string& name) const;
};

// Throws cosim::Error naming the file (and line) if it cannot be read, a
// quote is left open or a row has more fields than the header.
CsvTable read_csv(const std::string& path);

}  // namespace cosim

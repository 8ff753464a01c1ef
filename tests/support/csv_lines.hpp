#pragma once
// The data lines of the reference CSV files under tests/data.
#include <istream>
#include <string>
#include <vector>

namespace test_support {

// Every line of `in` but empty lines and '#' comments, less the first of those that
// remain when the file has a header row.
inline std::vector<std::string> csv_data_lines(std::istream& in, bool skip_header) {
  std::vector<std::string> lines;
  std::string line;
  bool header = skip_header;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) { header = false; continue; }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace test_support

#include "cosim/csv.hpp"

#include <fstream>

#include "cosim/error.hpp"

namespace cosim {
namespace {

std::vector<std::string> split_line(const std::string& line, const std::string& file, int number) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else fields.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  if (quoted) throw Error(file + ":" + std::to_string(number) + ": a quoted field is not closed");
  return fields;
}

}  // namespace

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t c = 0; c < header.size(); ++c)
    if (header[c] == name) return c;
  throw Error(file + ":1: no column '" + name + "'");
}

const std::string& CsvTable::field(const Row& row, const std::string& name) const {
  static const std::string empty;
  const std::size_t c = column(name);
  return c < row.fields.size() ? row.fields[c] : empty;
}

std::string CsvTable::where(const Row& row, const std::string& name) const {
  return file + ":" + std::to_string(row.line) + ": field " + name;
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot be read");
  CsvTable table;
  table.file = path;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line == "\r" || line[0] == '#') continue;
    auto fields = split_line(line, path, number);
    if (table.header.empty()) {
      table.header = std::move(fields);
      continue;
    }
    if (fields.size() > table.header.size())
      throw Error(path + ":" + std::to_string(number) + ": " + std::to_string(fields.size()) + " fields, the header has " +
                  std::to_string(table.header.size()));
    table.rows.push_back({number, std::move(fields)});
  }
  if (table.header.empty()) throw Error(path + ": no header line");
  return table;
}

}  // namespace cosim

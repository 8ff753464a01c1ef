#pragma once
// The tyre's material constants as the tests read them at run time from thesis
// Tables 5.2-5.4 ($COSIM_TEST_DATA/rubber_yeoh.csv, reinforcement_rebar.csv,
// reinforcement_elastic.csv).
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "csv_lines.hpp"
#include "tyre_fe/materials.hpp"

namespace tyre_material_data {

inline std::string data_dir() {
  const char* env = std::getenv("COSIM_TEST_DATA");
  return (env && *env) ? std::string(env) : std::string("tests/data/reference");
}

// The row of `file` whose first cell is `key`, '#' comments and the header skipped.
inline std::vector<double> csv_row(const std::string& file, const std::string& key) {
  const std::string path = data_dir() + "/" + file;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path + " (set COSIM_TEST_DATA)");
  for (const std::string& line : test_support::csv_data_lines(in, true)) {
    std::stringstream ss(line);
    std::string cell;
    std::getline(ss, cell, ',');
    if (cell != key) continue;
    std::vector<double> values;
    while (std::getline(ss, cell, ',')) values.push_back(std::stod(cell));
    return values;
  }
  throw std::runtime_error("no row '" + key + "' in " + path);
}

// A Yeoh rubber from its row of rubber_yeoh.csv (density, C10, C20, C30); the bulk
// modulus is the caller's.
inline tyre_fe::SolidMaterial yeoh_rubber(const std::vector<double>& row) {
  tyre_fe::SolidMaterial m;
  m.kind = tyre_fe::SolidMaterial::Kind::yeoh;
  m.yeoh.density_kg_per_m3 = row.at(0);
  m.yeoh.C10_Pa = row.at(1);
  m.yeoh.C20_Pa = row.at(2);
  m.yeoh.C30_Pa = row.at(3);
  return m;
}

}  // namespace tyre_material_data

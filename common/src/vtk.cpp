#include "cosim/vtk.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"

namespace cosim::vtk {
namespace {

void put_be(std::string& out, std::uint64_t bits, int bytes) {
  for (int shift = 8 * (bytes - 1); shift >= 0; shift -= 8) out.push_back(static_cast<char>((bits >> shift) & 0xFF));
}

}  // namespace

void put_be_int32(std::string& out, std::int32_t value) { put_be(out, static_cast<std::uint32_t>(value), 4); }

void put_be_float32(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  put_be(out, bits, 4);
}

void put_be_float64(std::string& out, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  put_be(out, bits, 8);
}

LegacyFile::LegacyFile(const std::string& title, const char* dataset, Real real)
    : real_(real), poly_data_(std::strcmp(dataset, "POLYDATA") == 0) {
  if (title.size() > 256 || title.find('\n') != std::string::npos)
    throw Error("VTK title '" + title + "' is longer than 256 characters or has a line break");
  out_ = "# vtk DataFile Version 3.0\n" + title + "\nBINARY\nDATASET " + dataset + "\n";
}

LegacyFile LegacyFile::poly_data(const std::string& title, Real real) { return LegacyFile(title, "POLYDATA", real); }

LegacyFile LegacyFile::unstructured_grid(const std::string& title, Real real) {
  return LegacyFile(title, "UNSTRUCTURED_GRID", real);
}

void LegacyFile::put_real(double v) {
  if (real_ == Real::Float32) put_be_float32(out_, v);
  else put_be_float64(out_, v);
}

void LegacyFile::points(std::size_t n, const double* x, const double* y, const double* z) {
  if (n_points_ != 0 || section_ != 0) throw Error("VTK file: POINTS written twice or after the attributes");
  out_ += "POINTS " + std::to_string(n) + (real_ == Real::Float32 ? " float\n" : " double\n");
  for (std::size_t i = 0; i < n; ++i) put_real(x[i]), put_real(y[i]), put_real(z[i]);
  out_ += "\n";
  n_points_ = n;
}

void LegacyFile::vertices() {
  if (!poly_data_) throw Error("VTK file: VERTICES belong to a POLYDATA dataset");
  const std::size_t n = n_points_;
  out_ += "VERTICES " + std::to_string(n) + " " + std::to_string(2 * n) + "\n";
  for (std::size_t i = 0; i < n; ++i) put_be_int32(out_, 1), put_be_int32(out_, static_cast<std::int32_t>(i));
  out_ += "\n";
  n_cells_ = n;
}

void LegacyFile::cells(const std::vector<int>& connectivity, int nodes_per_cell, CellType type) {
  if (poly_data_) throw Error("VTK file: CELLS belong to an UNSTRUCTURED_GRID dataset");
  if (nodes_per_cell <= 0 || connectivity.size() % nodes_per_cell != 0)
    throw Error("VTK file: " + std::to_string(connectivity.size()) + " point ids are not cells of " +
                std::to_string(nodes_per_cell) + " points");
  const std::size_t n = connectivity.size() / nodes_per_cell;
  out_ += "CELLS " + std::to_string(n) + " " + std::to_string(n * (nodes_per_cell + 1)) + "\n";
  for (std::size_t c = 0; c < n; ++c) {
    put_be_int32(out_, nodes_per_cell);
    for (int a = 0; a < nodes_per_cell; ++a) put_be_int32(out_, connectivity[c * nodes_per_cell + a]);
  }
  out_ += "\nCELL_TYPES " + std::to_string(n) + "\n";
  for (std::size_t c = 0; c < n; ++c) put_be_int32(out_, static_cast<int>(type));
  out_ += "\n";
  n_cells_ = n;
}

void LegacyFile::begin(On on, const std::string& name, std::size_t values_per_entry, std::size_t values) {
  if (name.empty() || name.find_first_of(" \t\n") != std::string::npos)
    throw Error("VTK file: field name '" + name + "' is empty or has blanks");
  const std::size_t n = count(on);
  if (values != n * values_per_entry)
    throw Error("VTK file: field '" + name + "' has " + std::to_string(values) + " values for " + std::to_string(n) +
                (on == On::Points ? " points" : " cells") + " of " + std::to_string(values_per_entry) +
                " component(s)");
  const int section = on == On::Points ? 1 : 2;
  if (section_ != section) out_ += (on == On::Points ? "POINT_DATA " : "CELL_DATA ") + std::to_string(n) + "\n";
  section_ = section;
}

void LegacyFile::scalars(On on, const std::string& name, const double* values) {
  begin(on, name, 1, count(on));
  out_ += "SCALARS " + name + (real_ == Real::Float32 ? " float" : " double") + " 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < count(on); ++i) put_real(values[i]);
  out_ += "\n";
}

void LegacyFile::scalars(On on, const std::string& name, const std::vector<double>& values) {
  begin(on, name, 1, values.size());
  scalars(on, name, values.data());
}

void LegacyFile::int_scalars(On on, const std::string& name, const std::vector<int>& values) {
  begin(on, name, 1, values.size());
  out_ += "SCALARS " + name + " int 1\nLOOKUP_TABLE default\n";
  for (int v : values) put_be_int32(out_, v);
  out_ += "\n";
}

void LegacyFile::vectors(On on, const std::string& name, const double* x, const double* y, const double* z) {
  begin(on, name, 1, count(on));
  out_ += "VECTORS " + name + (real_ == Real::Float32 ? " float\n" : " double\n");
  for (std::size_t i = 0; i < count(on); ++i) put_real(x[i]), put_real(y[i]), put_real(z[i]);
  out_ += "\n";
}

void LegacyFile::vectors(On on, const std::string& name, const std::vector<double>& xyz) {
  begin(on, name, 3, xyz.size());
  out_ += "VECTORS " + name + (real_ == Real::Float32 ? " float\n" : " double\n");
  for (double v : xyz) put_real(v);
  out_ += "\n";
}

void LegacyFile::save(const std::string& path) const {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream file(tmp, std::ios::binary);
    if (!file) throw Error("cannot write VTK file '" + tmp + "'");
    file.write(out_.data(), static_cast<std::streamsize>(out_.size()));
    if (!file) throw Error("error writing VTK file '" + tmp + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw Error("cannot rename '" + tmp + "' to '" + path + "': " + ec.message());
}

Series::Series(std::string folder, std::string name) : folder_(std::move(folder)), name_(std::move(name)) {
  make_folder(folder_);
}

std::string Series::file_name(std::size_t frame) const {
  std::ostringstream name;
  name << name_ << "_" << std::setw(5) << std::setfill('0') << frame << ".vtk";
  return name.str();
}

void Series::write_index() const {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& [n, t] : entries_) files.push_back({{"name", n}, {"time", t}});
  write_json(folder_ + "/" + name_ + ".vtk.series", {{"file-series-version", "1.0"}, {"files", files}});
}

std::string Series::write(double time_s, const LegacyFile& file) {
  const std::string name = file_name(entries_.size());
  file.save(folder_ + "/" + name);
  entries_.emplace_back(name, time_s);
  write_index();
  return name;
}

std::vector<double> Series::times() const {
  std::vector<double> t;
  for (const auto& e : entries_) t.push_back(e.second);
  return t;
}

void Series::resume(const std::vector<double>& times) {
  entries_.clear();
  for (double t : times) entries_.emplace_back(file_name(entries_.size()), t);
  write_index();
}

}  // namespace cosim::vtk

#include "cosim/outputs.hpp"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "cosim/error.hpp"

namespace cosim {

void make_folder(const std::string& path) {
  std::error_code ec;
  std::filesystem::create_directories(path, ec);
  if (ec) throw Error(path + ": cannot create folder: " + ec.message());
}

void write_json(const std::string& path, const nlohmann::json& value) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(path + ": cannot write: " + std::strerror(errno));
    out << value.dump(2) << "\n";
    if (!out) throw Error(path + ": write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw Error(path + ": cannot rename from " + tmp + ": " + std::strerror(errno));
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : path_(path), columns_(columns.size()), out_(path), last_flush_(std::chrono::steady_clock::now()) {
  if (!out_) throw Error(path + ": cannot write: " + std::strerror(errno));
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  out_ << "\n";
  out_.flush();
}

CsvWriter::~CsvWriter() { out_.flush(); }

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw Error(path_ + ": row has " + std::to_string(values.size()) + " values, header has " +
                std::to_string(columns_));
  char buffer[64];
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buffer, sizeof buffer, "%.10g", values[i]);
    out_ << (i ? "," : "") << buffer;
  }
  out_ << "\n";
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::seconds(1)) flush();
}

void CsvWriter::flush() {
  out_.flush();
  last_flush_ = std::chrono::steady_clock::now();
}

namespace {
// Legacy VTK binary is big-endian.
void put_be_float(std::ofstream& out, double v) {
  float f = static_cast<float>(v);
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  u = __builtin_bswap32(u);
  out.write(reinterpret_cast<const char*>(&u), 4);
}
void put_be_int(std::ofstream& out, std::int32_t v) {
  std::uint32_t u = __builtin_bswap32(static_cast<std::uint32_t>(v));
  out.write(reinterpret_cast<const char*>(&u), 4);
}
}  // namespace

VtkSeries::VtkSeries(std::string folder, std::string name)
    : folder_(std::move(folder)), name_(std::move(name)) {
  make_folder(folder_);
}

std::string VtkSeries::write(double time_s, std::size_t n, const double* x, const double* y,
                             const double* z, const std::vector<ScalarField>& scalars,
                             const std::vector<VectorField>& vectors) {
  std::ostringstream file;
  file << name_ << "_" << std::setw(5) << std::setfill('0') << entries_.size() << ".vtk";
  const std::string path = folder_ + "/" + file.str();
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error(path + ": cannot write");
  out << "# vtk DataFile Version 3.0\n" << name_ << " t=" << time_s << " s\nBINARY\nDATASET POLYDATA\n";
  out << "POINTS " << n << " float\n";
  for (std::size_t i = 0; i < n; ++i) put_be_float(out, x[i]), put_be_float(out, y[i]), put_be_float(out, z[i]);
  out << "\nVERTICES " << n << " " << 2 * n << "\n";
  for (std::size_t i = 0; i < n; ++i) put_be_int(out, 1), put_be_int(out, static_cast<std::int32_t>(i));
  out << "\nPOINT_DATA " << n << "\n";
  for (const auto& f : scalars) {
    out << "SCALARS " << f.name << " float 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) put_be_float(out, f.values[i]);
    out << "\n";
  }
  for (const auto& f : vectors) {
    out << "VECTORS " << f.name << " float\n";
    for (std::size_t i = 0; i < n; ++i) put_be_float(out, f.x[i]), put_be_float(out, f.y[i]), put_be_float(out, f.z[i]);
    out << "\n";
  }
  if (!out) throw Error(path + ": write failed");
  entries_.emplace_back(file.str(), time_s);
  write_index();
  return file.str();
}

void VtkSeries::write_index() const {
  nlohmann::json files = nlohmann::json::array();
  for (const auto& [name, t] : entries_) files.push_back({{"name", name}, {"time", t}});
  write_json(folder_ + "/" + name_ + ".vtk.series", {{"file-series-version", "1.0"}, {"files", files}});
}

bool plot_csv(const std::string& csv, const std::string& png, int x_column,
              const std::vector<PlotSeries>& series, const std::string& title,
              const std::string& x_label, const std::string& y_label,
              const std::string& extra_commands) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,600 font ',11' noenhanced\nset output '" << png << "'\n"
       << "set datafile separator ','\nset key autotitle columnhead\nset grid\n"
       << "set title '" << title << "'\nset xlabel '" << x_label << "'\nset ylabel '" << y_label << "'\n"
       << extra_commands << "plot ";
    for (std::size_t k = 0; k < series.size(); ++k)
      gp << (k ? ", " : "") << "'" << csv << "' using " << x_column << ":" << series[k].column
         << " with lines lw 2 title '" << series[k].title << "'";
    gp << "\n";
  }
  const bool ok = std::system(("gnuplot '" + script + "' >/dev/null 2>&1").c_str()) == 0;
  std::remove(script.c_str());
  return ok;
}

bool plot_csv_map(const std::string& csv, const std::string& png, int x_column, int y_column, int value_column,
                  const std::string& title, const std::string& x_label, const std::string& y_label,
                  const std::string& value_label) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 900,700 font ',11' noenhanced\nset output '" << png << "'\n"
       << "set datafile separator ','\nset grid\nset size ratio -1\nset palette rgb 33,13,10\n"
       << "set title '" << title << "'\nset xlabel '" << x_label << "'\nset ylabel '" << y_label << "'\n"
       << "set cblabel '" << value_label << "'\n"
       << "plot '" << csv << "' every ::1 using " << x_column << ":" << y_column << ":" << value_column
       << " with points pt 5 ps 1.2 palette notitle\n";
  }
  const bool ok = std::system(("gnuplot '" + script + "' >/dev/null 2>&1").c_str()) == 0;
  std::remove(script.c_str());
  return ok;
}

}  // namespace cosim

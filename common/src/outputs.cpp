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

VtkSeries::VtkSeries(std::string folder, std::string name) : series_(std::move(folder), std::move(name)) {}

std::string VtkSeries::write(double time_s, std::size_t n, const double* x, const double* y,
                             const double* z, const std::vector<ScalarField>& scalars,
                             const std::vector<VectorField>& vectors) {
  std::ostringstream title;
  title << series_.name() << " t=" << time_s << " s";
  auto file = vtk::LegacyFile::poly_data(title.str(), vtk::Real::Float32);
  file.points(n, x, y, z);
  file.vertices();
  for (const auto& f : scalars) file.scalars(vtk::LegacyFile::On::Points, f.name, f.values);
  for (const auto& f : vectors) file.vectors(vtk::LegacyFile::On::Points, f.name, f.x, f.y, f.z);
  return series_.write(time_s, file);
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

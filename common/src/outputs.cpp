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

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns, bool resume)
    : path_(path), columns_(columns.size()), last_flush_(std::chrono::steady_clock::now()) {
  if (resume && !std::filesystem::exists(path))
    throw Error(path + ": the series of the run being restarted is missing");
  std::string header;
  for (std::size_t i = 0; i < columns.size(); ++i) header += (i ? "," : "") + columns[i];
  if (resume) {
    // Rows of another layout appended under the old header would corrupt the
    // series: a build that writes other columns cannot continue this run.
    std::ifstream in(path);
    std::string first;
    std::getline(in, first);
    if (first != header)
      throw Error(path + ", line 1: the run being restarted wrote the columns '" + first + "'; this build writes '" +
                  header + "': restart with the build that began the run, or start afresh");
  }
  out_.open(path, resume ? std::ios::app : std::ios::trunc);
  if (!out_) throw Error(path + ": cannot write: " + std::strerror(errno));
  muted_ = resume;
  if (resume) return;
  out_ << header << "\n";
  out_.flush();
}

CsvWriter::~CsvWriter() { out_.flush(); }

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != columns_)
    throw Error(path_ + ": row has " + std::to_string(values.size()) + " values, header has " +
                std::to_string(columns_));
  if (muted_) return;
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

std::uint64_t CsvWriter::length() {
  flush();
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path_, ec);
  if (ec) throw Error(path_ + ": cannot read its length: " + ec.message());
  return bytes;
}

void CsvWriter::truncate(std::uint64_t bytes) {
  // Opened to append (O_APPEND): after the cut, rows go on at the new end.
  flush();
  std::error_code ec;
  if (std::filesystem::file_size(path_, ec) < bytes || ec)
    throw Error(path_ + ": shorter than at the checkpoint (" + std::to_string(bytes) + " bytes); cannot continue it");
  std::filesystem::resize_file(path_, bytes, ec);
  if (ec) throw Error(path_ + ": cannot cut it back to the checkpoint: " + ec.message());
  muted_ = false;
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

bool plot_png(const std::string& png, const PlotOptions& o, const std::vector<PlotCurve>& curves) {
  if (curves.empty()) throw Error(png + ": a plot needs at least one curve");
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
  // Text in a gnuplot single-quoted string: a quote is written twice (a title
  // such as "the ribs' depth" otherwise ends the string and the plot is lost).
  auto q = [](const std::string& text) {
    std::string out = "'";
    for (char ch : text) out += ch == '\'' ? std::string("''") : std::string(1, ch);
    return out + "'";
  };
  const std::string script = png + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size " << o.width_px << "," << o.height_px << " font ',11' noenhanced\n"
       << "set output '" << png << "'\nset datafile separator ','\nset grid\n";
    if (o.equal_axes) gp << "set size ratio -1\n";
    if (o.log_x) gp << "set logscale x\n";
    if (o.log_y) gp << "set logscale y\n";
    if (!o.colour_label.empty()) gp << "set palette rgb 33,13,10\nset cblabel " << q(o.colour_label) << "\n";
    if (!o.key) gp << "set key off\n";
    gp << "set title " << q(o.title) << "\nset xlabel " << q(o.x_label) << "\nset ylabel " << q(o.y_label) << "\n"
       << o.extra_commands << "plot ";
    for (std::size_t k = 0; k < curves.size(); ++k) {
      const auto& c = curves[k];
      gp << (k ? ", " : "") << "'" << c.csv << "' every ::1 using " << c.columns << " with " << c.style;
      if (c.title.empty()) gp << " notitle";
      else gp << " title " << q(c.title);
    }
    gp << "\n";
  }
  const bool ok = std::system(("gnuplot '" + script + "' >/dev/null 2>&1").c_str()) == 0;
  std::remove(script.c_str());
  if (!ok) std::remove(png.c_str());
  return ok;
}

bool plot_csv(const std::string& csv, const std::string& png, int x_column,
              const std::vector<PlotSeries>& series, const std::string& title,
              const std::string& x_label, const std::string& y_label,
              const std::string& extra_commands) {
  PlotOptions o;
  o.title = title, o.x_label = x_label, o.y_label = y_label, o.extra_commands = extra_commands;
  std::vector<PlotCurve> curves;
  for (const auto& s : series)
    curves.push_back({csv, std::to_string(x_column) + ":" + std::to_string(s.column), "lines lw 2", s.title});
  return plot_png(png, o, curves);
}

bool plot_csv_stacked(const std::string& csv, const std::string& png, int x_column,
                      const std::vector<PlotSeries>& stacked, const std::vector<PlotSeries>& lines,
                      const std::string& title, const std::string& x_label, const std::string& y_label) {
  // Sixteen colours told apart in print and by most colour-blind readers
  // (Tableau 10, then six darker tones); a seventeenth term repeats the first.
  static const char* const kColours[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948",
                                         "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac", "#1f3b5a", "#8c4a0f",
                                         "#6b1f22", "#2f5d2a", "#5a3b57", "#4d4d4d"};
  PlotOptions o;
  o.title = title, o.x_label = x_label, o.y_label = y_label;
  o.extra_commands = "set key top left reverse Left opaque box font ',9'\nset autoscale xfix\n";
  std::vector<PlotCurve> curves;
  const std::string x = std::to_string(x_column);
  std::string below = "0";
  for (std::size_t k = 0; k < stacked.size(); ++k) {
    const std::string above = (k ? below + "+" : std::string()) + "$" + std::to_string(stacked[k].column);
    curves.push_back({csv, x + ":(" + below + "):(" + above + ")",
                      std::string("filledcurves fs solid 0.85 noborder fc rgb '") + kColours[k % 16] + "'",
                      stacked[k].title});
    below = above;
  }
  for (const auto& l : lines)
    curves.push_back({csv, x + ":" + std::to_string(l.column), "lines lw 2 dt 2 lc rgb 'black'", l.title});
  return plot_png(png, o, curves);
}

bool plot_csv_map(const std::string& csv, const std::string& png, int x_column, int y_column, int value_column,
                  const std::string& title, const std::string& x_label, const std::string& y_label,
                  const std::string& value_label) {
  PlotOptions o;
  o.title = title, o.x_label = x_label, o.y_label = y_label;
  o.height_px = 700, o.equal_axes = true, o.colour_label = value_label;
  const std::string columns =
      std::to_string(x_column) + ":" + std::to_string(y_column) + ":" + std::to_string(value_column);
  return plot_png(png, o, {{csv, columns, "points pt 5 ps 1.2 palette", ""}});
}

}  // namespace cosim

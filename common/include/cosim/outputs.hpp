#pragma once
// Run outputs: summary.json, CSV time series, VTK files for ParaView.
// Everything is flushed as it is written, so a run that fails keeps what it
// produced up to its last completed step.
#include <chrono>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/vtk.hpp"

namespace cosim {

// Creates the folder (and parents); throws cosim::Error if it cannot.
void make_folder(const std::string& path);

// Writes JSON to path via a temporary file and rename (never half-written).
void write_json(const std::string& path, const nlohmann::json& value);

// A CSV time series with a fixed header. Rows are flushed at least every
// second of wall time and when the writer is destroyed.
class CsvWriter {
 public:
  CsvWriter(const std::string& path, const std::vector<std::string>& columns);
  ~CsvWriter();
  void row(const std::vector<double>& values);
  void flush();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::size_t columns_;
  std::ofstream out_;
  std::chrono::steady_clock::time_point last_flush_;
};

// Point cloud output (legacy binary VTK POLYDATA of float points, one file per
// frame) plus a "<name>.vtk.series" index that ParaView opens as a time series;
// written through the project's one VTK writer (cosim/vtk.hpp).
class VtkSeries {
 public:
  VtkSeries(std::string folder, std::string name);
  struct ScalarField {
    std::string name;
    const double* values;
  };
  struct VectorField {
    std::string name;
    const double* x;
    const double* y;
    const double* z;
  };
  // Writes one frame; returns the file name.
  std::string write(double time_s, std::size_t count, const double* x, const double* y,
                    const double* z, const std::vector<ScalarField>& scalars,
                    const std::vector<VectorField>& vectors);
  std::size_t frames() const { return series_.frames(); }

 private:
  vtk::Series series_;
};

// A PNG line plot of CSV columns (1-based column numbers) drawn by gnuplot.
// Returns false (and writes nothing) if gnuplot is not available: a missing
// plot never fails a run.
struct PlotSeries {
  int column;
  std::string title;
};
bool plot_csv(const std::string& csv, const std::string& png, int x_column,
              const std::vector<PlotSeries>& series, const std::string& title,
              const std::string& x_label, const std::string& y_label,
              const std::string& extra_commands = "");
// A map: points at (x, y) of a CSV coloured by a third column (pressure
// pictures), equal axis scales. Same rules as plot_csv.
bool plot_csv_map(const std::string& csv, const std::string& png, int x_column, int y_column, int value_column,
                  const std::string& title, const std::string& x_label, const std::string& y_label,
                  const std::string& value_label);

}  // namespace cosim

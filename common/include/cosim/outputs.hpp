#pragma once
// Run outputs: summary.json, CSV time series, VTK files for ParaView.
// Everything is flushed as it is written, so a run that fails keeps what it
// produced up to its last completed step.
#include <chrono>
#include <cstdint>
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
// second of wall time and when the writer is destroyed. `resume`: the file of
// a run being restarted, opened to append; it takes no rows (the restarted
// run's set-up repeats those of step 0) until truncate() has cut it back to
// its length at the checkpoint.
class CsvWriter {
 public:
  CsvWriter(const std::string& path, const std::vector<std::string>& columns, bool resume = false);
  ~CsvWriter();
  void row(const std::vector<double>& values);
  void flush();
  // Flushes and returns the file's length [bytes]: where a restart continues it.
  std::uint64_t length();
  // Flushes and cuts the file to `bytes` (rows after a checkpoint); the next rows follow on.
  void truncate(std::uint64_t bytes);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::size_t columns_;
  bool muted_ = false;  // resumed, not yet cut back to the checkpoint
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
  // The frames' times, and a restarted run's series taken back to those frames
  // (the index rewritten; frame files beyond them are overwritten as they come).
  std::vector<double> frame_times() const { return series_.times(); }
  void resume(const std::vector<double>& times) { series_.resume(times); }

 private:
  vtk::Series series_;
};

// PNG plots of CSV files, drawn by gnuplot (pngcairo terminal); the project's
// one gnuplot call. Every plot returns false (and writes nothing) if gnuplot is
// not on the PATH or fails: a missing plot never fails a run.
//
// One curve: `columns` is gnuplot's `using` spec ("1:4", "6:(abs($9)*100)",
// "1:2:($3/1000)"), `style` its `with` clause; the CSV's first row (the header)
// is skipped. An empty title draws the curve without a key entry.
struct PlotCurve {
  std::string csv;
  std::string columns;
  std::string style = "lines lw 2";
  std::string title;
};
struct PlotOptions {
  std::string title, x_label, y_label;
  int width_px = 900, height_px = 600;
  bool log_x = false, log_y = false;
  bool equal_axes = false;   // one metre is as long on x as on y
  std::string colour_label;  // non-empty: a colour bar for `palette` curves
  bool key = true;
  std::string extra_commands;  // gnuplot lines, each ending in "\n", before `plot`
};
bool plot_png(const std::string& png, const PlotOptions& options, const std::vector<PlotCurve>& curves);

// A line plot of CSV columns (1-based column numbers) against x_column.
struct PlotSeries {
  int column;
  std::string title;
};
bool plot_csv(const std::string& csv, const std::string& png, int x_column,
              const std::vector<PlotSeries>& series, const std::string& title,
              const std::string& x_label, const std::string& y_label,
              const std::string& extra_commands = "");
// A stacked plot of CSV columns against x_column: each of `stacked` filled, in
// a colour of its own, between the sum of the columns before it and the sum
// with it (where a total goes, term by term); `lines` drawn over them. Same
// rules as plot_csv.
bool plot_csv_stacked(const std::string& csv, const std::string& png, int x_column,
                      const std::vector<PlotSeries>& stacked, const std::vector<PlotSeries>& lines,
                      const std::string& title, const std::string& x_label, const std::string& y_label);
// A map: points at (x, y) of a CSV coloured by a third column (pressure
// pictures), equal axis scales. Same rules as plot_csv.
bool plot_csv_map(const std::string& csv, const std::string& png, int x_column, int y_column, int value_column,
                  const std::string& title, const std::string& x_label, const std::string& y_label,
                  const std::string& value_label);

}  // namespace cosim

#pragma once
// The one legacy VTK writer of the project: SPH particle frames (POLYDATA point
// clouds) and the tyre's meshes (UNSTRUCTURED_GRID of quads and hexahedra) are
// both written through it, and ParaView's ".vtk.series" index beside them.
//
// Format: "Simple Legacy Formats" in the VTK file-format document
// (https://docs.vtk.org/en/latest/vtk_file_formats/vtk_legacy_file_format.html,
// taken from the VTK User's Guide, Kitware). A file is five parts: the line
// "# vtk DataFile Version 3.0", a title line (at most 256 characters), "ASCII" or
// "BINARY", the geometry ("DATASET POLYDATA" / "DATASET UNSTRUCTURED_GRID" with
// POINTS and VERTICES / CELLS + CELL_TYPES) and the attributes (POINT_DATA n /
// CELL_DATA n, each followed by SCALARS and VECTORS). Binary data follow the
// newline of their keyword line and are big-endian whatever the machine (the
// document's "Binary Files" section).
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace cosim::vtk {

// Big-endian encoders: append the value's bytes, most significant first.
void put_be_int32(std::string& out, std::int32_t value);
void put_be_float32(std::string& out, double value);  // rounded to float
void put_be_float64(std::string& out, double value);

// The data type of points and real-valued fields: "float" (4 bytes) or "double" (8).
enum class Real { Float32, Float64 };

// VTK cell type ids (vtkCellType.h; the guide's figure "Linear cell types").
enum class CellType : int { Quad = 9, Hexahedron = 12 };

// One legacy binary VTK file assembled in memory, section by section, in the
// order the format prescribes: points, then cells (vertices), then attributes.
// A POINT_DATA or CELL_DATA header is written before the first field of its
// kind (again when the kind changes). Field names must not contain blanks.
// Misuse (a wrong number of values, a blank in a name) throws cosim::Error.
class LegacyFile {
 public:
  static LegacyFile poly_data(const std::string& title, Real real);
  static LegacyFile unstructured_grid(const std::string& title, Real real);

  // POINTS from separate coordinate arrays of n values each.
  void points(std::size_t n, const double* x, const double* y, const double* z);
  // POLYDATA only: VERTICES, one single-point vertex per point.
  void vertices();
  // UNSTRUCTURED_GRID only: CELLS and CELL_TYPES, `nodes_per_cell` point ids
  // per cell in `connectivity` (all cells of one type).
  void cells(const std::vector<int>& connectivity, int nodes_per_cell, CellType type);

  enum class On { Points, Cells };
  // SCALARS name <float|double> 1, one value per point or cell.
  void scalars(On on, const std::string& name, const double* values);
  void scalars(On on, const std::string& name, const std::vector<double>& values);
  // SCALARS name int 1.
  void int_scalars(On on, const std::string& name, const std::vector<int>& values);
  // VECTORS name <float|double>, from separate component arrays ...
  void vectors(On on, const std::string& name, const double* x, const double* y, const double* z);
  // ... or interleaved (x0 y0 z0 x1 ...).
  void vectors(On on, const std::string& name, const std::vector<double>& xyz);

  std::size_t point_count() const { return n_points_; }
  std::size_t cell_count() const { return n_cells_; }
  const std::string& bytes() const { return out_; }
  // Writes "<path>.tmp" and renames it over path: a reader never sees half a file.
  void save(const std::string& path) const;

 private:
  LegacyFile(const std::string& title, const char* dataset, Real real);
  void put_real(double v);
  void begin(On on, const std::string& name, std::size_t values_per_entry, std::size_t values);
  std::size_t count(On on) const { return on == On::Points ? n_points_ : n_cells_; }

  std::string out_;
  Real real_;
  bool poly_data_;
  std::size_t n_points_ = 0, n_cells_ = 0;
  int section_ = 0;  // 0 none, 1 POINT_DATA, 2 CELL_DATA
};

// A ParaView ".vtk.series" index (JSON: {"file-series-version": "1.0",
// "files": [{"name": ..., "time": ...}]}, ParaView's reader vtkFileSeriesReader)
// and the numbered files it lists: folder/name_00000.vtk, name_00001.vtk, ...
class Series {
 public:
  Series(std::string folder, std::string name);
  // Saves the next frame, rewrites the index; returns the file name.
  std::string write(double time_s, const LegacyFile& file);
  std::size_t frames() const { return entries_.size(); }
  const std::string& name() const { return name_; }
  std::vector<double> times() const;
  // Takes the series back to frames 0 .. times.size() - 1 at these times (a restart).
  void resume(const std::vector<double>& times);

 private:
  std::string file_name(std::size_t frame) const;
  void write_index() const;
  std::string folder_, name_;
  std::vector<std::pair<std::string, double>> entries_;
};

}  // namespace cosim::vtk

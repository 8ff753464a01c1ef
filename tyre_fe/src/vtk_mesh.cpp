// Legacy VTK writers for tyre meshes. The legacy binary format stores every value
// big-endian, whatever the machine; points and fields are written as doubles.
#include "tyre_fe/vtk_mesh.hpp"

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "cosim/error.hpp"

namespace tyre_fe {
namespace {

constexpr int kVtkQuad = 9;
constexpr int kVtkHexahedron = 12;

void put_be32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFF));
}
void put_int(std::string& out, int v) { put_be32(out, static_cast<std::uint32_t>(v)); }
void put_double(std::string& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  for (int shift = 56; shift >= 0; shift -= 8) out.push_back(static_cast<char>((bits >> shift) & 0xFF));
}

// An unstructured grid being assembled in memory: points, cells of one type,
// then the attribute sections.
class VtkGrid {
 public:
  VtkGrid(const std::string& path, const std::string& title) : path_(path) {
    out_ = "# vtk DataFile Version 3.0\n" + title + "\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
  }

  void points(const std::vector<Eigen::Vector3d>& p) {
    out_ += "POINTS " + std::to_string(p.size()) + " double\n";
    for (const auto& x : p)
      for (int c = 0; c < 3; ++c) put_double(out_, x[c]);
    out_ += "\n";
    n_points_ = p.size();
  }

  template <size_t N>
  void cells(const std::vector<std::array<int, N>>& c, int vtk_type) {
    out_ += "CELLS " + std::to_string(c.size()) + " " + std::to_string(c.size() * (N + 1)) + "\n";
    for (const auto& cell : c) {
      put_int(out_, static_cast<int>(N));
      for (int n : cell) put_int(out_, n);
    }
    out_ += "\nCELL_TYPES " + std::to_string(c.size()) + "\n";
    for (size_t i = 0; i < c.size(); ++i) put_int(out_, vtk_type);
    out_ += "\n";
    n_cells_ = c.size();
  }

  void cell_ints(const std::string& name, const std::vector<int>& values) {
    begin_cell_data();
    out_ += "SCALARS " + name + " int 1\nLOOKUP_TABLE default\n";
    for (int v : values) put_int(out_, v);
    out_ += "\n";
  }

  void fields(const std::vector<VtkField>& f, bool cell_data) {
    for (const auto& field : f) {
      const size_t count = cell_data ? n_cells_ : n_points_;
      check(field, count);
      if (cell_data) begin_cell_data();
      else begin_point_data();
      if (field.components == 1) out_ += "SCALARS " + field.name + " double 1\nLOOKUP_TABLE default\n";
      else out_ += "VECTORS " + field.name + " double\n";
      for (double v : field.values) put_double(out_, v);
      out_ += "\n";
    }
  }

  // Writes "<path>.tmp", then renames it over the target.
  void save() const {
    const std::string tmp = path_ + ".tmp";
    {
      std::ofstream file(tmp, std::ios::binary);
      if (!file) throw cosim::Error("cannot write VTK file '" + tmp + "'");
      file.write(out_.data(), static_cast<std::streamsize>(out_.size()));
      if (!file) throw cosim::Error("error writing VTK file '" + tmp + "'");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path_, ec);
    if (ec) throw cosim::Error("cannot rename '" + tmp + "' to '" + path_ + "': " + ec.message());
  }

 private:
  void check(const VtkField& f, size_t count) const {
    if (f.name.empty() || f.name.find_first_of(" \t\n") != std::string::npos)
      throw cosim::Error("VTK file '" + path_ + "': field name '" + f.name + "' is empty or has blanks");
    if ((f.components != 1 && f.components != 3) || f.values.size() != count * f.components)
      throw cosim::Error("VTK file '" + path_ + "': field '" + f.name + "' has " +
                         std::to_string(f.values.size()) + " values for " + std::to_string(count) +
                         " entries of " + std::to_string(f.components) + " component(s) (1 or 3)");
  }
  void begin_cell_data() {
    if (!in_cell_data_) out_ += "CELL_DATA " + std::to_string(n_cells_) + "\n";
    in_cell_data_ = true;
    in_point_data_ = false;
  }
  void begin_point_data() {
    if (!in_point_data_) out_ += "POINT_DATA " + std::to_string(n_points_) + "\n";
    in_point_data_ = true;
    in_cell_data_ = false;
  }

  std::string path_;
  std::string out_;
  size_t n_points_ = 0, n_cells_ = 0;
  bool in_cell_data_ = false, in_point_data_ = false;
};

std::vector<int> region_ids(const std::vector<Region>& r) {
  std::vector<int> out;
  for (Region x : r) out.push_back(static_cast<int>(x));
  return out;
}

}  // namespace

void write_vtk_cross_section(const std::string& path, const CrossSection& section,
                             const std::vector<Eigen::Vector2d>& positions,
                             const std::vector<VtkField>& point_fields,
                             const std::vector<VtkField>& cell_fields) {
  const auto& x = positions.empty() ? section.nodes : positions;
  if (x.size() != section.nodes.size())
    throw cosim::Error("VTK file '" + path + "': " + std::to_string(x.size()) + " positions for " +
                       std::to_string(section.nodes.size()) + " nodes");
  std::vector<Eigen::Vector3d> p;
  for (const auto& ry : x) p.emplace_back(0.0, ry.y(), ry.x());
  VtkGrid grid(path, "tyre_fe cross-section (x, y, z) = (0, y, r)");
  grid.points(p);
  grid.cells(section.quads, kVtkQuad);
  grid.cell_ints("region", region_ids(section.quad_region));
  grid.fields(cell_fields, true);
  grid.fields(point_fields, false);
  grid.save();
}

void write_vtk_mesh(const std::string& path, const Mesh3D& mesh,
                    const std::vector<Eigen::Vector3d>& positions,
                    const std::vector<VtkField>& point_fields,
                    const std::vector<VtkField>& cell_fields) {
  if (positions.size() != mesh.nodes.size())
    throw cosim::Error("VTK file '" + path + "': " + std::to_string(positions.size()) +
                       " positions for " + std::to_string(mesh.nodes.size()) + " nodes");
  VtkGrid grid(path, "tyre_fe 3D mesh");
  grid.points(positions);
  grid.cells(mesh.hexes, kVtkHexahedron);
  grid.cell_ints("region", region_ids(mesh.hex_region));
  grid.fields(cell_fields, true);
  grid.fields(point_fields, false);
  grid.save();
}

void write_vtk_facets(const std::string& path, const Mesh3D& mesh,
                      const std::vector<Eigen::Vector3d>& positions,
                      const std::vector<VtkField>& facet_fields) {
  if (positions.size() != mesh.nodes.size())
    throw cosim::Error("VTK file '" + path + "': " + std::to_string(positions.size()) +
                       " positions for " + std::to_string(mesh.nodes.size()) + " nodes");
  std::vector<int> local(mesh.nodes.size(), -1);
  std::vector<Eigen::Vector3d> p;
  std::vector<std::array<int, 4>> quads;
  std::vector<int> tags, hexes;
  for (const auto& f : mesh.facets) {
    std::array<int, 4> q;
    for (int a = 0; a < 4; ++a) {
      int& id = local[f.nodes[a]];
      if (id < 0) {
        id = static_cast<int>(p.size());
        p.push_back(positions[f.nodes[a]]);
      }
      q[a] = id;
    }
    quads.push_back(q);
    tags.push_back(static_cast<int>(f.tag));
    hexes.push_back(f.hex);
  }
  VtkGrid grid(path, "tyre_fe boundary facets");
  grid.points(p);
  grid.cells(quads, kVtkQuad);
  grid.cell_ints("surface_tag", tags);
  grid.cell_ints("hex", hexes);
  grid.fields(facet_fields, true);
  grid.save();
}

}  // namespace tyre_fe

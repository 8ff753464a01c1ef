// Legacy VTK files of tyre meshes, through the project's one VTK writer
// (cosim/vtk.hpp): unstructured grids of quads and hexahedra, points and fields
// as doubles (big-endian, as the legacy binary format stores every value).
#include "tyre_fe/vtk_mesh.hpp"

#include <array>

#include "cosim/error.hpp"

namespace tyre_fe {
namespace {

using cosim::vtk::CellType;
using cosim::vtk::LegacyFile;
using On = LegacyFile::On;

cosim::vtk::LegacyFile grid(const std::string& title, const std::vector<Eigen::Vector3d>& p) {
  auto file = LegacyFile::unstructured_grid(title, cosim::vtk::Real::Float64);
  std::vector<double> x(p.size()), y(p.size()), z(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x[i] = p[i].x(), y[i] = p[i].y(), z[i] = p[i].z();
  file.points(p.size(), x.data(), y.data(), z.data());
  return file;
}

template <std::size_t N>
std::vector<int> connectivity(const std::vector<std::array<int, N>>& cells) {
  std::vector<int> ids;
  ids.reserve(N * cells.size());
  for (const auto& c : cells) ids.insert(ids.end(), c.begin(), c.end());
  return ids;
}

void add_fields(LegacyFile& file, On on, const std::vector<VtkField>& fields) {
  for (const auto& f : fields) {
    if (f.components == 1) file.scalars(on, f.name, f.values);
    else if (f.components == 3) file.vectors(on, f.name, f.values);
    else throw cosim::Error("VTK field '" + f.name + "' has " + std::to_string(f.components) +
                            " components (1 or 3)");
  }
}

std::vector<int> region_ids(const std::vector<Region>& r) {
  std::vector<int> out;
  for (Region x : r) out.push_back(static_cast<int>(x));
  return out;
}

// A grid of one cell type with each cell's Region ("region") and the given fields.
template <std::size_t N>
LegacyFile region_grid(const std::string& title, const std::vector<Eigen::Vector3d>& p,
                       const std::vector<std::array<int, N>>& cells, CellType type, const std::vector<Region>& regions,
                       const std::vector<VtkField>& point_fields, const std::vector<VtkField>& cell_fields) {
  auto file = grid(title, p);
  file.cells(connectivity(cells), static_cast<int>(N), type);
  file.int_scalars(On::Cells, "region", region_ids(regions));
  add_fields(file, On::Cells, cell_fields);
  add_fields(file, On::Points, point_fields);
  return file;
}

void check_positions(const std::string& what, std::size_t positions, std::size_t nodes) {
  if (positions != nodes)
    throw cosim::Error("VTK file '" + what + "': " + std::to_string(positions) + " positions for " +
                       std::to_string(nodes) + " nodes");
}

// Saves a file built by `build`, naming the path in any error.
template <class Build>
void save(const std::string& path, Build build) {
  LegacyFile file = [&] {
    try {
      return build();
    } catch (const cosim::Error& e) {
      throw cosim::Error("VTK file '" + path + "': " + e.what());
    }
  }();
  file.save(path);
}

}  // namespace

cosim::vtk::LegacyFile vtk_cross_section(const CrossSection& section, const std::vector<Eigen::Vector2d>& positions,
                                         const std::vector<VtkField>& point_fields,
                                         const std::vector<VtkField>& cell_fields) {
  const auto& x = positions.empty() ? section.nodes : positions;
  check_positions("cross-section", x.size(), section.nodes.size());
  std::vector<Eigen::Vector3d> p;
  for (const auto& ry : x) p.emplace_back(0.0, ry.y(), ry.x());
  return region_grid("tyre_fe cross-section (x, y, z) = (0, y, r)", p, section.quads, CellType::Quad,
                     section.quad_region, point_fields, cell_fields);
}

cosim::vtk::LegacyFile vtk_mesh(const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions,
                                const std::vector<VtkField>& point_fields,
                                const std::vector<VtkField>& cell_fields) {
  check_positions("3D mesh", positions.size(), mesh.nodes.size());
  return region_grid("tyre_fe 3D mesh", positions, mesh.hexes, CellType::Hexahedron, mesh.hex_region,
                     point_fields, cell_fields);
}

cosim::vtk::LegacyFile vtk_facets(const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions,
                                  const std::vector<VtkField>& facet_fields) {
  check_positions("boundary facets", positions.size(), mesh.nodes.size());
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
  auto file = grid("tyre_fe boundary facets", p);
  file.cells(connectivity(quads), 4, CellType::Quad);
  file.int_scalars(On::Cells, "surface_tag", tags);
  file.int_scalars(On::Cells, "hex", hexes);
  add_fields(file, On::Cells, facet_fields);
  return file;
}

void write_vtk_cross_section(const std::string& path, const CrossSection& section,
                             const std::vector<Eigen::Vector2d>& positions,
                             const std::vector<VtkField>& point_fields,
                             const std::vector<VtkField>& cell_fields) {
  save(path, [&] { return vtk_cross_section(section, positions, point_fields, cell_fields); });
}

void write_vtk_mesh(const std::string& path, const Mesh3D& mesh,
                    const std::vector<Eigen::Vector3d>& positions,
                    const std::vector<VtkField>& point_fields,
                    const std::vector<VtkField>& cell_fields) {
  save(path, [&] { return vtk_mesh(mesh, positions, point_fields, cell_fields); });
}

void write_vtk_facets(const std::string& path, const Mesh3D& mesh,
                      const std::vector<Eigen::Vector3d>& positions,
                      const std::vector<VtkField>& facet_fields) {
  save(path, [&] { return vtk_facets(mesh, positions, facet_fields); });
}

}  // namespace tyre_fe

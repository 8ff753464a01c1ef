#pragma once
// Legacy VTK (binary, big-endian) output of tyre meshes for ParaView/VisIt:
// the cross-section, the 3D hex mesh and its tagged boundary facets, built with
// the project's one VTK writer (cosim/vtk.hpp). The vtk_* functions return the
// file (for a cosim::vtk::Series of frames); the write_vtk_* ones save it.
//
// Every writer writes to "<path>.tmp" and renames it over <path> when complete,
// so a reader never sees a half-written file; failures throw cosim::Error naming
// the file. Field names must not contain blanks (a VTK restriction).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cosim/vtk.hpp"
#include "tyre_fe/mesh.hpp"

namespace tyre_fe {

// A named output field: `components` (1: scalar, 3: vector) values per point,
// cell or facet, interleaved (x0 y0 z0 x1 ...).
struct VtkField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

cosim::vtk::LegacyFile vtk_cross_section(const CrossSection& section,
                                         const std::vector<Eigen::Vector2d>& positions = {},
                                         const std::vector<VtkField>& point_fields = {},
                                         const std::vector<VtkField>& cell_fields = {});
cosim::vtk::LegacyFile vtk_mesh(const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions,
                                const std::vector<VtkField>& point_fields = {},
                                const std::vector<VtkField>& cell_fields = {});
cosim::vtk::LegacyFile vtk_facets(const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions,
                                  const std::vector<VtkField>& facet_fields = {});

// The cross-section as VTK_QUAD cells. Points are placed in the wheel frame's
// theta = 0 half plane, (x, y, z) = (0, y, r), so that the section overlays the 3D
// mesh. Cell data: "region" (Region as int) and `cell_fields`; point data:
// `point_fields` (vectors given in (r, y) are the caller's to convert, e.g. as
// (0, u_y, u_r)). `positions`: current (r, y) of the nodes; empty: the reference.
void write_vtk_cross_section(const std::string& path, const CrossSection& section,
                             const std::vector<Eigen::Vector2d>& positions = {},
                             const std::vector<VtkField>& point_fields = {},
                             const std::vector<VtkField>& cell_fields = {});

// The 3D mesh as VTK_HEXAHEDRON cells at the given node positions (e.g. the
// deformed ones; mesh.nodes for the reference). Cell data: "region" and
// `cell_fields`; point data: `point_fields`.
void write_vtk_mesh(const std::string& path, const Mesh3D& mesh,
                    const std::vector<Eigen::Vector3d>& positions,
                    const std::vector<VtkField>& point_fields = {},
                    const std::vector<VtkField>& cell_fields = {});

// The tagged boundary facets as VTK_QUAD cells (only the nodes they use are
// written). Cell data: "surface_tag" (SurfaceTag as int), "hex" (owning hex) and
// `facet_fields` (one value or vector per facet, e.g. contact pressure).
void write_vtk_facets(const std::string& path, const Mesh3D& mesh,
                      const std::vector<Eigen::Vector3d>& positions,
                      const std::vector<VtkField>& facet_fields = {});

}  // namespace tyre_fe

#pragma once
// Outputs of a tyre run besides summary.json and tyre.csv: VTK files of the
// meshes and of the deforming 3D model (with a .vtk.series index for ParaView),
// the footprint (contact pressure per node, CSV and PNG), and PNG plots.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cosim/checkpoint.hpp"
#include "cosim/vtk.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/solver3d.hpp"
#include "tyre_fe/terrain_port.hpp"

namespace tyre_fe {

void write_cross_section_vtk(const std::string& path, const CrossSection& section,
                             const std::vector<Eigen::Vector2d>& positions);
void write_mesh_vtk(const std::string& path, const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions);
void write_facets_vtk(const std::string& path, const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions);

// Frames of the 3D model every `interval_s` of simulated time (0: none):
// BODY_NNNNN.vtk (hexahedra; displacement, velocity) and surface_NNNNN.vtk
// (tagged facets; contact pressure), indexed by BODY.vtk.series / surface.vtk.series;
// BODY is "tyre" or "tread_block".
class FrameWriter {
 public:
  FrameWriter(std::string folder, double interval_s, const std::string& body = "tyre");
  void maybe_write(const Model3d& model, const State3d& s);
  void write(const Model3d& model, const State3d& s);
  // The frames written and the next frame's time, for a restart (docs/reliability.md).
  void save(cosim::CheckpointWriter& out) const;
  void restore(const cosim::CheckpointReader& in);

 private:
  double interval_s_, next_s_ = 0.0;
  double last_written_s_ = -1.0;
  cosim::vtk::Series body_frames_, surface_frames_;
};

// Contact pressure per contact node [Pa] = normal force / tributary area.
std::vector<double> contact_pressure_Pa(const Model3d& model, const State3d& s);

// Contact pressure per mesh facet [Pa]: the mean of its four nodes' road
// pressure, plus the terrain's pressure on the facets it reports in a coupled
// run (surface facet -> mesh facet through surface.mesh_facets).
std::vector<double> facet_contact_pressure_Pa(const Mesh3D& mesh, const std::vector<double>& nodal_road_pressure_Pa,
                                              const ContactSurfaceDef& surface, const cosim::SurfaceLoads& loads);

// footprint.csv (x, y, contact pressure of the nodes in contact) and
// footprint.png; returns the largest nodal contact pressure [Pa].
double write_footprint(const std::string& folder, const Model3d& model, const State3d& s);

// PNG plots of tyre.csv (rim height, road forces, energies); never fails a run.
void write_plots(const std::string& folder);

}  // namespace tyre_fe

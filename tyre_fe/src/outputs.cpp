#include "tyre_fe/outputs.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "tyre_fe/vtk_mesh.hpp"

namespace tyre_fe {
namespace {

std::vector<Eigen::Vector3d> positions_of(const State3d& s) {
  std::vector<Eigen::Vector3d> x(s.x.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = Eigen::Vector3d(s.x[i], s.y[i], s.z[i]);
  return x;
}

}  // namespace

static VtkField facet_pressure(const Model3d& model, const State3d& s) {
  return {"contact_pressure_Pa", 1,
          facet_contact_pressure_Pa(model.mesh, contact_pressure_Pa(model, s), s.terrain.surface, s.terrain.loads)};
}

std::vector<double> facet_contact_pressure_Pa(const Mesh3D& mesh, const std::vector<double>& nodal_road_pressure_Pa,
                                              const ContactSurfaceDef& surface, const cosim::SurfaceLoads& loads) {
  const auto& p = nodal_road_pressure_Pa;
  std::vector<double> facet_p;
  facet_p.reserve(mesh.facets.size());
  for (const auto& facet : mesh.facets)
    facet_p.push_back(0.25 * (p[facet.nodes[0]] + p[facet.nodes[1]] + p[facet.nodes[2]] + p[facet.nodes[3]]));
  for (std::size_t k = 0; k < loads.facets.size() && k < loads.pressure_Pa.size(); ++k)
    facet_p[surface.mesh_facets.at(loads.facets[k])] += loads.pressure_Pa[k];
  return facet_p;
}

void write_cross_section_vtk(const std::string& path, const CrossSection& section,
                             const std::vector<Eigen::Vector2d>& positions) {
  VtkField displacement{"displacement_m", 3, {}};
  for (std::size_t i = 0; i < section.nodes.size(); ++i) {
    const Eigen::Vector2d u = positions[i] - section.nodes[i];
    displacement.values.insert(displacement.values.end(), {0.0, u[1], u[0]});  // (x, y, z) = (0, y, r)
  }
  write_vtk_cross_section(path, section, positions, {displacement});
}

void write_mesh_vtk(const std::string& path, const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions) {
  write_vtk_mesh(path, mesh, positions);
}

void write_facets_vtk(const std::string& path, const Mesh3D& mesh, const std::vector<Eigen::Vector3d>& positions) {
  write_vtk_facets(path, mesh, positions);
}

std::vector<double> contact_pressure_Pa(const Model3d& model, const State3d& s) {
  std::vector<double> p(s.x.size(), 0.0);
  if (!s.road.present) return p;
  for (std::size_t c = 0; c < model.contact_nodes.size(); ++c)
    if (s.road.normal_force_N[c] > 0.0 && model.contact_node_area_m2[c] > 0.0)
      p[model.contact_nodes[c]] = s.road.normal_force_N[c] / model.contact_node_area_m2[c];
  return p;
}

FrameWriter::FrameWriter(std::string folder, double interval_s, const std::string& body)
    : interval_s_(interval_s), body_frames_(folder, body), surface_frames_(folder, "surface") {}

void FrameWriter::maybe_write(const Model3d& model, const State3d& s) {
  if (interval_s_ <= 0.0 || s.time_s < next_s_) return;
  write(model, s);
  next_s_ = s.time_s + interval_s_;
}

void FrameWriter::save(cosim::CheckpointWriter& out) const {
  out.put("frames.clock", std::vector<double>{next_s_, last_written_s_});
  out.put("frames.body_times", body_frames_.times());
  out.put("frames.surface_times", surface_frames_.times());
}

void FrameWriter::restore(const cosim::CheckpointReader& in) {
  const auto clock = in.get<double>("frames.clock", 2);
  next_s_ = clock[0], last_written_s_ = clock[1];
  body_frames_.resume(in.get<double>("frames.body_times"));
  surface_frames_.resume(in.get<double>("frames.surface_times"));
}

void FrameWriter::write(const Model3d& model, const State3d& s) {
  if (interval_s_ <= 0.0 || s.time_s == last_written_s_) return;
  last_written_s_ = s.time_s;
  const auto x = positions_of(s);
  VtkField displacement{"displacement_m", 3, {}}, velocity{"velocity_m_per_s", 3, {}};
  displacement.values.reserve(3 * x.size()), velocity.values.reserve(3 * x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Eigen::Vector3d u = x[i] - model.mesh.nodes[i];
    displacement.values.insert(displacement.values.end(), {u.x(), u.y(), u.z()});
    velocity.values.insert(velocity.values.end(), {s.vx[i], s.vy[i], s.vz[i]});
  }
  body_frames_.write(s.time_s, vtk_mesh(model.mesh, x, {displacement, velocity}));
  surface_frames_.write(s.time_s, vtk_facets(model.mesh, x, {facet_pressure(model, s)}));
}

double write_footprint(const std::string& folder, const Model3d& model, const State3d& s) {
  const std::vector<double> p = contact_pressure_Pa(model, s);
  const std::string csv = folder + "/footprint.csv";
  double largest = 0.0;
  {
    std::ofstream out(csv);
    if (!out) throw cosim::Error(csv + ": cannot write");
    out << "x_m,y_m,contact_pressure_Pa\n" << std::setprecision(9);
    for (int n : model.contact_nodes) {
      if (!(p[n] > 0.0)) continue;
      out << s.x[n] - s.rim.x << "," << s.y[n] << "," << p[n] << "\n";
      largest = std::max(largest, p[n]);
    }
  }
  cosim::PlotOptions o;
  o.title = "Footprint: contact pressure [kPa] (x forward, y left)";
  o.x_label = "x [m]", o.y_label = "y [m]", o.colour_label = "kPa";
  o.height_px = 700, o.equal_axes = true;
  cosim::plot_png(folder + "/footprint.png", o, {{csv, "1:2:($3/1000)", "points pt 5 ps 1.6 palette", ""}});
  return largest;
}

void write_plots(const std::string& folder) {
  const std::string csv = folder + "/tyre.csv";
  cosim::plot_csv(csv, folder + "/rim_height.png", 1, {{4, "rim z"}}, "Rim node height", "time [s]", "z [m]");
  cosim::plot_csv(csv, folder + "/road_forces.png", 1,
                  {{11, "road force x"}, {13, "road force z"}, {9, "rim vertical force"}},
                  "Road contact forces", "time [s]", "force [N]");
  cosim::plot_csv(csv, folder + "/energies.png", 1,
                  {{15, "kinetic"}, {16, "internal"}, {17, "hourglass"}, {18, "external work"}},
                  "Energies", "time [s]", "energy [J]");
}

}  // namespace tyre_fe

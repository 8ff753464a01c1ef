// What the SPH terrain's run writes as it goes (sph_run.hpp, docs/outputs.md):
// the CSV series' rows, the VTK frames, the rut's CSV and the plots.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "snow_sph/energy_split.hpp"
#include "snow_sph/scene.hpp"
#include "sph_run.hpp"

namespace snow_sph {
namespace {

// A length for a plot's title, in mm to a tenth: the cell centre through
// y = 0 is 1e-17 m away from it by rounding, which the title need not say.
std::string title_mm(double length_m) {
  double mm = std::round(length_m * 1e4) / 10.0;
  if (mm == 0.0) mm = 0.0;  // no "-0.0"
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", mm);
  return text;
}

// The rut's map (lowering in mm) and, if the grid spans y = 0, the top surface
// along x in the row of cells through y = 0, at step 0 and now. Listed under
// summary "plots" when drawn.
void plot_rut(cosim::RunRecord& record, const std::string& scene, const RutGrid& grid) {
  const std::string csv = record.path("rut_surface.csv");
  cosim::PlotOptions map;
  map.title = scene + ": lowering of the top particle centres [mm]";
  map.x_label = "x [m]", map.y_label = "y [m]", map.colour_label = "mm";
  // Equal scales unless the terrain is a slice (a plane-strain strip), where
  // they would draw a line; its rut is read from the profile.
  map.height_px = 700, map.equal_axes = 5 * std::min(grid.nx, grid.ny) >= std::max(grid.nx, grid.ny);
  if (cosim::plot_png(record.path("rut_surface.png"), map, {{csv, "1:2:($4*1000)", "points pt 5 ps 1.2 palette", ""}}))
    record.summary()["plots"].push_back("rut_surface.png");
  const double rows = std::floor(-grid.y0_m / grid.cell_m);
  if (!(rows >= 0 && rows < static_cast<double>(grid.ny))) return;
  // The row's cells by their centre's y, within a quarter cell (the CSV's 10 digits).
  const double row_y_m = grid.centre_y_m(static_cast<std::size_t>(rows));
  const std::string y = cosim::number_text(row_y_m);
  const std::string near = "abs($2 - (" + y + ")) < " + cosim::number_text(0.25 * grid.cell_m);
  cosim::PlotOptions profile;
  profile.title = scene + ": top particle centres along x at y = " + title_mm(row_y_m) + " mm";
  profile.x_label = "x [m]", profile.y_label = "z [mm]";
  profile.extra_commands = "set key bottom right\n";  // the undisturbed top runs along the upper edge
  if (cosim::plot_png(record.path("rut_profile.png"), profile,
                      {{csv, "1:(" + near + " ? ($3 + $4)*1000 : 1/0)", "lines lw 2", "step 0"},
                       {csv, "1:(" + near + " ? $3*1000 : 1/0)", "lines lw 2", "end of run"}}))
    record.summary()["plots"].push_back("rut_profile.png");
}

}  // namespace

double surge_front(const Model& m) {
  const Particles& p = m.particles;
  double front = -1e300;
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (m.materials[p.material[i]].kind == MaterialModel::Kind::water && p.neighbour_count[i] >= 4)
      front = std::max(front, p.x[i]);
  return front + 0.5 * m.settings.spacing - m.container_min[0];
}

void write_rut_csv(const std::string& path, const RutGrid& grid, const RutSurface& rut) {
  cosim::CsvWriter csv(path, {"x_m", "y_m", "top_z_m", "lowering_m"});
  for (std::size_t j = 0; j < grid.ny; ++j)
    for (std::size_t i = 0; i < grid.nx; ++i) {
      const std::size_t c = i + grid.nx * j;
      if (!std::isnan(rut.lowering_m[c]))
        csv.row({grid.centre_x_m(i), grid.centre_y_m(j), rut.top_z_m[c], rut.lowering_m[c]});
    }
}

// The series every run writes (energy) and those its scene asks for (bodies,
// surge front, floor pressure, VTK frames); the coupled run's contact series
// is opened when it joins.
void SphRun::open_series(cosim::RunRecord& record) {
  const Model& model = *model_;
  energy_columns_ = {"time_s",
                     "kinetic_J",
                     "internal_J",
                     "elastic_stored_J",
                     "plastic_dissipation_J",
                     "viscous_dissipation_J",
                     "contact_dissipation_J",
                     "external_work_J",
                     "energy_relative_error"};
  for (const EnergyValue& v : energy_split(EnergyBalance{})) energy_columns_.push_back(v.key);  // the split's
  energy_csv_ = &record.series("energy.csv", energy_columns_);
  if (!model.bodies.empty()) {
    std::vector<std::string> cols{"time_s"};
    for (const auto& b : model.bodies)
      for (const char* c : {"_z_m", "_displacement_m", "_velocity_z_m_per_s", "_contact_force_z_N",
                            "_applied_force_z_N"})
        cols.push_back(b.name + c);
    bodies_csv_ = &record.series("bodies.csv", cols);
  }
  const auto& sph = scene_.sph();
  if (sph.probes().surge_front()) front_csv_ = &record.series("front.csv", {"time_s", "front_m"});
  if (sph.probes().floor_pressure())
    probe_csv_ = &record.series("floor_pressure.csv", {"time_s", "floor_pressure_Pa"});
  if (vtk_interval_ > 0) vtk_ = std::make_unique<cosim::VtkSeries>(record.path("vtk"), "particles");
}

void SphRun::output(cosim::RunRecord&) {
  record_rows(false);
  if (probe_csv_) {
    const double pr = solver_->pressure_at(floor_x_, floor_y_, model_->container_min[2]);
    if ((solver_->steps() & 63u) == 0) probe_csv_->row({solver_->time(), pr});
    if (solver_->time() >= probe_from_) probe_sum_ += pr * last_dt_, probe_time_ += last_dt_;
  }
  if (vtk_ && solver_->time() + 1e-12 >= next_vtk_) write_frame(), next_vtk_ += vtk_interval_;
}

void SphRun::write_frame() {
  const Particles& p = model_->particles;
  const std::size_t n = p.n_real;
  std::vector<double> id(p.id.begin(), p.id.begin() + n), mat(n), von_mises(n), cap_pressure(n);
  for (std::size_t i = 0; i < n; ++i) {
    mat[i] = p.material[i];
    von_mises[i] = von_mises_stress_Pa(p, i);
    // The cap's hydrostatic yield pressure p_b(eps_vol_pl): how far the snow has
    // been compacted (Abaqus 23.3.2); 0 for water.
    const MaterialModel& material = model_->materials[p.material[i]];
    cap_pressure[i] = material.kind == MaterialModel::Kind::snow
                          ? material.mdpc.cap_hydrostatic_yield_Pa(p.eps_vol_pl[i]) : 0.0;
  }
  vtk_->write(solver_->time(), n, p.x.data(), p.y.data(), p.z.data(),
              {{"density_kg_per_m3", p.density.data()},
               {"pressure_Pa", p.pressure.data()},
               {"von_mises_stress_Pa", von_mises.data()},
               {"volumetric_plastic_strain", p.eps_vol_pl.data()},
               {"cap_hydrostatic_yield_pressure_Pa", cap_pressure.data()},
               {"material", mat.data()},
               {"id", id.data()}},
              {{"velocity_m_per_s", p.vx.data(), p.vy.data(), p.vz.data()}});
}

void SphRun::record_rows(bool force) {
  if (!energy_csv_) return;
  const double t = solver_->time();
  if (!force && t + 1e-15 < next_csv_) return;
  next_csv_ = t + csv_interval_;
  const EnergyBalance& e = solver_->energy();
  std::vector<double> energy_row{t,
                                 e.kinetic,
                                 e.internal,
                                 e.elastic,
                                 e.plastic_dissipation,
                                 e.viscous_dissipation,
                                 e.contact_dissipation,
                                 e.external_work,
                                 e.relative_error()};
  for (const EnergyValue& v : energy_split(e)) energy_row.push_back(v.value);
  energy_csv_->row(energy_row);
  if (bodies_csv_) {
    std::vector<double> row{t};
    for (const auto& b : model_->bodies)
      row.insert(row.end(), {b.z, b.z0 - b.z, b.vz, b.contact_force_z_domain * b.symmetry_factor,
                             b.applied_force_z_now(t)});
    bodies_csv_->row(row);
  }
  if (front_csv_) front_csv_->row({t, surge_front(*model_)});
  if (contact_csv_) {
    const SurfaceContactResult& l = solver_->surface_loads();
    double area = 0.0, in_contact = 0.0;
    for (double a : l.facet_contact_area_m2) area += a;
    for (auto c : l.particles_in_contact) in_contact += c;
    contact_csv_->row({t, l.total_fx_N, l.total_fy_N, l.total_fz_N, area, in_contact,
                       static_cast<double>(solver_->drained_particles()), l.max_penetration_m, l.deepest_x_m,
                       l.deepest_z_m, static_cast<double>(l.deepest_facet),
                       static_cast<double>(l.particles_behind_surface), l.particle_reach_z_m});
  }
}

// Where the work went over time: the split's terms stacked (those not 0 at
// the end), the work done on the terrain as a line over them; the gap
// between the two is the balance.
void SphRun::plot_energy_split(cosim::RunRecord& record, const std::string& name) {
  const nlohmann::json energy = record.summary().value("energy", nlohmann::json::object());
  auto column = [&](const char* key) {
    const auto at = std::find(energy_columns_.begin(), energy_columns_.end(), key);
    return static_cast<int>(at - energy_columns_.begin()) + 1;
  };
  const cosim::EnergySplit& split = terrain_energy_split();
  std::vector<cosim::PlotSeries> stacked;
  for (const cosim::EnergyTerm& t : split.went_to)
    if (energy.contains(t.key) && energy[t.key].is_number() && energy[t.key].get<double>() != 0.0)
      stacked.push_back({column(t.key), t.label});
  if (stacked.empty()) return;
  record.plot_stacked("energy.csv", "energy_split.png", 1, stacked,
                      {{column(split.total.key), "work done on the terrain"}},
                      name + ": where the work done on the terrain went", "time [s]", "energy [J]");
}

void SphRun::plots(cosim::RunRecord& record) {
  if (!energy_csv_) return;
  const std::string name = scene_.name();
  if (surface_port_ && record.results().contains("rut_depth_m")) plot_rut(record, name, rut_grid_);
  record.plot("energy.csv", "energy.png", 1, {{2, "kinetic"}, {3, "internal"}, {6, "viscous"}, {8, "external work"}},
              name + ": energy", "time [s]", "energy [J]");
  plot_energy_split(record, name);
  if (bodies_csv_)
    record.plot("bodies.csv", "bodies.png", 1, {{3, model_->bodies[0].name + " displacement"}},
                name + ": " + model_->bodies[0].name + " displacement", "time [s]", "displacement [m]");
  if (front_csv_)
    record.plot("front.csv", "front.png", 1, {{2, "surge front"}}, name + ": surge front", "time [s]",
                "front position [m]");
  if (probe_csv_)
    record.plot("floor_pressure.csv", "floor_pressure.png", 1, {{2, "floor pressure"}}, name + ": floor pressure",
                "time [s]", "pressure [Pa]");
}

}  // namespace snow_sph

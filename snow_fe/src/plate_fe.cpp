// The plate-sinkage test on an axisymmetric Lagrangian mesh; see plate_fe.hpp.
#include "snow_fe/plate_fe.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "cosim/error.hpp"
#include "cosim/interrupt.hpp"
#include "cosim/outputs.hpp"
#include "cosim/progress.hpp"
#include "cosim/ramp.hpp"
#include "snow_fe/axisym_fe.hpp"
#include "snow_sph/scene.hpp"

namespace snow_fe {
namespace {

namespace fe = axisym;
// The snow's material and its layer at rest are the SPH scene's (snow_sph/scene.hpp).
using snow_sph::ConfinedLayerState;
using snow_sph::MaterialModel;
using snow_sph::confined_layer_state;
using snow_sph::material_from_scene;
constexpr double kTwoPi = 6.283185307179586;

// n equal intervals from a to b, n = max(1, round((b - a) / h)); appends the end points after `lines`' last.
void add_lines(std::vector<double>& lines, double a, double b, double h) {
  const int n = std::max(1, static_cast<int>(std::lround((b - a) / h)));
  if (lines.empty()) lines.push_back(a);
  for (int k = 1; k <= n; ++k) lines.push_back(a + (b - a) * k / n);
}

// The applied load on a loaded plate at the given time (ramped in smoothly).
double applied_force_N(const PlateFeSetup& s, double time) {
  return cosim::ramp(cosim::RampCurve::smootherstep, time, s.load_ramp_time_s, s.applied_force_N);
}

cosim::CsvWriter open_plate_csv(const std::string& out) {
  return cosim::CsvWriter(out + "/plate.csv",
                          {"time_s", "plate_displacement_m", "plate_velocity_z_m_per_s", "snow_force_on_plate_N",
                           "applied_force_N", "kinetic_energy_J", "elastic_energy_J", "plastic_work_J",
                           "external_work_J", "energy_balance_error_J", "smallest_jacobian_ratio"});
}

// The run's state that a row of plate.csv reports.
struct PlateRow {
  double t, plate_z, plate_v, snow_force, plastic_work, plate_drive_work, smallest_ratio;
};

// One row of plate.csv with the energy balance of the whole revolved model.
void write_plate_row(cosim::CsvWriter& csv, const PlateFeSetup& s, const fe::Mesh& mesh,
                     const std::vector<double>& z_reference, double elastic0, double plate_mass, const PlateRow& r) {
  const bool prescribed = s.prescribed_speed_m_per_s > 0.0;
  const double g = s.gravity_m_per_s2, H = s.slab_depth_m;
  const auto n = static_cast<std::size_t>(mesh.nodes());
  const double t = r.t, plate_z = r.plate_z, plate_v = r.plate_v, snow_force = r.snow_force;
  const double plastic_work = r.plastic_work, plate_drive_work = r.plate_drive_work, smallest_ratio = r.smallest_ratio;
  // A driven plate is outside the system (its drive's work is external); a loaded one is inside.
  const double plate_inside = prescribed ? 0.0 : 1.0;
  const double kinetic =
      kTwoPi * (fe::kinetic_energy_J_per_rad(mesh) + plate_inside * 0.5 * plate_mass * plate_v * plate_v);
  const double elastic = kTwoPi * (fe::elastic_energy_J_per_rad(mesh, s.snow) - elastic0);
  double gravity_work = plate_inside * s.plate_mass_kg * g * (H - plate_z);
  for (std::size_t k = 0; k < n; ++k) gravity_work += kTwoPi * mesh.mass_kg_per_rad[k] * g * (z_reference[k] - mesh.z_m[k]);
  const double external = gravity_work + plate_drive_work;
  const double balance = external - kinetic - elastic - kTwoPi * plastic_work;
  csv.row({t, H - plate_z, plate_v, snow_force, prescribed ? 0.0 : applied_force_N(s, t), kinetic, elastic,
           kTwoPi * plastic_work, external, balance, smallest_ratio});
}

// Mesh: the plate's edge is a node line; rollers on the side and the bottom.
fe::Mesh make_plate_mesh(const PlateFeSetup& s) {
  std::vector<double> r_lines, z_lines;
  add_lines(r_lines, 0.0, s.plate_radius_m, s.element_size_m);
  add_lines(r_lines, s.plate_radius_m, s.slab_radius_m, s.element_size_m);
  add_lines(z_lines, 0.0, s.slab_depth_m, s.element_size_m);
  fe::Mesh mesh = fe::make_mesh(r_lines, z_lines, s.density_kg_per_m3, s.snow);
  for (int j = 0; j < mesh.nodes_z; ++j) mesh.hold_r[mesh.node(0, j)] = mesh.hold_r[mesh.node(mesh.nodes_r - 1, j)] = 1;
  for (int i = 0; i < mesh.nodes_r; ++i) mesh.hold_z[mesh.node(i, 0)] = 1;
  const double g = s.gravity_m_per_s2, H = s.slab_depth_m;
  if (s.geostatic_initial_state) {
    // The K0 state of the SPH blocks (confined_layer_state); z is the mesh's axis 1.
    for (int e = 0; e < mesh.elements(); ++e)
      for (int p = 0; p < 4; ++p) {
        const double sv = -s.density_kg_per_m3 * g * (H - fe::gauss_point_position(mesh, e, p).y());
        const ConfinedLayerState k0 = confined_layer_state(s.snow, sv);
        Eigen::Matrix3d& sigma = mesh.stress_Pa[4 * e + p];
        sigma = Eigen::Matrix3d::Zero();
        sigma(1, 1) = sv, sigma(0, 0) = sigma(2, 2) = k0.horizontal_stress_Pa;
        mesh.eps_vol_pl[4 * e + p] = k0.eps_vol_pl;
      }
  }
  return mesh;
}

// Kinematic contact: every top node under the plate that the predictor put
// above its face goes back onto the face; with a loaded plate the plate and
// those nodes share the correction so that their momentum is conserved
// (plate mass M, nodes m_i at z_i above the face z_p: the face rises by
// sum m_i (z_i - z_p) / (M + sum m_i) and every such node ends on it).
// Returns the momentum the face gave the nodes (per radian).
double plate_contact(const PlateFeSetup& s, int top, bool prescribed, double plate_mass, double dt, fe::Mesh& mesh,
                     double& plate_z, double& plate_v, std::vector<int>& contact) {
  contact.clear();
  double mass_sum = 0.0, moment_sum = 0.0;
  for (int i = 0; i < mesh.nodes_r; ++i) {
    const int k = mesh.node(i, top);
    if (mesh.r_m[k] <= s.plate_radius_m && mesh.z_m[k] > plate_z) {
      contact.push_back(k);
      mass_sum += mesh.mass_kg_per_rad[k], moment_sum += mesh.mass_kg_per_rad[k] * (mesh.z_m[k] - plate_z);
    }
  }
  if (!prescribed && mass_sum > 0.0) {
    const double lift = moment_sum / (plate_mass + mass_sum);
    plate_z += lift, plate_v += lift / dt;
  }
  double node_momentum_change = 0.0;
  for (int k : contact) {
    const double dz = plate_z - mesh.z_m[k];
    mesh.z_m[k] += dz, mesh.v_z[k] += dz / dt;
    node_momentum_change += mesh.mass_kg_per_rad[k] * dz / dt;
    if (!mesh.hold_r[k]) {  // Coulomb: radial impulse at most mu times the normal one
      const double cap = s.friction_coefficient * std::abs(dz) / dt;
      const double dv = -std::clamp(mesh.v_r[k], -cap, cap);
      mesh.v_r[k] += dv, mesh.r_m[k] += dv * dt;
    }
  }
  return node_momentum_change;
}

// The deformed mesh: element outlines, mirrored about the axis, for a cut-section picture.
void write_final_mesh_and_plots(const PlateFeSetup& s, const fe::Mesh& mesh, const std::string& out, double t) {
  {
    std::ofstream m(out + "/mesh_final.csv");
    m << "r_m,z_m\n";
    for (int e = 0; e < mesh.elements(); ++e) {
      const int i = e % mesh.elements_r(), j = e / mesh.elements_r();
      const int c[5] = {mesh.node(i, j), mesh.node(i + 1, j), mesh.node(i + 1, j + 1), mesh.node(i, j + 1), mesh.node(i, j)};
      for (double side : {1.0, -1.0}) {
        for (int k : c) m << side * mesh.r_m[k] << ',' << mesh.z_m[k] << '\n';
        m << '\n';
      }
    }
  }
  cosim::plot_csv(out + "/plate.csv", out + "/plate_displacement.png", 1, {{2, "plate displacement"}},
                  s.name + ": plate displacement", "time [s]", "displacement [m]");
  cosim::plot_png(out + "/mesh_final.png",
                  {s.name + ": deformed mesh at t = " + cosim::number_text(t) + " s", "r [m]", "z [m]", 900, 700,
                   false, false, true, "", false, ""},
                  {{out + "/mesh_final.csv", "1:2", "lines lw 0.5 lc rgb '#303030'", ""}});
}

// summary.json: the run's description and its results, compared with the references.
nlohmann::json write_plate_summary(const PlateFeSetup& s, const fe::Mesh& mesh, const std::string& out,
                                   const std::string& status, const std::string& error, std::uint64_t steps,
                                   double wall_time_s, const PlateRow& last, double max_force,
                                   double depth_at_max_force) {
  const double H = s.slab_depth_m;
  const double t = last.t, plate_z = last.plate_z, plate_v = last.plate_v, snow_force = last.snow_force;
  const double smallest_ratio = last.smallest_ratio, plastic_work = last.plastic_work;
  nlohmann::json summary;
  summary["name"] = s.name;
  summary["status"] = status;
  if (!error.empty()) summary["error"] = error;
  summary["method"] = "Lagrangian axisymmetric FE (4-node quads, 2x2 Gauss, B-bar), kinematic plate contact";
  summary["mesh"] = {{"elements", mesh.elements()}, {"nodes", mesh.nodes()}, {"element_size_m", s.element_size_m},
                     {"slab_radius_m", s.slab_radius_m}, {"slab_depth_m", s.slab_depth_m}};
  summary["steps"] = steps;
  summary["simulated_time_s"] = t;
  summary["wall_time_s"] = wall_time_s;
  // The mesh's snow surface is the slab's top, where the plate starts: its
  // sinkage is its displacement.
  summary["results"] = {{"plate_displacement_m", H - plate_z},
                        {"plate_sinkage_m", H - plate_z},
                        {"plate_velocity_z_m_per_s", plate_v},
                        {"snow_force_on_plate_N", snow_force},
                        {"largest_snow_force_N", max_force},
                        {"depth_at_largest_snow_force_m", depth_at_max_force},
                        {"smallest_jacobian_ratio", smallest_ratio},
                        {"plastic_work_J", kTwoPi * plastic_work}};
  if (!s.references.empty()) summary["comparison"] = cosim::compare_with_references(s.references, summary["results"]);
  cosim::write_json(out + "/summary.json", summary);
  return summary;
}

}  // namespace

PlateFeSetup plate_fe_setup_from_scene(const cosim::LoadedScene& loaded, double element_size) {
  const auto& scene = loaded.message;
  const std::string where = loaded.file;
  if (!scene.has_sph() || scene.sph().blocks_size() < 1 || scene.sph().rigid_bodies_size() < 1)
    throw cosim::Error(where + ": the finite-element plate test needs an `sph` section with a snow block and a rigid body");
  const auto& sph = scene.sph();
  const auto& block = sph.blocks(0);
  if (!block.material().has_snow())
    throw cosim::Error(where + ": sph.blocks[0].material: the finite-element plate test needs snow");
  const MaterialModel material = material_from_scene(block.material());
  const auto& body = sph.rigid_bodies(0);
  PlateFeSetup s;
  s.name = scene.name() + "_fe";
  s.snow = material.mdpc;
  s.density_kg_per_m3 = material.density0;
  // The full box's plan (a symmetry plane doubles the simulated width).
  double width[2];
  for (int axis = 0; axis < 2; ++axis) {
    const auto& lo = sph.container().min();
    const auto& hi = sph.container().max();
    width[axis] = axis == 0 ? hi.x() - lo.x() : hi.y() - lo.y();
    for (int f : sph.symmetry_planes())
      if ((axis == 0 && (f == cosim::scene::X_MIN || f == cosim::scene::X_MAX)) ||
          (axis == 1 && (f == cosim::scene::Y_MIN || f == cosim::scene::Y_MAX)))
        width[axis] *= 2.0;
  }
  s.slab_radius_m = std::sqrt(width[0] * width[1] / (kTwoPi / 2.0));
  s.slab_depth_m = block.region().max().z() - block.region().min().z();
  s.element_size_m = element_size > 0.0 ? element_size : sph.particle_spacing_m();
  s.plate_radius_m = body.radius_m();
  s.plate_mass_kg = body.mass_kg();
  s.friction_coefficient = body.friction_coefficient();
  s.gravity_m_per_s2 = -sph.gravity_m_per_s2().z();
  if (body.drive_case() == cosim::scene::RigidBody::kPrescribedVelocityZMPerS) {
    s.prescribed_speed_m_per_s = -body.prescribed_velocity_z_m_per_s();
    if (!(s.prescribed_speed_m_per_s > 0.0))
      throw cosim::Error(where + ": sph.rigid_bodies[0].prescribed_velocity_z_m_per_s must be negative (downwards)");
  } else {
    s.applied_force_N = -body.applied_force_z_n();
    s.load_ramp_time_s = body.load_ramp_time_s();
  }
  s.end_time_s = scene.time().end_time_s();
  if (scene.output().csv_interval_s() > 0.0) s.output_interval_s = scene.output().csv_interval_s();
  s.geostatic_initial_state = block.geostatic_initial_state();
  s.references = scene.references();
  if (!(s.plate_radius_m < s.slab_radius_m))
    throw cosim::Error(where + ": sph.rigid_bodies[0].radius_m must be smaller than the slab's radius");
  return s;
}

nlohmann::json run_plate_fe(const PlateFeSetup& s, const std::string& out, bool quiet) {
  check_parameters(s.snow);
  if (!(s.element_size_m > 0.0) || !(s.end_time_s > 0.0) || !(s.plate_mass_kg > 0.0))
    throw cosim::Error(s.name + ": element size, end time and plate mass must be positive");
  cosim::make_folder(out);

  fe::Mesh mesh = make_plate_mesh(s);
  const int top = mesh.nodes_z - 1;
  const double g = s.gravity_m_per_s2, H = s.slab_depth_m;
  const double K = s.snow.bulk_modulus_Pa(), G = s.snow.shear_modulus_Pa();
  const double wave_speed = std::sqrt((K + 4.0 * G / 3.0) / s.density_kg_per_m3);
  const std::vector<double> z_reference = mesh.z_m;

  // The plate, per radian of the revolved model.
  const double plate_mass = s.plate_mass_kg / kTwoPi;
  const bool prescribed = s.prescribed_speed_m_per_s > 0.0;
  double plate_z = H, plate_v = prescribed ? -s.prescribed_speed_m_per_s : 0.0;

  std::vector<double> f_r, f_z, a_r, a_z;
  fe::element_pass(mesh, s.snow, 0.0, f_r, f_z);
  fe::nodal_accelerations(mesh, f_r, f_z, g, a_r, a_z);
  const double elastic0 = fe::elastic_energy_J_per_rad(mesh, s.snow);

  cosim::CsvWriter csv = open_plate_csv(out);
  cosim::Progress progress(s.name, s.end_time_s, quiet);
  double t = 0.0, dt_previous = 0.0, next_output = 0.0;
  double plastic_work = 0.0, plate_drive_work = 0.0, window_impulse = 0.0, window_time = 0.0;
  double snow_force = 0.0, smallest_ratio = 1.0, max_force = 0.0, depth_at_max_force = 0.0;
  std::uint64_t steps = 0;
  std::vector<int> contact;
  std::string status = "completed", error;
  auto applied = [&](double time) { return applied_force_N(s, time); };
  auto write_row = [&] {
    write_plate_row(csv, s, mesh, z_reference, elastic0, plate_mass,
                    {t, plate_z, plate_v, snow_force, plastic_work, plate_drive_work, smallest_ratio});
  };
  write_row();
  next_output = s.output_interval_s;

  while (t < s.end_time_s - 1e-12) {
    if (cosim::interrupt_requested()) {
      status = "failed", error = "interrupted by a signal";
      break;
    }
    const double dt = std::min(fe::stable_time_step(mesh, wave_speed, s.time_step_fraction), s.end_time_s - t);
    const double dt_v = steps == 0 ? 0.5 * dt : 0.5 * (dt + dt_previous);  // central difference, variable step
    fe::advance_nodes(mesh, a_r, a_z, dt_v, dt);
    const double load_now = prescribed ? 0.0 : applied(t + 0.5 * dt);
    if (!prescribed) plate_v += dt_v * (-load_now / s.plate_mass_kg - g);
    const double plate_z_before = plate_z;
    plate_z += dt * plate_v;

    const double node_momentum_change =
        plate_contact(s, top, prescribed, plate_mass, dt, mesh, plate_z, plate_v, contact);
    // The snow's force on the plate (upwards positive) is the reaction to the
    // momentum the face gave the nodes.
    const double face_force = -kTwoPi * node_momentum_change / dt;
    const double plate_travel = plate_z_before - plate_z;  // downwards positive
    if (prescribed)
      plate_drive_work += face_force * plate_travel;  // the drive's work on the snow
    else
      plate_drive_work += load_now * plate_travel;
    window_impulse += face_force * dt;
    window_time += dt;

    const fe::ElementPassResult pass = fe::element_pass(mesh, s.snow, dt, f_r, f_z);
    plastic_work += pass.plastic_work_J_per_rad;
    smallest_ratio = pass.smallest_jacobian_ratio;
    fe::nodal_accelerations(mesh, f_r, f_z, g, a_r, a_z);
    t += dt, dt_previous = dt, ++steps;
    progress.update(t, steps);
    if (smallest_ratio <= 0.0) {
      status = "mesh_inverted";
      error = "an element under the plate turned inside out at t = " + std::to_string(t) + " s";
      snow_force = window_time > 0.0 ? window_impulse / window_time : 0.0;
      write_row();
      break;
    }
    if (t >= next_output - 1e-12 || t >= s.end_time_s - 1e-12) {
      snow_force = window_time > 0.0 ? window_impulse / window_time : 0.0;
      window_impulse = window_time = 0.0;
      if (snow_force > max_force) max_force = snow_force, depth_at_max_force = H - plate_z;
      write_row();
      next_output += s.output_interval_s;
    }
  }
  progress.finish(t, steps);
  csv.flush();

  write_final_mesh_and_plots(s, mesh, out, t);

  return write_plate_summary(s, mesh, out, status, error, steps, progress.elapsed_s(),
                             {t, plate_z, plate_v, snow_force, plastic_work, plate_drive_work, smallest_ratio},
                             max_force, depth_at_max_force);
}

}  // namespace snow_fe

// A strip footing on a layer over a rigid base, plane strain; see strip_fe.hpp.
#include "snow_fe/strip_fe.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cosim/error.hpp"
#include "cosim/ramp.hpp"
#include "snow_fe/axisym_fe.hpp"
#include "snow_sph/scene.hpp"

namespace snow_fe {
namespace {

namespace fe = axisym;

// n equal intervals from a to b, n = max(1, round((b - a) / h)), appended after `lines`' last.
void append_lines(std::vector<double>& lines, double a, double b, double h) {
  const int n = std::max(1, static_cast<int>(std::lround((b - a) / h)));
  if (lines.empty()) lines.push_back(a);
  for (int k = 1; k <= n; ++k) lines.push_back(a + (b - a) * k / n);
}

void check_setup(const StripBearingSetup& s) {
  snow_sph::check_parameters(s.snow);
  if (!(s.density_kg_per_m3 > 0.0) || !(s.footing_width_m > 0.0) || !(s.layer_depth_m > 0.0) ||
      !(s.element_size_m > 0.0) || !(s.footing_speed_m_per_s > 0.0) || !(s.end_displacement_m > 0.0))
    throw cosim::Error("strip bearing: density, widths, element size, speed and end displacement must be positive");
  if (!(s.layer_half_length_m > 0.5 * s.footing_width_m))
    throw cosim::Error("strip bearing: the layer must reach beyond the footing's edge");
}

// The mesh with its supports; `footing` gets the top nodes under the footing.
fe::Mesh make_strip_mesh(const StripBearingSetup& s, std::vector<int>& footing) {
  std::vector<double> x_lines, z_lines;
  const double half_width = 0.5 * s.footing_width_m;
  append_lines(x_lines, 0.0, half_width, s.element_size_m);
  append_lines(x_lines, half_width, s.layer_half_length_m, s.element_size_m);
  append_lines(z_lines, 0.0, s.layer_depth_m, s.element_size_m);
  fe::Mesh mesh = fe::make_mesh(x_lines, z_lines, s.density_kg_per_m3, s.snow, fe::Geometry::plane_strain);
  for (int j = 0; j < mesh.nodes_z; ++j) {
    mesh.hold_r[mesh.node(0, j)] = 1;
    if (s.confined_end) mesh.hold_r[mesh.node(mesh.nodes_r - 1, j)] = 1;
  }
  for (int i = 0; i < mesh.nodes_r; ++i) {
    mesh.hold_z[mesh.node(i, 0)] = 1;
    if (s.rough_base) mesh.hold_r[mesh.node(i, 0)] = 1;
  }
  footing.clear();
  const int top = mesh.nodes_z - 1;
  for (int i = 0; i < mesh.nodes_r && x_lines[i] <= half_width * (1.0 + 1e-12); ++i) {
    const int k = mesh.node(i, top);
    mesh.hold_r[k] = mesh.hold_z[k] = 1;
    footing.push_back(k);
  }
  return mesh;
}

}  // namespace

StripBearingResult run_strip_bearing(const StripBearingSetup& s, int outputs) {
  check_setup(s);
  std::vector<int> footing;
  fe::Mesh mesh = make_strip_mesh(s, footing);
  const double K = s.snow.bulk_modulus_Pa(), G = s.snow.shear_modulus_Pa();
  const double wave_speed = std::sqrt((K + 4.0 * G / 3.0) / s.density_kg_per_m3);
  std::vector<double> f_x, f_z, a_x, a_z;
  fe::element_pass(mesh, s.snow, 0.0, f_x, f_z);
  fe::nodal_accelerations(mesh, f_x, f_z, 0.0, a_x, a_z);

  StripBearingResult result;
  double t = 0.0, dt_previous = 0.0, displacement = 0.0;
  double next_output = s.end_displacement_m / outputs;
  while (displacement < s.end_displacement_m) {
    const double dt = fe::stable_time_step(mesh, wave_speed, s.time_step_fraction);
    const double speed =
        cosim::ramp(cosim::RampCurve::smootherstep, t + 0.5 * dt, s.speed_ramp_time_s, s.footing_speed_m_per_s);
    for (int k : footing) mesh.v_r[k] = 0.0, mesh.v_z[k] = -speed;
    fe::advance_nodes(mesh, a_x, a_z, result.steps == 0 ? 0.5 * dt : 0.5 * (dt + dt_previous), dt);
    displacement += speed * dt;
    const fe::ElementPassResult pass = fe::element_pass(mesh, s.snow, dt, f_x, f_z);
    fe::nodal_accelerations(mesh, f_x, f_z, 0.0, a_x, a_z);
    result.smallest_jacobian_ratio = std::min(result.smallest_jacobian_ratio, pass.smallest_jacobian_ratio);
    if (!(pass.smallest_jacobian_ratio > 0.0))
      throw cosim::Error("strip bearing: an element turned inside out at a displacement of " +
                         std::to_string(displacement) + " m");
    t += dt, dt_previous = dt, ++result.steps;
    if (displacement >= next_output) {
      // The snow's force on the footing's nodes (upwards), per metre of the half model.
      double force = 0.0;
      for (int k : footing) force += f_z[k];
      const double pressure = force / (0.5 * s.footing_width_m);
      result.displacement_m.push_back(displacement), result.pressure_Pa.push_back(pressure);
      result.largest_pressure_Pa = std::max(result.largest_pressure_Pa, pressure);
      next_output += s.end_displacement_m / outputs;
    }
  }
  return result;
}

double limit_pressure_Pa(const std::vector<double>& d, const std::vector<double>& p, double footing_width_m) {
  if (d.size() != p.size() || d.empty() || !(d.front() <= footing_width_m / 40.0))
    throw cosim::Error("strip bearing: no output point up to a settlement of B/40");
  double largest = -1e300;
  for (std::size_t k = 0; k < d.size() && d[k] <= footing_width_m / 40.0; ++k) largest = std::max(largest, p[k]);
  return largest;
}

StripBearingSetup strip_setup_from_scene(const cosim::LoadedScene& loaded, bool rough_base, double element_size) {
  const auto& scene = loaded.message;
  const std::string& where = loaded.file;
  if (!scene.has_sph() || scene.sph().blocks_size() < 1 || scene.sph().rigid_bodies_size() < 1 ||
      scene.sph().rigid_bodies(0).drive_case() != cosim::scene::RigidBody::kPrescribedVelocityZMPerS)
    throw cosim::Error(where + ": the strip test needs an `sph` section with a block and a body at a prescribed speed");
  const auto& sph = scene.sph();
  if (!sph.blocks(0).material().has_snow())
    throw cosim::Error(where + ": sph.blocks[0].material: the strip test needs snow");
  const auto material = snow_sph::material_from_scene(sph.blocks(0).material());
  const auto& body = sph.rigid_bodies(0);
  StripBearingSetup s;
  s.snow = material.mdpc;
  s.density_kg_per_m3 = material.density0;
  s.footing_width_m = 2.0 * (body.initial_bottom_centre_m().x() + body.radius_m());
  const auto& layer = sph.blocks(0).region();
  s.layer_depth_m = layer.max().z() - layer.min().z();
  s.layer_half_length_m = layer.max().x() - layer.min().x();
  s.element_size_m = element_size;
  s.rough_base = rough_base;
  s.footing_speed_m_per_s = -body.prescribed_velocity_z_m_per_s();
  s.end_displacement_m = s.footing_speed_m_per_s * scene.time().end_time_s();
  s.speed_ramp_time_s = 0.1 * scene.time().end_time_s();
  if (!(s.footing_speed_m_per_s > 0.0))
    throw cosim::Error(where + ": sph.rigid_bodies[0].prescribed_velocity_z_m_per_s must be negative (downwards)");
  return s;
}

}  // namespace snow_fe

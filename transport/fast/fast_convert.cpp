// Neutral structs <-> fastddsgen classes, field by field in IDL order.
#include "fast_convert.hpp"

#include <utility>

namespace cosim::transport::fast {

// The enumerations keep the IDL's numbering; the last enumerator pins the count.
// Every facet tag (cosim/facet_tag.hpp) has the IDL's value.
static_assert(static_cast<int>(cosim_wire::TAG_TREAD_TOP) == static_cast<int>(FacetTag::tread_top));
static_assert(static_cast<int>(cosim_wire::TAG_GROOVE_WALL) == static_cast<int>(FacetTag::groove_wall));
static_assert(static_cast<int>(cosim_wire::TAG_GROOVE_BOTTOM) == static_cast<int>(FacetTag::groove_bottom));
static_assert(static_cast<int>(cosim_wire::TAG_SIPE_WALL) == static_cast<int>(FacetTag::sipe_wall));
static_assert(static_cast<int>(cosim_wire::TAG_SHOULDER) == static_cast<int>(FacetTag::shoulder));
static_assert(static_cast<int>(cosim_wire::TAG_SIDEWALL) == static_cast<int>(FacetTag::sidewall));
static_assert(static_cast<int>(cosim_wire::TAG_INNER_LINER) == static_cast<int>(FacetTag::inner_liner));
static_assert(static_cast<int>(cosim_wire::TAG_RIM_CONTACT) == static_cast<int>(FacetTag::rim_contact));
static_assert(static_cast<int>(cosim_wire::TAG_OTHER) == static_cast<int>(FacetTag::other));
static_assert(kFacetTagCount == cosim_wire::TAG_OTHER + 1);
static_assert(static_cast<int>(cosim_wire::ROLE_MONITOR) == static_cast<int>(Role::monitor) &&
              kRoleCount == cosim_wire::ROLE_MONITOR + 1);
static_assert(static_cast<int>(cosim_wire::CONTROL_CHECKPOINT_AT) == static_cast<int>(ControlKind::checkpoint_at) &&
              kControlKindCount == cosim_wire::CONTROL_CHECKPOINT_AT + 1);

namespace {

void to_wire(const SampleHeader& s, cosim_wire::SampleHeader& w) {
  w.run_id(s.run_id);
  w.step(s.step);
  w.sim_time_s(s.sim_time_s);
}
void from_wire(const cosim_wire::SampleHeader& w, SampleHeader& s) {
  s.run_id = w.run_id();
  s.step = w.step();
  s.sim_time_s = w.sim_time_s();
}

}  // namespace

void to_wire(const SurfaceMesh& s, cosim_wire::SurfaceMesh& w) {
  to_wire(s.header, w.header());
  w.node_ids() = s.node_ids;
  w.x_m() = s.x_m;
  w.y_m() = s.y_m;
  w.z_m() = s.z_m;
  w.facet_nodes() = s.facet_nodes;
  w.facet_tags().resize(s.facet_tags.size());
  for (std::size_t i = 0; i < s.facet_tags.size(); ++i)
    w.facet_tags()[i] = static_cast<cosim_wire::FacetTag>(s.facet_tags[i]);
  w.node_mass_kg() = s.node_mass_kg;
}
void from_wire(cosim_wire::SurfaceMesh& w, SurfaceMesh& s) {
  from_wire(w.header(), s.header);
  s.node_ids = std::move(w.node_ids());
  s.x_m = std::move(w.x_m());
  s.y_m = std::move(w.y_m());
  s.z_m = std::move(w.z_m());
  s.facet_nodes = std::move(w.facet_nodes());
  s.facet_tags.resize(w.facet_tags().size());
  for (std::size_t i = 0; i < s.facet_tags.size(); ++i)
    s.facet_tags[i] = static_cast<FacetTag>(w.facet_tags()[i]);
  s.node_mass_kg = std::move(w.node_mass_kg());
}

void to_wire(const SurfaceKinematics& s, cosim_wire::SurfaceKinematics& w) {
  to_wire(s.header, w.header());
  w.nodes() = s.nodes;
  w.x_m() = s.x_m;
  w.y_m() = s.y_m;
  w.z_m() = s.z_m;
  w.vx_mps() = s.vx_mps;
  w.vy_mps() = s.vy_mps;
  w.vz_mps() = s.vz_mps;
  w.facets() = s.facets;
  w.friction_coefficient() = s.friction_coefficient;
}
void from_wire(cosim_wire::SurfaceKinematics& w, SurfaceKinematics& s) {
  from_wire(w.header(), s.header);
  s.nodes = std::move(w.nodes());
  s.x_m = std::move(w.x_m());
  s.y_m = std::move(w.y_m());
  s.z_m = std::move(w.z_m());
  s.vx_mps = std::move(w.vx_mps());
  s.vy_mps = std::move(w.vy_mps());
  s.vz_mps = std::move(w.vz_mps());
  s.facets = std::move(w.facets());
  s.friction_coefficient = std::move(w.friction_coefficient());
}

void to_wire(const ContactLoads& s, cosim_wire::ContactLoads& w) {
  to_wire(s.header, w.header());
  w.nodes() = s.nodes;
  w.fx_N() = s.fx_N;
  w.fy_N() = s.fy_N;
  w.fz_N() = s.fz_N;
  w.facets() = s.facets;
  w.normal_force_N() = s.normal_force_N;
  w.pressure_x_N() = s.pressure_x_N;
  w.pressure_y_N() = s.pressure_y_N;
  w.pressure_z_N() = s.pressure_z_N;
  w.tangential_x_N() = s.tangential_x_N;
  w.tangential_y_N() = s.tangential_y_N;
  w.tangential_z_N() = s.tangential_z_N;
  w.contact_area_m2() = s.contact_area_m2;
  w.pressure_Pa() = s.pressure_Pa;
  w.particle_reach_z_m(s.particle_reach_z_m);
}
void from_wire(cosim_wire::ContactLoads& w, ContactLoads& s) {
  from_wire(w.header(), s.header);
  s.nodes = std::move(w.nodes());
  s.fx_N = std::move(w.fx_N());
  s.fy_N = std::move(w.fy_N());
  s.fz_N = std::move(w.fz_N());
  s.facets = std::move(w.facets());
  s.normal_force_N = std::move(w.normal_force_N());
  s.pressure_x_N = std::move(w.pressure_x_N());
  s.pressure_y_N = std::move(w.pressure_y_N());
  s.pressure_z_N = std::move(w.pressure_z_N());
  s.tangential_x_N = std::move(w.tangential_x_N());
  s.tangential_y_N = std::move(w.tangential_y_N());
  s.tangential_z_N = std::move(w.tangential_z_N());
  s.contact_area_m2 = std::move(w.contact_area_m2());
  s.pressure_Pa = std::move(w.pressure_Pa());
  s.particle_reach_z_m = w.particle_reach_z_m();
}

void to_wire(const WheelState& s, cosim_wire::WheelState& w) {
  to_wire(s.header, w.header());
  w.rim_x_m(s.rim_x_m);
  w.rim_z_m(s.rim_z_m);
  w.rotation_angle_rad(s.rotation_angle_rad);
  w.forward_speed_mps(s.forward_speed_mps);
  w.spin_rate_radps(s.spin_rate_radps);
  w.applied_torque_Nm(s.applied_torque_Nm);
  w.reaction_moment_y_Nm(s.reaction_moment_y_Nm);
  w.wheel_load_N(s.wheel_load_N);
  w.rim_longitudinal_force_N(s.rim_longitudinal_force_N);
}
void from_wire(cosim_wire::WheelState& w, WheelState& s) {
  from_wire(w.header(), s.header);
  s.rim_x_m = w.rim_x_m();
  s.rim_z_m = w.rim_z_m();
  s.rotation_angle_rad = w.rotation_angle_rad();
  s.forward_speed_mps = w.forward_speed_mps();
  s.spin_rate_radps = w.spin_rate_radps();
  s.applied_torque_Nm = w.applied_torque_Nm();
  s.reaction_moment_y_Nm = w.reaction_moment_y_Nm();
  s.wheel_load_N = w.wheel_load_N();
  s.rim_longitudinal_force_N = w.rim_longitudinal_force_N();
}

void to_wire(const ForceSummary& s, cosim_wire::ForceSummary& w) {
  to_wire(s.header, w.header());
  w.traction_force_N(s.traction_force_N);
  w.motion_resistance_N(s.motion_resistance_N);
  w.groove_force_N(s.groove_force_N);
  w.rolling_resistance_force_N(s.rolling_resistance_force_N);
  w.drawbar_pull_N(s.drawbar_pull_N);
  w.net_longitudinal_pressure_force_N(s.net_longitudinal_pressure_force_N);
  w.sinkage_m(s.sinkage_m);
  w.contact_area_m2(s.contact_area_m2);
}
void from_wire(cosim_wire::ForceSummary& w, ForceSummary& s) {
  from_wire(w.header(), s.header);
  s.traction_force_N = w.traction_force_N();
  s.motion_resistance_N = w.motion_resistance_N();
  s.groove_force_N = w.groove_force_N();
  s.rolling_resistance_force_N = w.rolling_resistance_force_N();
  s.drawbar_pull_N = w.drawbar_pull_N();
  s.net_longitudinal_pressure_force_N = w.net_longitudinal_pressure_force_N();
  s.sinkage_m = w.sinkage_m();
  s.contact_area_m2 = w.contact_area_m2();
}

void to_wire(const RunControl& s, cosim_wire::RunControl& w) {
  to_wire(s.header, w.header());
  w.kind(static_cast<cosim_wire::ControlKind>(s.kind));
  w.sender(static_cast<cosim_wire::Role>(s.sender));
  w.addressee(static_cast<cosim_wire::Role>(s.addressee));
  w.proposed_time_step_s(s.proposed_time_step_s);
  w.agreed_time_step_s(s.agreed_time_step_s);
  w.reason(s.reason);
}
void from_wire(cosim_wire::RunControl& w, RunControl& s) {
  from_wire(w.header(), s.header);
  s.kind = static_cast<ControlKind>(w.kind());
  s.sender = static_cast<Role>(w.sender());
  s.addressee = static_cast<Role>(w.addressee());
  s.proposed_time_step_s = w.proposed_time_step_s();
  s.agreed_time_step_s = w.agreed_time_step_s();
  s.reason = std::move(w.reason());
}

}  // namespace cosim::transport::fast

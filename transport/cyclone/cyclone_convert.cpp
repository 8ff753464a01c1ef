// Neutral structs <-> idlc's C structs, field by field in IDL order.
#include "cyclone_convert.hpp"

#include <type_traits>

#include "field_count.hpp"

namespace cosim::transport::cyclone {

// Drift checks: same number of fields as the IDL, same enumeration numbering.
#define COSIM_SAME_FIELDS(T)                                                         \
  static_assert(field_count<T>() == field_count<cosim_wire_##T>(),                   \
                "cosim::transport::" #T " and idl/cosim_topics.idl's " #T            \
                " have different fields: update both, the conversions and the tests")
COSIM_SAME_FIELDS(SampleHeader);
COSIM_SAME_FIELDS(SurfaceMesh);
COSIM_SAME_FIELDS(SurfaceKinematics);
COSIM_SAME_FIELDS(ContactLoads);
COSIM_SAME_FIELDS(WheelState);
COSIM_SAME_FIELDS(ForceSummary);
COSIM_SAME_FIELDS(RunControl);
#undef COSIM_SAME_FIELDS
// Every facet tag (cosim/facet_tag.hpp) has the IDL's value.
static_assert(cosim_wire_TAG_TREAD_TOP == static_cast<int>(FacetTag::tread_top));
static_assert(cosim_wire_TAG_GROOVE_WALL == static_cast<int>(FacetTag::groove_wall));
static_assert(cosim_wire_TAG_GROOVE_BOTTOM == static_cast<int>(FacetTag::groove_bottom));
static_assert(cosim_wire_TAG_SIPE_WALL == static_cast<int>(FacetTag::sipe_wall));
static_assert(cosim_wire_TAG_SHOULDER == static_cast<int>(FacetTag::shoulder));
static_assert(cosim_wire_TAG_SIDEWALL == static_cast<int>(FacetTag::sidewall));
static_assert(cosim_wire_TAG_INNER_LINER == static_cast<int>(FacetTag::inner_liner));
static_assert(cosim_wire_TAG_RIM_CONTACT == static_cast<int>(FacetTag::rim_contact));
static_assert(cosim_wire_TAG_OTHER == static_cast<int>(FacetTag::other));
static_assert(kFacetTagCount == cosim_wire_TAG_OTHER + 1);
static_assert(cosim_wire_ROLE_MONITOR == static_cast<int>(Role::monitor) && kRoleCount == cosim_wire_ROLE_MONITOR + 1);
static_assert(cosim_wire_CONTROL_CHECKPOINT_AT == static_cast<int>(ControlKind::checkpoint_at) &&
              kControlKindCount == cosim_wire_CONTROL_CHECKPOINT_AT + 1);

namespace {

template <class Seq, class E>
void view_seq(const std::vector<E>& v, Seq& q) {
  static_assert(std::is_same_v<std::remove_pointer_t<decltype(q._buffer)>, E>, "element type differs from the IDL");
  q._maximum = q._length = static_cast<uint32_t>(v.size());
  q._buffer = const_cast<E*>(v.data());
  q._release = false;
}
template <class Seq, class E>
void from_seq(const Seq& q, std::vector<E>& v) {
  static_assert(std::is_same_v<std::remove_pointer_t<decltype(q._buffer)>, E>, "element type differs from the IDL");
  v.assign(q._buffer, q._buffer + q._length);
}

void view(const SampleHeader& s, cosim_wire_SampleHeader& w) {
  w.run_id = s.run_id;
  w.step = s.step;
  w.sim_time_s = s.sim_time_s;
}
void from_wire(const cosim_wire_SampleHeader& w, SampleHeader& s) {
  s.run_id = w.run_id;
  s.step = w.step;
  s.sim_time_s = w.sim_time_s;
}

}  // namespace

void view(const SurfaceMesh& s, cosim_wire_SurfaceMesh& w, Scratch& scratch) {
  view(s.header, w.header);
  view_seq(s.node_ids, w.node_ids);
  view_seq(s.x_m, w.x_m);
  view_seq(s.y_m, w.y_m);
  view_seq(s.z_m, w.z_m);
  view_seq(s.facet_nodes, w.facet_nodes);
  scratch.facet_tags.resize(s.facet_tags.size());
  for (std::size_t i = 0; i < s.facet_tags.size(); ++i)
    scratch.facet_tags[i] = static_cast<cosim_wire_FacetTag>(s.facet_tags[i]);
  view_seq(scratch.facet_tags, w.facet_tags);
  view_seq(s.node_mass_kg, w.node_mass_kg);
}
void from_wire(const cosim_wire_SurfaceMesh& w, SurfaceMesh& s) {
  from_wire(w.header, s.header);
  from_seq(w.node_ids, s.node_ids);
  from_seq(w.x_m, s.x_m);
  from_seq(w.y_m, s.y_m);
  from_seq(w.z_m, s.z_m);
  from_seq(w.facet_nodes, s.facet_nodes);
  s.facet_tags.resize(w.facet_tags._length);
  for (std::size_t i = 0; i < s.facet_tags.size(); ++i) s.facet_tags[i] = static_cast<FacetTag>(w.facet_tags._buffer[i]);
  from_seq(w.node_mass_kg, s.node_mass_kg);
}

void view(const SurfaceKinematics& s, cosim_wire_SurfaceKinematics& w, Scratch&) {
  view(s.header, w.header);
  view_seq(s.nodes, w.nodes);
  view_seq(s.x_m, w.x_m);
  view_seq(s.y_m, w.y_m);
  view_seq(s.z_m, w.z_m);
  view_seq(s.vx_mps, w.vx_mps);
  view_seq(s.vy_mps, w.vy_mps);
  view_seq(s.vz_mps, w.vz_mps);
  view_seq(s.facets, w.facets);
  view_seq(s.friction_coefficient, w.friction_coefficient);
}
void from_wire(const cosim_wire_SurfaceKinematics& w, SurfaceKinematics& s) {
  from_wire(w.header, s.header);
  from_seq(w.nodes, s.nodes);
  from_seq(w.x_m, s.x_m);
  from_seq(w.y_m, s.y_m);
  from_seq(w.z_m, s.z_m);
  from_seq(w.vx_mps, s.vx_mps);
  from_seq(w.vy_mps, s.vy_mps);
  from_seq(w.vz_mps, s.vz_mps);
  from_seq(w.facets, s.facets);
  from_seq(w.friction_coefficient, s.friction_coefficient);
}

void view(const ContactLoads& s, cosim_wire_ContactLoads& w, Scratch&) {
  view(s.header, w.header);
  view_seq(s.nodes, w.nodes);
  view_seq(s.fx_N, w.fx_N);
  view_seq(s.fy_N, w.fy_N);
  view_seq(s.fz_N, w.fz_N);
  view_seq(s.facets, w.facets);
  view_seq(s.normal_force_N, w.normal_force_N);
  view_seq(s.pressure_x_N, w.pressure_x_N);
  view_seq(s.pressure_y_N, w.pressure_y_N);
  view_seq(s.pressure_z_N, w.pressure_z_N);
  view_seq(s.tangential_x_N, w.tangential_x_N);
  view_seq(s.tangential_y_N, w.tangential_y_N);
  view_seq(s.tangential_z_N, w.tangential_z_N);
  view_seq(s.contact_area_m2, w.contact_area_m2);
  view_seq(s.pressure_Pa, w.pressure_Pa);
  w.particle_reach_z_m = s.particle_reach_z_m;
}
void from_wire(const cosim_wire_ContactLoads& w, ContactLoads& s) {
  from_wire(w.header, s.header);
  from_seq(w.nodes, s.nodes);
  from_seq(w.fx_N, s.fx_N);
  from_seq(w.fy_N, s.fy_N);
  from_seq(w.fz_N, s.fz_N);
  from_seq(w.facets, s.facets);
  from_seq(w.normal_force_N, s.normal_force_N);
  from_seq(w.pressure_x_N, s.pressure_x_N);
  from_seq(w.pressure_y_N, s.pressure_y_N);
  from_seq(w.pressure_z_N, s.pressure_z_N);
  from_seq(w.tangential_x_N, s.tangential_x_N);
  from_seq(w.tangential_y_N, s.tangential_y_N);
  from_seq(w.tangential_z_N, s.tangential_z_N);
  from_seq(w.contact_area_m2, s.contact_area_m2);
  from_seq(w.pressure_Pa, s.pressure_Pa);
  s.particle_reach_z_m = w.particle_reach_z_m;
}

void view(const WheelState& s, cosim_wire_WheelState& w, Scratch&) {
  view(s.header, w.header);
  w.rim_x_m = s.rim_x_m;
  w.rim_z_m = s.rim_z_m;
  w.rotation_angle_rad = s.rotation_angle_rad;
  w.forward_speed_mps = s.forward_speed_mps;
  w.spin_rate_radps = s.spin_rate_radps;
  w.applied_torque_Nm = s.applied_torque_Nm;
  w.reaction_moment_y_Nm = s.reaction_moment_y_Nm;
  w.wheel_load_N = s.wheel_load_N;
  w.rim_longitudinal_force_N = s.rim_longitudinal_force_N;
}
void from_wire(const cosim_wire_WheelState& w, WheelState& s) {
  from_wire(w.header, s.header);
  s.rim_x_m = w.rim_x_m;
  s.rim_z_m = w.rim_z_m;
  s.rotation_angle_rad = w.rotation_angle_rad;
  s.forward_speed_mps = w.forward_speed_mps;
  s.spin_rate_radps = w.spin_rate_radps;
  s.applied_torque_Nm = w.applied_torque_Nm;
  s.reaction_moment_y_Nm = w.reaction_moment_y_Nm;
  s.wheel_load_N = w.wheel_load_N;
  s.rim_longitudinal_force_N = w.rim_longitudinal_force_N;
}

void view(const ForceSummary& s, cosim_wire_ForceSummary& w, Scratch&) {
  view(s.header, w.header);
  w.traction_force_N = s.traction_force_N;
  w.motion_resistance_N = s.motion_resistance_N;
  w.groove_force_N = s.groove_force_N;
  w.rolling_resistance_force_N = s.rolling_resistance_force_N;
  w.drawbar_pull_N = s.drawbar_pull_N;
  w.net_longitudinal_pressure_force_N = s.net_longitudinal_pressure_force_N;
  w.sinkage_m = s.sinkage_m;
  w.contact_area_m2 = s.contact_area_m2;
}
void from_wire(const cosim_wire_ForceSummary& w, ForceSummary& s) {
  from_wire(w.header, s.header);
  s.traction_force_N = w.traction_force_N;
  s.motion_resistance_N = w.motion_resistance_N;
  s.groove_force_N = w.groove_force_N;
  s.rolling_resistance_force_N = w.rolling_resistance_force_N;
  s.drawbar_pull_N = w.drawbar_pull_N;
  s.net_longitudinal_pressure_force_N = w.net_longitudinal_pressure_force_N;
  s.sinkage_m = w.sinkage_m;
  s.contact_area_m2 = w.contact_area_m2;
}

void view(const RunControl& s, cosim_wire_RunControl& w, Scratch&) {
  view(s.header, w.header);
  w.kind = static_cast<cosim_wire_ControlKind>(s.kind);
  w.sender = static_cast<cosim_wire_Role>(s.sender);
  w.addressee = static_cast<cosim_wire_Role>(s.addressee);
  w.proposed_time_step_s = s.proposed_time_step_s;
  w.agreed_time_step_s = s.agreed_time_step_s;
  w.reason = const_cast<char*>(s.reason.c_str());
}
void from_wire(const cosim_wire_RunControl& w, RunControl& s) {
  from_wire(w.header, s.header);
  s.kind = static_cast<ControlKind>(w.kind);
  s.sender = static_cast<Role>(w.sender);
  s.addressee = static_cast<Role>(w.addressee);
  s.proposed_time_step_s = w.proposed_time_step_s;
  s.agreed_time_step_s = w.agreed_time_step_s;
  s.reason = w.reason ? w.reason : "";
}

}  // namespace cosim::transport::cyclone

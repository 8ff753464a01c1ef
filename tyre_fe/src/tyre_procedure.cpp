// The tyre's procedure (tyre_run.hpp): after the transfer, three stages of
// steps, each begun, stepped and ended here with the rim's drive for it:
//   3. a check at rest after the transfer (no damping, rim held),
//   4. loading onto the road or the terrain (dynamic relaxation, the load ramped in),
//   5. rolling (the speed ramped in, then free rolling or a drive torque).
#include <algorithm>
#include <cmath>

#include "cosim/ramp.hpp"
#include "tyre_run.hpp"

namespace tyre_fe {
namespace sc = cosim::scene;
namespace {

// Lowest point of the outer surface relative to the rim node: the unloaded radius.
double free_radius(const Model3d& m, const State3d& s) { return s.rim.z - lowest_contact_z(m, s); }

// The wheel load, speed and drive torque ramp in with zero rate at both ends.
double smooth_ramp(double t, double ramp) { return cosim::ramp(cosim::RampCurve::smoothstep, t, ramp); }

}  // namespace

void lower_tyre_to(const Model3d& model, State3d& s, double height_m) {
  const double lift = height_m - lowest_contact_z(model, s);
  for (double& z : s.z) z += lift;
  s.rim.z += lift;
}

bool TyreRun::before_exchange() {
  // Stages end when their time is up (or their per-step work says so); a step
  // limit ends every stage at once (their results are those of the state reached).
  while (stage_ != kDone) {
    if (!stage_begun_) begin_stage();
    const bool time_up = !(s_.time_s < stage_t_end_s_ - 0.5 * s_.dt_s);
    if (!time_up && !stage_done_ && !at_max_steps_) {
      if (max_steps_ > 0 && s_.step >= max_steps_) {
        at_max_steps_ = true;
        continue;
      }
      return true;
    }
    end_stage();
  }
  return false;
}

void TyreRun::begin_stage() {
  stage_begun_ = true;
  stage_done_ = false;
  stage_t0_s_ = s_.time_s;
  switch (stage_) {
    case kTransferCheck:  // 3. Check at rest after the transfer: no damping, rim held.
      stage_t_end_s_ = s_.time_s + t_.stages().transfer_check_s();
      break;
    case kLoading:  // 4. Loading onto the road or the terrain (dynamic relaxation).
      begin_loading();
      break;
    case kRolling:  // 5. Rolling.
      begin_rolling();
      break;
    case kDone:
      break;
  }
}

void TyreRun::begin_loading() {
  const auto& st = t_.stages();
  if (port_ && !loaded_before_terrain()) join_terrain();
  stage_t_end_s_ = s_.time_s + st.loading_s();
  if (st.loading_s() <= 0) return;
  if (loaded_before_terrain())
    stand_on_the_terrains_floor();
  else if (!port_)
    place_road(*model_, s_, t_.road().initial_gap_m(), t_.road().friction_coefficient(), t_.road().penalty_scale());
  loading_.unloaded_radius_m = free_radius(*model_, s_);
  s_.damping_per_s = st.loading_damping_per_s();
  loading_.load_N = t_.rim().wheel_load_n(), loading_.ramp_s = t_.rim().load_ramp_time_s();
  loading_.start_s = s_.time_s;
  loading_.previous_kinetic_J = 0.0;
  loading_.at_rest = false;
}

void TyreRun::begin_rolling() {
  const auto& st = t_.stages();
  if (loaded_before_terrain()) join_terrain();  // the water placed around the tyre at rest
  stage_t_end_s_ = s_.time_s + st.rolling_s();
  if (st.rolling_s() <= 0) return;
  window_length_s_ = averaging_window_s(st);
  window_start_s_ = s_.time_s + st.rolling_s() - window_length_s_;
  // Effective rolling radius estimate R - deflection / 3 (a common estimate; Pacejka, Tire and Vehicle Dynamics, 2006).
  const double unloaded = record_->results().value("unloaded_radius_m", free_radius(*model_, s_));
  spin_up_radius_m_ = unloaded - (unloaded - (s_.rim.z - s_.road.height_m)) / 3.0;
}

// Loading before the terrain is placed (coupling.place_terrain_around_loaded_tyre):
// the road at the terrain's floor, the tyre road.initial_gap_m above it.
void TyreRun::stand_on_the_terrains_floor() {
  const double floor_z = scene_.sph().container().min().z();
  lower_tyre_to(*model_, s_, floor_z + t_.road().initial_gap_m());
  set_road(s_, floor_z, t_.road().friction_coefficient(), t_.road().penalty_scale());
}

RimDrive TyreRun::drive_now() const {
  const double tau = s_.time_s - stage_t0_s_;
  RimDrive d;
  switch (stage_) {
    case kTransferCheck:
      d.hold_z = true;
      break;
    case kLoading:
      d.wheel_load_N = loading_.load_N * smooth_ramp(tau, loading_.ramp_s);
      break;
    case kRolling:
      return rolling_drive(tau);
    case kDone:
      break;
  }
  return d;
}

RimDrive TyreRun::rolling_drive(double tau) const {
  const auto& rim = t_.rim();
  RimDrive d;
  d.hold_x = false;
  d.forward_speed_m_per_s = rim.forward_speed_m_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
  d.wheel_load_N = rim.wheel_load_n();
  if (rim.spin_case() == sc::RimSpec::kAngularVelocityRadPerS) {
    d.angular_velocity_rad_per_s = rim.angular_velocity_rad_per_s() * smooth_ramp(tau, rim.speed_ramp_time_s());
  } else if (tau < rim.speed_ramp_time_s()) {
    // Spin-up: while the speed ramps the spin follows it at the estimated free
    // rolling radius, so that the tyre starts rolling instead of sliding; then the
    // spin is released (free rolling) and the torque ramps in.
    d.angular_velocity_rad_per_s = d.forward_speed_m_per_s / spin_up_radius_m_;
  } else {
    d.spin_prescribed = false;
    d.drive_torque_Nm = rim.drive_torque_nm() * smooth_ramp(tau - rim.speed_ramp_time_s(), rim.torque_ramp_time_s());
  }
  return d;
}

bool TyreRun::each_step() {
  switch (stage_) {
    case kTransferCheck:
      transfer_.add_kinetic(s_.energy.kinetic_J);
      transfer_.add_growth(mean_radius_of(model_->mesh, s_, centre_) - centre_r0_m_, s_.dt_s);
      return false;
    case kLoading:
      return loading_step();
    case kRolling:
      return rolling_step();
    case kDone:
      return false;
  }
  return false;
}

bool TyreRun::loading_step() {
  const auto& st = t_.stages();
  if (st.loading_kinetic_damping()) {
    if (s_.energy.kinetic_J < loading_.previous_kinetic_J) {
      zero_velocities(s_);
      loading_.previous_kinetic_J = 0.0;
    } else {
      loading_.previous_kinetic_J = s_.energy.kinetic_J;
    }
  }
  const double tol = st.loading_rest_tolerance();
  if (tol <= 0.0) return false;
  const double load = loading_.load_N;
  const bool balanced = s_.time_s - loading_.start_s >= loading_.ramp_s && std::fabs(ground_fz(s_) - load) < tol * load &&
                        std::fabs(s_.rim.tyre_force_z_N - load) < tol * load &&
                        s_.energy.kinetic_J < tol * s_.energy.internal_J;
  // The rim's speed must stay below the rest speed for the hold time (as a body's rest in snow_sph).
  const double rest_speed = st.loading_rest_speed_m_per_s();
  if (!(balanced && (rest_speed <= 0.0 || std::fabs(s_.rim.vz) < rest_speed))) loading_.slow_since_s = s_.time_s;
  loading_.at_rest = balanced && (rest_speed <= 0.0 || s_.time_s - loading_.slow_since_s >= st.loading_rest_hold_s());
  return loading_.at_rest;
}

bool TyreRun::rolling_step() {
  if (road_under_terrain()) {
    hydroplaning_.add(s_.time_s, s_.rim.vx, s_.road.force_z_N, s_.terrain.load_totals.force_N[2]);
    if (t_.stages().end_rolling_when_afloat() && hydroplaning_.afloat(loading_.load_N)) {
      afloat_ = true;
      return true;
    }
    if (t_.stages().end_rolling_past_the_water() && past_the_water()) return true;
  }
  if (s_.time_s < window_start_s_) return false;
  window_.add(s_);
  return false;
}

void TyreRun::end_stage() {
  switch (stage_) {
    case kTransferCheck:
      transfer_check_results(transfer_, mean_radius_of(model_->mesh, s_, centre_) - centre_r0_m_, s_.energy,
                             record_->results());
      break;
    case kLoading:
      end_loading();
      break;
    case kRolling:
      end_rolling();
      break;
    case kDone:
      break;
  }
  stage_ = static_cast<Stage>(stage_ + 1);
  stage_begun_ = false;
}

void TyreRun::end_loading() {
  if (t_.stages().loading_s() <= 0) return;
  nlohmann::json& results = record_->results();
  loading_results(loading_, s_, ground(), results);
  // The rim's drop below where the undeformed tyre would touch the undisturbed
  // terrain surface z = 0: the sinkage less the tyre's deflection. The sinkage
  // (the rut below the undisturbed surface, thesis 5.3, 6.2) is the coupler's.
  if (port_ && !loaded_before_terrain()) results["rim_drop_m"] = free_radius(*model_, s_) - s_.rim.z;
  // On a terrain solver the footprint is the coupler's (contact_pressure.png);
  // a tyre loaded on its road before the terrain is placed has the road's.
  if (!port_ || loaded_before_terrain()) {
    // Thesis Figure 4.3: the footprint's pressure, its mean (load over the
    // road-facing area) and its peak (a node's force over its share).
    results["contact_pressure_max_Pa"] = write_footprint(record_->out_dir(), *model_, s_);
    results["contact_pressure_mean_Pa"] = s_.road.contact_area_m2 > 0 ? s_.road.force_z_N / s_.road.contact_area_m2
                                                                      : 0.0;
  }
  s_.damping_per_s = 0.0;
}

void TyreRun::end_rolling() {
  if (t_.stages().rolling_s() <= 0) return;
  nlohmann::json& results = record_->results();
  rolling_results(window_, s_, ground(), results);
  if (road_under_terrain()) report_hydroplaning_now();
  const auto& rim = t_.rim();
  results["drive_torque_Nm"] = rim.spin_case() == sc::RimSpec::kDriveTorqueNm ? rim.drive_torque_nm() : 0.0;
  results["averaging_window_s"] = window_length_s_;
}

WaterEnd TyreRun::water_end_now() const {
  const double unloaded = loading_.unloaded_radius_m;
  return water_end(scene_, unloaded, record_->results().value("loaded_radius_m", unloaded), s_.road.height_m);
}

bool TyreRun::past_the_water() const {
  const WaterEnd end = water_end_now();
  return s_.rim.x + end.tread_lead_m >= end.x_m + std::fabs(s_.rim.vx) * kHydroplaningFilter_s;
}

void TyreRun::report_hydroplaning_now() {
  if (report_hydroplaning(hydroplaning_, loading_.load_N, s_.rim.x, water_end_now(), afloat_, csv_interval_s_,
                          *record_))
    hydroplaning_curve_ = true;
}

}  // namespace tyre_fe

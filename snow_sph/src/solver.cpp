#include "snow_sph/solver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <omp.h>

#include "cosim/error.hpp"
#include "cosim/parallel.hpp"
#include "cosim/penalty_contact.hpp"
#include "cosim/ramp.hpp"
#include "snow_sph/boundaries.hpp"
#include "snow_sph/gradient_correction.hpp"
#include "snow_sph/placement.hpp"
#include "snow_sph/cylinder_contact.hpp"

namespace snow_sph {

double EnergyBalance::relative_error() const {
  const double scale = std::max({std::abs(kinetic), std::abs(internal), std::abs(external_work),
                                 std::abs(viscous_dissipation), 1e-30});
  return std::abs(total() - initial_total) / scale;
}

double RigidBody::applied_force_z_now(double t) const {
  return cosim::ramp(cosim::RampCurve::smootherstep, t, ramp_time, applied_force_z_full);
}

Solver::Solver(Model& model) : m_(model) {}

bool Solver::finite() const {
  const Particles& p = m_.particles;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (!std::isfinite(p.x[i] + p.y[i] + p.z[i] + p.vx[i] + p.vy[i] + p.vz[i] + p.density[i] +
                       p.sxx[i] + p.syy[i] + p.szz[i] + p.sxy[i] + p.syz[i] + p.sxz[i]))
      return false;
  }
  for (const auto& b : m_.bodies)
    if (!std::isfinite(b.z + b.vz)) return false;
  return true;
}

namespace {

// One particle's stable step: h / (c + |v|) (Courant) and sqrt(h / |a|), and
// which of the two is the smaller.
struct ParticleLimit {
  double dt = 1e30, speed = 0.0, acceleration = 0.0;
  bool by_acceleration = false;
};
ParticleLimit particle_limit(const Particles& p, std::size_t i, double h) {
  ParticleLimit l;
  l.speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  l.dt = h / (p.sound_speed[i] + l.speed);
  l.acceleration = std::sqrt(p.ax[i] * p.ax[i] + p.ay[i] * p.ay[i] + p.az[i] * p.az[i]);
  if (l.acceleration > 0 && std::sqrt(h / l.acceleration) < l.dt)
    l.dt = std::sqrt(h / l.acceleration), l.by_acceleration = true;
  return l;
}

}  // namespace

double Solver::stability_limit_dt() const {
  const Particles& p = m_.particles;
  const double h = m_.kernel.h;
  double limit = 1e30;
  // Particles outside the active domain are not integrated: they rest, and their
  // accelerations are those of their last active step (a splash resting against a
  // side wall, whose acceleration the wall's push piled up to 1.3e9 m/s^2 before
  // wall_repulsion skipped resting particles, held a hydroplaning run at 20 sub-steps).
  for (std::size_t i = 0; i < p.n_real; ++i)
    if (p.active[i]) limit = std::min(limit, particle_limit(p, i, h).dt);
  if (!m_.bodies.empty() && m_.settings.contact_stiffness > 0) {
    double m_min = 1e30;
    for (std::size_t i = 0; i < p.n_real; ++i) m_min = std::min(m_min, p.mass[i]);
    // Penalty spring: omega dt < 2 is the central-difference limit.
    limit = std::min(limit, 2.0 * std::sqrt(m_min / m_.settings.contact_stiffness));
  }
  if (coupled_) limit = std::min(limit, surface_contact_limit_dt());
  return limit;
}

std::string Solver::limit_cause() const {
  // The particle that sets the limit, and by which criterion.
  const Particles& p = m_.particles;
  const double h = m_.kernel.h;
  double limit = 1e30;
  std::size_t worst = p.n_real;
  ParticleLimit worst_limit;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (!p.active[i]) continue;  // as stability_limit_dt()
    const ParticleLimit l = particle_limit(p, i, h);
    if (l.dt < limit) limit = l.dt, worst = i, worst_limit = l;
  }
  if (worst == p.n_real) return "contact penalty";
  // Its density and pressure too: a water particle whose density was driven
  // through zero shows a sound speed above c0 (c0 rho0 / |rho| for s = 0).
  const std::string where = "particle " + std::to_string(p.id[worst]) + " at (" + cosim::number_text(p.x[worst]) +
                            ", " + cosim::number_text(p.y[worst]) + ", " + cosim::number_text(p.z[worst]) +
                            ") m, density " + cosim::number_text(p.density[worst]) + " kg/m^3, pressure " +
                            cosim::number_text(p.pressure[worst]) + " Pa";
  if (worst_limit.by_acceleration)
    return "acceleration " + cosim::number_text(worst_limit.acceleration) + " m/s^2 of " + where;
  return "sound speed " + cosim::number_text(p.sound_speed[worst]) + " m/s + speed " +
         cosim::number_text(worst_limit.speed) + " m/s of " + where;
}

double Solver::stable_dt() const {
  const double limit = stability_limit_dt();
  smallest_limit_dt_ = std::min(smallest_limit_dt_, limit);
  const double imposed = m_.settings.imposed_dt_s();
  if (imposed > 0.0) {
    if (imposed > limit)
      throw cosim::Error((m_.settings.coupling_window_s > 0.0 ? "the coupling window " : "time.fixed_dt_s = ") +
                         cosim::number_text(imposed) + " s exceeds the stable limit " + cosim::number_text(limit) +
                         " s at t = " + cosim::number_text(time_) + " s (" + limit_cause() + ")");
    return imposed;
  }
  return m_.settings.cfl * limit;
}

void Solver::rebuild_if_needed(bool force) {
  Particles& p = m_.particles;
  const double half_skin = 0.5 * m_.settings.skin;
  bool rebuild = force || ref_x_.size() != p.n_real;
  if (!rebuild) {
    const double limit2 = half_skin * half_skin;
    for (std::size_t i = 0; i < p.n_real && !rebuild; ++i) {
      const double dx = p.x[i] - ref_x_[i], dy = p.y[i] - ref_y_[i], dz = p.z[i] - ref_z_[i];
      rebuild = dx * dx + dy * dy + dz * dz > limit2;
    }
  }
  if (!rebuild) {
    refresh_ghost_kinematics(m_);
    return;
  }
  const double radius = m_.kernel.support + m_.settings.skin;
  p.resize(p.n_real);
  p.permute_real(cell_order(p.x.data(), p.y.data(), p.z.data(), p.n_real, radius));
  make_ghosts(m_, radius);
  if (any_water_) {
    // Particles change order and ghosts only here, so their material flags do too.
    is_water_.resize(p.size());
    water_viscosity_.resize(p.size());
    for (std::size_t j = 0; j < p.size(); ++j) {
      const MaterialModel& mj = m_.materials[p.material[j]];
      const bool water = mj.kind == MaterialModel::Kind::water;
      is_water_[j] = water ? 1.0 : 0.0;
      water_viscosity_[j] = water ? mj.viscosity : 0.0;
    }
  }
  build_neighbour_list(p.x.data(), p.y.data(), p.z.data(), p.n_real, p.size(), radius, list_);
  ref_x_.assign(p.x.begin(), p.x.begin() + p.n_real);
  ref_y_.assign(p.y.begin(), p.y.begin() + p.n_real);
  ref_z_.assign(p.z.begin(), p.z.begin() + p.n_real);
  ++rebuilds_;
  if (domain_) rebuild_lists();  // particles were reordered and ghosts made
}

// Velocity gradient L_i = (1/rho_i) sum_j m_j (v_j - v_i) (x) grad_i W_ij and
// continuity drho_i/dt = -rho_i tr(L_i) (the pair that conserves energy with
// the momentum equation in compute_forces), plus delta-SPH diffusion for water.
void Solver::compute_rates() {
  const bool correct = m_.settings.kernel_gradient_correction;
  switch (m_.kernel.type) {
    case KernelType::cubic:
      return correct ? compute_rates_t<KernelType::cubic, true>() : compute_rates_t<KernelType::cubic, false>();
    case KernelType::quadratic:
      return correct ? compute_rates_t<KernelType::quadratic, true>() : compute_rates_t<KernelType::quadratic, false>();
    case KernelType::quintic:
      return correct ? compute_rates_t<KernelType::quintic, true>() : compute_rates_t<KernelType::quintic, false>();
  }
}

template <KernelType T, bool Correct>
void Solver::compute_rates_t() {
  Particles& p = m_.particles;
  const Kernel k = m_.kernel;
  const double s2 = k.support * k.support;
  const double* g = m_.settings.gravity;
  const double delta = m_.settings.density_diffusion_delta;
  const double eta2 = 0.01 * k.h * k.h;
  pair_f_.resize(list_.index.size());
  pair_inv_.resize(list_.index.size());
  const auto* off = list_.offsets.data();
  const auto* nb = list_.index.data();
  const double* is_water = is_water_.data();
  for_active("sph.rates", [&](std::size_t i) {
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    const MaterialModel& mi = m_.materials[p.material[i]];
    const bool diffuse = delta > 0 && mi.kind == MaterialModel::Kind::water;
    const double c_diff = diffuse ? delta * k.h * mi.eos.c0 : 0.0;
    const double hydro = diffuse ? mi.density0 / (mi.eos.c0 * mi.eos.c0) : 0.0;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0, l4 = 0, l5 = 0, l6 = 0, l7 = 0, l8 = 0;
    // sum_j m_j (x_j - x_i) (x) grad W (symmetric): the correction's matrix.
    double mxx = 0, mxy = 0, mxz = 0, myy = 0, myz = 0, mzz = 0;
    double diffusion = 0.0;
    double count = 0.0;  // a double so that the loop below vectorises as one type
    const double* px = p.x.data(); const double* py = p.y.data(); const double* pz = p.z.data();
    const double* pvx = p.vx.data(); const double* pvy = p.vy.data(); const double* pvz = p.vz.data();
    const double* pm = p.mass.data(); const double* prho = p.density.data();
    float* pf = pair_f_.data();
    float* pinv = pair_inv_.data();
    const std::uint32_t first = off[i];
    const int n_pairs = static_cast<int>(off[i + 1] - first);
    const std::uint32_t* __restrict nbi = nb + first;
    float* __restrict pfi = pf + first;
    float* __restrict pinvi = pinv + first;
    // Branch-free body: pairs beyond the support (list skin) have a zero
    // gradient, so the loop vectorises over neighbours. The summation order is
    // fixed by the pair list, so results do not depend on the thread count.
    {
#pragma omp simd reduction(+ : l0, l1, l2, l3, l4, l5, l6, l7, l8, mxx, mxy, mxz, myy, myz, mzz, count)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        // + 1e-24 m^2 keeps coincident points finite; it is below the rounding
        // of any r^2 within the support (and, unlike max(), vectorises).
        const double r2 = rx * rx + ry * ry + rz * rz + 1e-24;
        count += r2 < s2 ? 1.0 : 0.0;
        const double r = std::sqrt(r2);
        const double f = k.template gradient_over_r_t<T>(r, 1.0 / r);
        pfi[e] = static_cast<float>(f);  // reused by the force pass (same positions)
        pinvi[e] = static_cast<float>(1.0 / (r2 + eta2));
        const double mjf = pm[j] * f;
        const double gx = rx * mjf, gy = ry * mjf, gz = rz * mjf;
        const double dvx = pvx[j] - vxi, dvy = pvy[j] - vyi, dvz = pvz[j] - vzi;
        l0 += dvx * gx, l1 += dvx * gy, l2 += dvx * gz;
        l3 += dvy * gx, l4 += dvy * gy, l5 += dvy * gz;
        l6 += dvz * gx, l7 += dvz * gy, l8 += dvz * gz;
        if constexpr (Correct) {
          mxx -= rx * gx, mxy -= rx * gy, mxz -= rx * gz;
          myy -= ry * gy, myz -= ry * gz, mzz -= rz * gz;
        }
      }
    }
    if (diffuse) {
      const double rho_i = prho[i];
      const double hgx = hydro * g[0], hgy = hydro * g[1], hgz = hydro * g[2];
#pragma omp simd reduction(+ : diffusion)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        const double f = pfi[e];  // from the loop above
        // psi_ij . grad W = 2 (rho_j - rho_i - drho_hydro) (x_ji . grad W) / r^2, and
        // (x_ji . grad W) / r^2 = -F; drho_hydro = rho0/c^2 g . (x_j - x_i).
        // Water neighbours only (is_water = 1 or 0).
        const double drho_h = -(hgx * rx + hgy * ry + hgz * rz);
        const double psi = 2.0 * (prho[j] - rho_i - drho_h);
        diffusion += is_water[j] * psi * (-f) * pm[j] / prho[j];
      }
    }
    double l[9] = {l0, l1, l2, l3, l4, l5, l6, l7, l8};
    if constexpr (Correct) {
      const double m[6] = {mxx, mxy, mxz, myy, myz, mzz};
      correct_velocity_gradient(l, p.density[i], m);
    }
    const double inv_rho = 1.0 / p.density[i];
    lxx_[i] = l[0] * inv_rho, lxy_[i] = l[1] * inv_rho, lxz_[i] = l[2] * inv_rho;
    lyx_[i] = l[3] * inv_rho, lyy_[i] = l[4] * inv_rho, lyz_[i] = l[5] * inv_rho;
    lzx_[i] = l[6] * inv_rho, lzy_[i] = l[7] * inv_rho, lzz_[i] = l[8] * inv_rho;
    p.density_rate[i] = -(l[0] + l[4] + l[8]) + c_diff * diffusion;
    p.neighbour_count[i] = static_cast<std::uint32_t>(count);
  });
}

// Density, then stress: Jaumann rotation of sigma^n and the constitutive
// update with the strain increment D dt (snow: mdpc_update), or the equation
// of state (water). Records stress power for the energy balance.
void Solver::update_materials(double dt) {
  Particles& p = m_.particles;
  const double eps_as = m_.settings.artificial_stress_epsilon;
  for_active("sph.material", [&](std::size_t i) {
    const MaterialModel& mat = m_.materials[p.material[i]];
    const double rho_old = p.density[i];
    // The continuity equation as d(ln rho)/dt = -tr(L) (the rate is rho_i
    // times a strain rate, compute_rates), integrated over the step with the rate
    // held: rho^{n+1} = rho^n exp(dt drho/dt / rho^n). It agrees with
    // rho^n + dt drho/dt to first order and stays positive under any
    // expansion: the forward step drove a splash particle of the hydroplaning
    // run to -19.8 kg/m^3 (1.15 GPa by the Us-Up law) once dt tr(L) passed 1
    // (docs/water.md).
    const double rho = rho_old * std::exp(dt * p.density_rate[i] / rho_old);
    p.density[i] = rho;
    Eigen::Matrix3d L;
    L << lxx_[i], lxy_[i], lxz_[i], lyx_[i], lyy_[i], lyz_[i], lzx_[i], lzy_[i], lzz_[i];
    const Eigen::Matrix3d D = 0.5 * (L + L.transpose());
    Eigen::Matrix3d s;
    s << p.sxx[i], p.sxy[i], p.sxz[i], p.sxy[i], p.syy[i], p.syz[i], p.sxz[i], p.syz[i], p.szz[i];
    const Eigen::Matrix3d s_old = s;
    double plastic = 0.0;
    if (mat.kind == MaterialModel::Kind::snow) {
      const Eigen::Matrix3d W = 0.5 * (L - L.transpose());
      s += dt * (W * s - s * W);  // objective (Jaumann) rotation
      const MdpcStepResult r = mdpc_update(mat.mdpc, D * dt, s, p.eps_vol_pl[i]);
      plastic = r.plastic_work_density_J_per_m3 * p.mass[i] / rho;
      const double K = mat.mdpc.bulk_modulus_Pa(), G = mat.mdpc.shear_modulus_Pa();
      p.sound_speed[i] = std::sqrt((K + 4.0 * G / 3.0) / rho);
    } else {
      const double pr = mat.eos.pressure(rho);
      s = -pr * Eigen::Matrix3d::Identity();
      p.sound_speed[i] = mat.eos.sound_speed(rho);
    }
    p.sxx[i] = s(0, 0), p.syy[i] = s(1, 1), p.szz[i] = s(2, 2);
    p.sxy[i] = s(0, 1), p.syz[i] = s(1, 2), p.sxz[i] = s(0, 2);
    p.pressure[i] = -s.trace() / 3.0;
    p.plastic_work[i] += plastic;
    plastic_increment_[i] = plastic;
    // Stress power with the mid-step stress and mid-step volume.
    const double volume = p.mass[i] * 0.5 * (1.0 / rho_old + 1.0 / rho);
    stress_power_[i] = volume * (0.5 * (s_old + s)).cwiseProduct(D).sum();
    if (eps_as > 0.0) {
      // Gray et al. (2001) eq. 4.7-4.9: repulsive term for tensile principal
      // stresses; for water in tension (p < 0) it is Monaghan's (2000) R = eps |p| / rho^2
      // on every axis, which keeps a splash under negative pressure from clumping.
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
      es.computeDirect(s);
      Eigen::Vector3d rp = Eigen::Vector3d::Zero();
      for (int a = 0; a < 3; ++a)
        if (es.eigenvalues()(a) > 0) rp(a) = -eps_as * es.eigenvalues()(a) / (rho * rho);
      const Eigen::Matrix3d R = es.eigenvectors() * rp.asDiagonal() * es.eigenvectors().transpose();
      rxx_[i] = R(0, 0), ryy_[i] = R(1, 1), rzz_[i] = R(2, 2);
      rxy_[i] = R(0, 1), ryz_[i] = R(1, 2), rxz_[i] = R(0, 2);
    }
  });
}

// a_i = sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + (R_i + R_j) f_ij^4) grad_i W_ij
//       + viscous term (Morris et al. 1997) + g.
// Pi_ij: Monaghan (1992) artificial viscosity.
void Solver::compute_forces() {
  switch (m_.kernel.type) {
    case KernelType::cubic: return compute_forces_t<KernelType::cubic>();
    case KernelType::quadratic: return compute_forces_t<KernelType::quadratic>();
    case KernelType::quintic: return compute_forces_t<KernelType::quintic>();
  }
}

template <KernelType T>
void Solver::compute_forces_t() {
  Particles& p = m_.particles;
  const Kernel k = m_.kernel;
  const double h = k.h;
  const double alpha = m_.settings.av_alpha, beta = m_.settings.av_beta;
  const double* g = m_.settings.gravity;
  const bool art = any_artificial_stress_;
  const double inv_wdx = 1.0 / w_dx_;
  const auto* off = list_.offsets.data();
  const auto* nb = list_.index.data();
  // Ghosts carry the artificial stress of their source, mirrored like stress.
  if (art) {
    if (rxx_.size() < p.size())
      for (auto* v : {&rxx_, &ryy_, &rzz_, &rxy_, &ryz_, &rxz_}) v->resize(p.size(), 0.0);
    for (std::size_t gi = p.n_real; gi < p.size(); ++gi) {
      const auto s = p.ghost_source[gi];
      const ShearFlips f = ghost_shear_flips(m_, p.ghost_planes[gi]);
      rxx_[gi] = rxx_[s], ryy_[gi] = ryy_[s], rzz_[gi] = rzz_[s];
      rxy_[gi] = f.xy * rxy_[s], ryz_[gi] = f.yz * ryz_[s], rxz_[gi] = f.xz * rxz_[s];
    }
  }
  // sigma / rho^2 of every particle, once per step.
  const std::size_t n_all = p.size();
  for (auto* v : {&qxx_, &qyy_, &qzz_, &qxy_, &qyz_, &qxz_}) v->resize(n_all);
  cosim::parallel_for("sph.stress_over_rho2", n_all, [&](std::size_t i) {
    const double inv = 1.0 / (p.density[i] * p.density[i]);
    qxx_[i] = p.sxx[i] * inv, qyy_[i] = p.syy[i] * inv, qzz_[i] = p.szz[i] * inv;
    qxy_[i] = p.sxy[i] * inv, qyz_[i] = p.syz[i] * inv, qxz_[i] = p.sxz[i] * inv;
  });
  const double* qxx = qxx_.data(); const double* qyy = qyy_.data(); const double* qzz = qzz_.data();
  const double* qxy = qxy_.data(); const double* qyz = qyz_.data(); const double* qxz = qxz_.data();
  const bool any_water = any_water_;
  const double damping = m_.settings.damping_per_s;
  const double* rxx = rxx_.data(); const double* ryy = ryy_.data(); const double* rzz = rzz_.data();
  const double* rxy = rxy_.data(); const double* ryz = ryz_.data(); const double* rxz = rxz_.data();
  const double* water_viscosity = water_viscosity_.data();
  const bool domain = domain_;
  const double* frozen = frozen_.data();
  for_active("sph.forces", [&](std::size_t i) {
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    const double rhoi = p.density[i], ci = p.sound_speed[i];
    const double axx = qxx[i], ayy = qyy[i], azz = qzz[i];
    const double axy = qxy[i], ayz = qyz[i], axz = qxz[i];
    const double mu_i = any_water ? water_viscosity[i] : 0.0;
    double fx = 0, fy = 0, fz = 0;      // stress + artificial stress
    double vx_ = 0, vy_ = 0, vz_ = 0;   // viscous (artificial + physical)
    const double* px = p.x.data(); const double* py = p.y.data(); const double* pz = p.z.data();
    const double* pvx = p.vx.data(); const double* pvy = p.vy.data(); const double* pvz = p.vz.data();
    const double* pm = p.mass.data(); const double* prho = p.density.data();
    const double* pc = p.sound_speed.data();
    const float* pf = pair_f_.data();
    const float* pinv = pair_inv_.data();
    const std::uint32_t first = off[i];
    const int n_pairs = static_cast<int>(off[i + 1] - first);
    const std::uint32_t* __restrict nbi = nb + first;
    const float* __restrict pfi = pf + first;
    const float* __restrict pinvi = pinv + first;
    // Branch-free bodies: pairs beyond the support (list skin) have F = 0 and
    // coincident pairs r = 0, so neither adds anything, and the loops
    // vectorise over neighbours. F and 1/(r^2 + 0.01 h^2) come from the rates pass.
    {
#pragma omp simd reduction(+ : fx, fy, fz, vx_, vy_, vz_)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        const double f = pfi[e];
        const double mj = pm[j];
        const double gx = rx * f, gy = ry * f, gz = rz * f;
        const double bxx = axx + qxx[j], byy = ayy + qyy[j], bzz = azz + qzz[j];
        const double bxy = axy + qxy[j], byz = ayz + qyz[j], bxz = axz + qxz[j];
        fx += mj * (bxx * gx + bxy * gy + bxz * gz);
        fy += mj * (bxy * gx + byy * gy + byz * gz);
        fz += mj * (bxz * gx + byz * gy + bzz * gz);
        const double dvx = vxi - pvx[j], dvy = vyi - pvy[j], dvz = vzi - pvz[j];
        const double vr = dvx * rx + dvy * ry + dvz * rz;
        // Pi_ij acts on approaching pairs only (vr < 0): mu = 0 otherwise.
        const double mu = h * std::min(vr, 0.0) * pinvi[e];
        const double visc = (-alpha * 0.5 * (ci + pc[j]) * mu + beta * mu * mu) * 2.0 / (rhoi + prho[j]);
        vx_ -= mj * visc * gx, vy_ -= mj * visc * gy, vz_ -= mj * visc * gz;
      }
    }
    if (art) {
      const double rxx_i = rxx[i], ryy_i = ryy[i], rzz_i = rzz[i];
      const double rxy_i = rxy[i], ryz_i = ryz[i], rxz_i = rxz[i];
#pragma omp simd reduction(+ : fx, fy, fz)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        const double r = std::sqrt(rx * rx + ry * ry + rz * rz);
        const double f = pfi[e];  // from the rates pass
        const double gx = rx * f, gy = ry * f, gz = rz * f;
        const double fw = k.template value_t<T>(r) * inv_wdx;
        const double fn = pm[j] * fw * fw * fw * fw;
        const double cxx = rxx_i + rxx[j], cyy = ryy_i + ryy[j], czz = rzz_i + rzz[j];
        const double cxy = rxy_i + rxy[j], cyz = ryz_i + ryz[j], cxz = rxz_i + rxz[j];
        fx += fn * (cxx * gx + cxy * gy + cxz * gz);
        fy += fn * (cxy * gx + cyy * gy + cyz * gz);
        fz += fn * (cxz * gx + cyz * gy + czz * gz);
      }
    }
    if (mu_i > 0.0) {
      // Morris et al. (1997) viscosity with neighbours of any water material.
#pragma omp simd reduction(+ : vx_, vy_, vz_)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        const double f = pfi[e];
        const double mu_sum = mu_i + water_viscosity[j];
        const double coef = pm[j] * mu_sum / (rhoi * prho[j]) * (rx * rx + ry * ry + rz * rz) * f * pinvi[e];
        vx_ += coef * (vxi - pvx[j]), vy_ += coef * (vyi - pvy[j]), vz_ += coef * (vzi - pvz[j]);
      }
    }
    if (domain) {
      // Stress of resting (inactive) neighbours on this particle: the part of
      // the pair force that no moving particle's stress power balances, so its
      // work is external work of the resting terrain (docs/coupling.md).
      double bx = 0, by = 0, bz = 0;
#pragma omp simd reduction(+ : bx, by, bz)
      for (int e = 0; e < n_pairs; ++e) {
        const std::uint32_t j = nbi[e];
        const double rx = xi - px[j], ry = yi - py[j], rz = zi - pz[j];
        const double w = frozen[j] * pm[j] * pfi[e];
        bx += w * (qxx[j] * rx + qxy[j] * ry + qxz[j] * rz);
        by += w * (qxy[j] * rx + qyy[j] * ry + qyz[j] * rz);
        bz += w * (qxz[j] * rx + qyz[j] * ry + qzz[j] * rz);
      }
      boundary_power_[i] = p.mass[i] * (vxi * bx + vyi * by + vzi * bz);
    }
    // Quasi-static damping (dynamic relaxation), counted as viscous.
    vx_ -= damping * vxi, vy_ -= damping * vyi, vz_ -= damping * vzi;
    p.ax[i] = fx + vx_ + g[0];
    p.ay[i] = fy + vy_ + g[1];
    p.az[i] = fz + vz_ + g[2];
    viscous_power_[i] = -p.mass[i] * (vxi * vx_ + vyi * vy_ + vzi * vz_);
  });
}

// The rigid bodies' normal damper: a fraction of critical, approaching and
// separating (cosim::penalty::Damping::both_ways).
constexpr double kBodyContactDampingRatio = 0.2;

// Penalty contact of particles (spheres of radius dx/2) with rigid
// cylinders, Coulomb friction regularised so that sticking stops the relative
// sliding within one step.
void Solver::compute_contact(double dt) {
  Particles& p = m_.particles;
  const double k_n = m_.settings.contact_stiffness;
  const double rc = 0.5 * m_.settings.spacing;
  double stored = 0.0;
  for (auto& b : m_.bodies) {
    std::fill(contact_fx_.begin(), contact_fx_.end(), 0.0);
    std::fill(contact_fy_.begin(), contact_fy_.end(), 0.0);
    std::fill(contact_fz_.begin(), contact_fz_.end(), 0.0);
    std::fill(contact_dissipation_.begin(), contact_dissipation_.end(), 0.0);
    cosim::parallel_for("sph.contact", p.n_real, [&](std::size_t i) {
      const CylinderContact c = cylinder_contact(p.x[i] - b.x, p.y[i] - b.y, p.z[i], b.radius, b.z, b.z + b.thickness, rc);
      if (!(c.depth > 0.0)) return;
      const double nx = c.nx, ny = c.ny, nz = c.nz, depth = c.depth;
      const double m = p.mass[i];
      const double wx = p.vx[i], wy = p.vy[i], wz = p.vz[i] - b.vz;  // relative velocity
      const double vn = wx * nx + wy * ny + wz * nz;
      const double damping = cosim::penalty::damping_coefficient(kBodyContactDampingRatio, k_n, m);
      const cosim::penalty::NormalForce normal =
          cosim::penalty::normal_force(k_n, depth, vn, damping, cosim::penalty::Damping::both_ways);
      const double fn = normal.force_N;
      const double tx = wx - vn * nx, ty = wy - vn * ny, tz = wz - vn * nz;
      const double vt = std::sqrt(tx * tx + ty * ty + tz * tz);
      double ft = 0.0;
      if (vt > 0.0) ft = cosim::penalty::velocity_stop_friction(b.friction * fn, m, vt, dt);
      const double fx = fn * nx - (vt > 0 ? ft * tx / vt : 0.0);
      const double fy = fn * ny - (vt > 0 ? ft * ty / vt : 0.0);
      const double fz = fn * nz - (vt > 0 ? ft * tz / vt : 0.0);
      p.ax[i] += fx / m, p.ay[i] += fy / m, p.az[i] += fz / m;
      contact_fx_[i] = fx, contact_fy_[i] = fy, contact_fz_[i] = fz;
      contact_dissipation_[i] = (ft * vt + cosim::penalty::approach_damping_power(normal, vn)) * dt;
    });
    double fx = 0, fy = 0, fz = 0, dissipated = 0;
    for (std::size_t i = 0; i < p.n_real; ++i) {
      fx -= contact_fx_[i], fy -= contact_fy_[i], fz -= contact_fz_[i];
      dissipated += contact_dissipation_[i];
      if (contact_fx_[i] != 0 || contact_fy_[i] != 0 || contact_fz_[i] != 0) {
        const double fn = std::sqrt(contact_fx_[i] * contact_fx_[i] + contact_fy_[i] * contact_fy_[i] +
                                    contact_fz_[i] * contact_fz_[i]);
        stored += 0.5 * fn * fn / k_n;
      }
    }
    b.contact_force_x_domain = fx, b.contact_force_y_domain = fy, b.contact_force_z_domain = fz;
    energy_.contact_dissipation += dissipated;
  }
  energy_.contact_elastic = stored;
}

void Solver::couple(const SurfaceContactParameters& parameters) {
  coupled_ = true;
  surface_params_ = parameters;
  // Water between a facet and a wall (the floor under a tread) in a film
  // thinner than half a particle drains out of the flow (docs/water.md,
  // "Films thinner than a particle"): half of such a particle no longer fits.
  surface_params_.walls.clear();
  for (const MirrorPlane& plane : m_.planes)
    if (!plane.symmetry) surface_params_.walls.push_back({plane.axis, plane.position, plane.inside_sign});
  surface_params_.drain_film_m = parameters.particle_radius_m;
}

double Solver::surface_contact_limit_dt() const {
  if (!coupled_) return 0.0;
  const Particles& p = m_.particles;
  double m_min = 1e30;
  for (std::size_t i = 0; i < p.n_real; ++i) m_min = std::min(m_min, p.mass[i]);
  return surface_contact_stable_dt(m_min, surface_params_.stiffness_N_per_m);
}

void Solver::contact_surface(const ContactSurface* surface, std::uint64_t exchange) {
  last_surface_ = surface;
  if (!surface) return;
  // Exchange 0 is made with the particles at t_0, before the first step.
  // The contact's step is the window over which its force is held.
  const double dt = exchange == 0 ? stable_dt() : window_dt_;
  if (exchange == 0 && place_around_owner_) {
    // The terrain placed around the body at rest (placement.hpp): what it
    // occupies, and the particles that would overlap it, are not terrain; the
    // state at t_0 is that of the particles left.
    const Particles& p = m_.particles;
    const auto inside = particles_in_body(*surface, p.n_real, p.x.data(), p.y.data(), p.z.data(),
                                          surface_params_.particle_radius_m);
    if (!inside.empty()) {
      displaced_mass_kg_ += remove_particles(inside).first;
      displaced_particles_ += inside.size();
      prepare();
    }
  }
  if (exchange == 0) {
    // Multi-rate: the owner holds these loads over the window (docs/coupling.md).
    held_load_limit_dt_ = held_load_window_limit(*surface, surface_params_.stiffness_N_per_m, m_.settings.spacing);
    if (dt > held_load_limit_dt_)
      throw cosim::Error("the coupling window " + cosim::number_text(dt) + " s is above the limit " +
                         cosim::number_text(held_load_limit_dt_) + " s for holding the contact loads on the "
                         "surface's lightest node per area (docs/coupling.md); use coupling.scheme: COMMON_STEP "
                         "or a softer coupling.contact_stiffness_scale");
  }
  // The owner sent this surface after completing the window of the last
  // exchange, whose loads the window's kicks gave the particles: that window counts.
  if (exchange > 0)
    for (int c = 0; c < 3; ++c) surface_impulse_[c] += window_surface_kick_ * surface_force_[c];
  window_surface_kick_ = 0.0;
  Particles& p = m_.particles;
  const std::size_t n = p.n_real;
  a_before_.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    a_before_[3 * i] = p.ax[i], a_before_[3 * i + 1] = p.ay[i], a_before_[3 * i + 2] = p.az[i];
  drainable_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    drainable_[i] = m_.materials[p.material[i]].kind == MaterialModel::Kind::water ? 1 : 0;
  surface_contact(*surface, surface_params_, n, p.x.data(), p.y.data(), p.z.data(), p.vx.data(), p.vy.data(),
                  p.vz.data(), p.mass.data(), dt, p.ax.data(), p.ay.data(), p.az.data(), surface_loads_,
                  &friction_history_, p.id.data(), drainable_.data());
  // The force of the surface on each particle, held over the next window (its
  // sub-steps and the work it does in their kicks), and its total (momentum
  // exchanged with the owner).
  double fx = 0.0, fy = 0.0, fz = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dfx = p.mass[i] * (p.ax[i] - a_before_[3 * i]), dfy = p.mass[i] * (p.ay[i] - a_before_[3 * i + 1]),
                 dfz = p.mass[i] * (p.az[i] - a_before_[3 * i + 2]);
    p.surface_fx[i] = dfx, p.surface_fy[i] = dfy, p.surface_fz[i] = dfz;
    fx += dfx, fy += dfy, fz += dfz;
  }
  surface_force_[0] = fx, surface_force_[1] = fy, surface_force_[2] = fz;
  surface_held_ = true;
  if (!surface_loads_.drained.empty()) drain(surface_loads_.drained);
  // Where the owner's next surface must reach down to: the particles' reach over the next window.
  const double next_window = m_.settings.coupling_window_s > 0.0 ? m_.settings.coupling_window_s : dt;
  surface_loads_.particle_reach_z_m = particle_reach_z(p.n_real, p.z.data(), p.vz.data(), p.az.data(), next_window,
                                                       surface_params_.particle_radius_m);
}

// Removes the drained particles (ascending indices) from the flow: their mass
// leaves the terrain and their kinetic energy the balance; ghosts and lists are
// made anew for the particles that stay.
void Solver::drain(const std::vector<std::uint32_t>& drained) {
  const auto [mass, kinetic] = remove_particles(drained);
  energy_.drained_kinetic += kinetic;
  drained_mass_kg_ += mass;
  drained_particles_ += drained.size();
}

std::pair<double, double> Solver::remove_particles(const std::vector<std::uint32_t>& gone) {
  Particles& p = m_.particles;
  std::vector<std::uint32_t> keep;
  keep.reserve(p.n_real - gone.size());
  std::size_t next = 0;
  double mass = 0.0, kinetic = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (next < gone.size() && gone[next] == i) {
      kinetic += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      mass += p.mass[i];
      ++next;
      continue;
    }
    keep.push_back(static_cast<std::uint32_t>(i));
  }
  p.resize(p.n_real);
  p.permute_real(keep);
  p.n_real = keep.size();
  p.resize(p.n_real);
  rebuild_if_needed(true);
  return {mass, kinetic};
}

void Solver::start_clock_at(double time_s) {
  if (steps_ != 0) throw cosim::Error("the terrain's clock can be set only before its first step");
  time_ = time_s;
}

void Solver::prepare() {
  Particles& p = m_.particles;
  prepared_ = true;
  w_dx_ = m_.kernel.value(m_.settings.spacing);
  any_water_ = false;
  for (const auto& mat : m_.materials) any_water_ = any_water_ || mat.kind == MaterialModel::Kind::water;
  any_artificial_stress_ = m_.settings.artificial_stress_epsilon > 0;
  rebuild_if_needed(true);
  const std::size_t n = p.n_real;
  for (auto* v : {&lxx_, &lxy_, &lxz_, &lyx_, &lyy_, &lyz_, &lzx_, &lzy_, &lzz_, &stress_power_,
                  &viscous_power_, &contact_fx_, &contact_fy_, &contact_fz_,
                  &contact_dissipation_, &plastic_increment_, &wall_power_})
    v->assign(n, 0.0);
  for (auto* v : {&rxx_, &ryy_, &rzz_, &rxy_, &ryz_, &rxz_}) v->assign(p.size(), 0.0);
  compute_rates();
  update_materials(0.0);
  refresh_ghost_state(m_);
  compute_forces();
  wall_repulsion(m_, p.ax.data(), p.ay.data(), p.az.data(), wall_power_.data());
  compute_contact(1e-30 + stable_dt());
}

void Solver::initialise() {
  if (!prepared_) prepare();
  if (domain_) {
    // Every particle's acceleration is that of the state at t_0 (prepare()), so
    // those inside the domain move from the first step.
    update_activity(last_surface_);
    for (std::size_t i = 0; i < m_.particles.n_real; ++i) m_.particles.moving[i] = m_.particles.active[i];
    rebuild_lists();
  }
  energy_ = EnergyBalance{};
  energy_.contact_elastic = 0.0;
  update_energy(0.0);
  energy_.initial_total = energy_.total();
}

void Solver::update_energy(double dt) {
  const Particles& p = m_.particles;
  double ke = 0, el = 0, ip = 0, vp = 0, pl = 0, gw = 0;
  const double* g = m_.settings.gravity;
  // Resting particles (outside the active domain) have v = 0 and no stress
  // power this step; their entries of the per-step arrays are stale.
  double bp = 0.0;
  if (domain_)
    for (std::uint32_t i : force_list_)
      ip += stress_power_[i], vp += viscous_power_[i], pl += plastic_increment_[i], bp += boundary_power_[i];
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const double m = p.mass[i];
    ke += 0.5 * m * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    if (!domain_) ip += stress_power_[i], vp += viscous_power_[i], pl += plastic_increment_[i];
    gw += m * (g[0] * p.vx[i] + g[1] * p.vy[i] + g[2] * p.vz[i]) + wall_power_[i];
    const MaterialModel& mat = m_.materials[p.material[i]];
    if (mat.kind == MaterialModel::Kind::water) {
      el += m * mat.eos.energy_per_mass(p.density[i]);
    } else {
      // (1/2) sigma : C^-1 : sigma V, isotropic: p^2/(2K) + q^2/(6G)
      const double K = mat.mdpc.bulk_modulus_Pa(), G = mat.mdpc.shear_modulus_Pa();
      const double pr = p.pressure[i];
      const double dxx = p.sxx[i] + pr, dyy = p.syy[i] + pr, dzz = p.szz[i] + pr;
      const double j2 = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + p.sxy[i] * p.sxy[i] +
                        p.syz[i] * p.syz[i] + p.sxz[i] * p.sxz[i];
      el += (pr * pr / (2.0 * K) + j2 / (2.0 * G)) * m / p.density[i];
    }
  }
  double body_work = 0.0;
  for (const auto& b : m_.bodies) {
    ke += 0.5 * b.mass_domain * b.vz * b.vz;
    if (b.prescribed_velocity)
      body_work += -b.contact_force_z_domain * b.vz;  // the drive balances contact
    else
      body_work += b.applied_force_z_now(time_) / b.symmetry_factor * b.vz;
  }
  energy_.kinetic = ke;
  energy_.elastic = el;
  energy_.internal += ip * dt;
  energy_.viscous_dissipation += vp * dt;
  energy_.plastic_dissipation += pl;
  energy_.external_work += (gw + body_work + bp) * dt;
}

void Solver::set_active_domain(double margin_m, double wake_speed_m_per_s, double wake_limit_m) {
  active_margin_m_ = margin_m;
  wake_speed_ = wake_speed_m_per_s;
  wake_limit_m_ = wake_limit_m;
  domain_ = coupled_ && margin_m > 0.0;
}

template <class Body>
void Solver::for_active(const char* label, Body&& body) {
  if (domain_)
    cosim::parallel_for(label, force_list_.size(), [&](std::size_t k) { body(force_list_[k]); });
  else
    cosim::parallel_for(label, m_.particles.n_real, body);
}

void Solver::rebuild_lists() {
  Particles& p = m_.particles;
  force_list_.clear(), move_list_.clear();
  for (std::size_t i = 0; i < p.n_real; ++i) {
    if (p.active[i]) force_list_.push_back(static_cast<std::uint32_t>(i));
    if (p.moving[i]) move_list_.push_back(static_cast<std::uint32_t>(i));
  }
  frozen_.resize(p.size());
  boundary_power_.resize(p.n_real, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    frozen_[i] = p.active[i < p.n_real ? i : p.ghost_source[i]] ? 0.0 : 1.0;
}

void Solver::update_activity(const ContactSurface* surface) {
  Particles& p = m_.particles;
  // The box of the surface near the terrain, grown by the margin (x and y).
  double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
  if (surface)
    for (std::size_t k = 0; k < surface->x.size(); ++k) {
      const double c[3] = {surface->x[k], surface->y[k], surface->z[k]};
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], c[a] - active_margin_m_), hi[a] = std::max(hi[a], c[a] + active_margin_m_);
    }
  const double wake2 = wake_speed_ * wake_speed_;
  // A moving particle stays active within the wake limit (grown beyond the margin), if there is one.
  const double w = wake_limit_m_ - active_margin_m_;
  const double near_lo[2] = {lo[0] - w, lo[1] - w}, near_hi[2] = {hi[0] + w, hi[1] + w};
  double removed = 0.0;
  for (std::size_t i = 0; i < p.n_real; ++i) {
    const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i];
    // In plan only: the load of the surface spreads down through the whole
    // depth below it (a margin in depth froze the snow under a loaded tyre and
    // made the layer stiffer: +26 % vertical force on the coarse indentation).
    const bool inside = p.x[i] >= lo[0] && p.x[i] <= hi[0] && p.y[i] >= lo[1] && p.y[i] <= hi[1];
    const bool near = wake_limit_m_ <= 0.0 || (p.x[i] >= near_lo[0] && p.x[i] <= near_hi[0] &&
                                               p.y[i] >= near_lo[1] && p.y[i] <= near_hi[1]);
    const bool next = inside || (p.active[i] && v2 > wake2 && near);
    if (p.active[i] && !next) {
      // Comes to rest where it is: its kinetic energy leaves the balance as a loss.
      removed += 0.5 * p.mass[i] * v2;
      p.vx[i] = p.vy[i] = p.vz[i] = 0.0;
    }
    // A particle coming in moves from the step after its first force pass.
    p.moving[i] = p.active[i] && next;
    p.active[i] = next;
  }
  energy_.deactivated_kinetic += removed;
  rebuild_lists();
  active_share_sum_ += p.n_real ? double(force_list_.size()) / double(p.n_real) : 1.0;
  ++active_samples_;
}

StepStats Solver::step() {
  const StepStats stats = advance();
  complete_step();
  return stats;
}

StepStats Solver::advance() {
  const double window = m_.settings.coupling_window_s;
  if (!coupled_ || !(window > 0.0)) return advance_by(stable_dt());
  // Coupled: one step per window while the terrain's Courant number stays at or
  // below 1 (as the window was agreed); beyond, k equal sub-steps at the CFL
  // factor, re-planned for what is left if the limit falls further inside.
  StepStats stats;
  stats.dt = window;
  stats.substeps = 0;
  double left = window;
  std::uint64_t pieces = 0;  // sub-steps left, this one included
  double h = window;
  for (;;) {
    const double limit = stability_limit_dt();
    smallest_limit_dt_ = std::min(smallest_limit_dt_, limit);
    if (pieces == 0 || h > limit) {
      pieces = left > limit ? static_cast<std::uint64_t>(std::ceil(left / (m_.settings.cfl * limit))) : 1;
      if (stats.substeps + pieces > kMaxSubsteps)
        throw cosim::Error("the terrain's stable limit " + cosim::number_text(limit) + " s at t = " +
                           cosim::number_text(time_) + " s (" + limit_cause() + ") would take more than " +
                           std::to_string(kMaxSubsteps) + " sub-steps in the coupling window " +
                           cosim::number_text(window) + " s");
      h = left / static_cast<double>(pieces);
    }
    const bool last = pieces == 1;
    const StepStats sub = advance_by(last ? left : h);  // the last closes the window
    stats.clamped += sub.clamped;
    stats.rebuilt = stats.rebuilt || sub.rebuilt;
    ++stats.substeps;
    if (last) break;
    hold_surface_force();
    complete_step();
    left -= h;
    --pieces;
  }
  window_dt_ = window;
  if (stats.substeps > 1) ++substepped_windows_;
  most_substeps_ = std::max(most_substeps_, stats.substeps);
  return stats;
}

void Solver::hold_surface_force() {
  if (!surface_held_) return;
  Particles& p = m_.particles;
  auto add = [&](std::size_t i) {
    const double inv_m = 1.0 / p.mass[i];
    p.ax[i] += p.surface_fx[i] * inv_m, p.ay[i] += p.surface_fy[i] * inv_m, p.az[i] += p.surface_fz[i] * inv_m;
  };
  if (domain_)
    for (std::uint32_t i : move_list_) add(i);
  else
    for (std::size_t i = 0; i < p.n_real; ++i) add(i);
}

StepStats Solver::advance_by(double dt) {
  Particles& p = m_.particles;
  StepStats stats;
  stats.dt = dt;
  window_dt_ = dt;
  // Kick: v^{n+1/2} = v^{n-1/2} + a^n (dt_prev + dt)/2 (first step: half kick).
  const double kick = steps_ == 0 ? 0.5 * dt : 0.5 * (dt_prev_ + dt);
  // The coupled surface's force in a^n is kicked with this step's length, not
  // the mean of two: it is held over the window's steps, which change length
  // from window to window when the terrain sub-steps, and its impulse over a
  // window must be the window times the force (for equal steps the two agree).
  const double surface_kick = steps_ == 0 ? kick : dt;
  const double extra = surface_held_ ? surface_kick - kick : 0.0;
  auto kick_drift = [&](std::size_t i) {
    p.vx[i] += kick * p.ax[i], p.vy[i] += kick * p.ay[i], p.vz[i] += kick * p.az[i];
    p.x[i] += dt * p.vx[i], p.y[i] += dt * p.vy[i], p.z[i] += dt * p.vz[i];
  };
  auto kick_held_drift = [&](std::size_t i) {
    const double c = extra / p.mass[i];
    p.vx[i] += kick * p.ax[i] + c * p.surface_fx[i], p.vy[i] += kick * p.ay[i] + c * p.surface_fy[i];
    p.vz[i] += kick * p.az[i] + c * p.surface_fz[i];
    p.x[i] += dt * p.vx[i], p.y[i] += dt * p.vy[i], p.z[i] += dt * p.vz[i];
  };
  // Work of the coupled surface's forces of the last exchange over this kick,
  // with the mean of the velocities before and after it (the central-difference
  // work; the velocity before alone books F^2 dt^2 / 2m too little a step, which
  // grows with the step: docs/coupling.md).
  if (surface_held_) {
    double work = 0.0;
    auto contact_work = [&](std::size_t i) {
      const double fx = p.surface_fx[i], fy = p.surface_fy[i], fz = p.surface_fz[i];
      if (fx == 0.0 && fy == 0.0 && fz == 0.0) return 0.0;
      const double c = 0.5 * extra / p.mass[i];
      const double mx = p.vx[i] + 0.5 * kick * p.ax[i] + c * fx, my = p.vy[i] + 0.5 * kick * p.ay[i] + c * fy,
                   mz = p.vz[i] + 0.5 * kick * p.az[i] + c * fz;
      return surface_kick * (fx * mx + fy * my + fz * mz);
    };
    if (domain_)
      for (std::uint32_t i : move_list_) work += contact_work(i);
    else
      for (std::size_t i = 0; i < p.n_real; ++i) work += contact_work(i);
    energy_.external_work += work;
    window_surface_kick_ += surface_kick;
  }
  if (extra != 0.0) {
    if (domain_)
      cosim::parallel_for("sph.kick_drift", move_list_.size(), [&](std::size_t k) { kick_held_drift(move_list_[k]); });
    else
      cosim::parallel_for("sph.kick_drift", p.n_real, kick_held_drift);
  } else if (domain_) {
    cosim::parallel_for("sph.kick_drift", move_list_.size(), [&](std::size_t k) { kick_drift(move_list_[k]); });
  } else {
    cosim::parallel_for("sph.kick_drift", p.n_real, kick_drift);
  }
  for (auto& b : m_.bodies) {
    if (b.prescribed_velocity) {
      b.vz = b.prescribed_vz;
    } else {
      const double force = b.applied_force_z_now(time_) / b.symmetry_factor + b.contact_force_z_domain;
      b.az = force / b.mass_domain;
      b.vz += kick * b.az;
    }
    b.z += dt * b.vz;
  }
  time_ += dt;
  stats.clamped = clamp_to_walls(m_);
  const std::size_t before = rebuilds_;
  rebuild_if_needed(false);
  stats.rebuilt = rebuilds_ != before;
  compute_rates();
  update_materials(dt);
  refresh_ghost_state(m_);
  compute_forces();
  wall_repulsion(m_, p.ax.data(), p.ay.data(), p.az.data(), wall_power_.data());
  compute_contact(dt);
  step_dt_ = dt;
  return stats;
}

void Solver::complete_step() {
  const Particles& p = m_.particles;
  const double dt = step_dt_;
  update_energy(dt);
  if (any_water_) {
    // Spray that has left the open-top box: the walls are planes that go on
    // above the box, and a splash falling back along one of them is not a flow
    // the box models (docs/water.md, "Films thinner than a particle"). And water
    // whose density has left its valid range: a splash stretched until its
    // continuity density says it is a third empty, or water crushed in a pinch,
    // is no longer a flow the particles resolve (DualSPHysics's RhopOut).
    std::vector<std::uint32_t> spray;
    for (std::size_t i = 0; i < p.n_real; ++i) {
      const MaterialModel& mat = m_.materials[p.material[i]];
      if (mat.kind != MaterialModel::Kind::water) continue;
      const bool out_of_range = !mat.density_valid(p.density[i]);
      if (out_of_range) ++density_out_particles_;
      if (out_of_range || p.z[i] > m_.container_max[2]) spray.push_back(static_cast<std::uint32_t>(i));
    }
    if (!spray.empty()) drain(spray);
  }
  if (domain_) {
    for (std::uint32_t i : force_list_) interactions_ += p.neighbour_count[i];
    if (last_surface_) update_activity(last_surface_);  // no surface: the run has ended
  } else {
    for (std::size_t i = 0; i < p.n_real; ++i) interactions_ += p.neighbour_count[i];
  }
  dt_prev_ = dt;
  ++steps_;
}

double Solver::pressure_at(double x, double y, double z) const {
  const Particles& p = m_.particles;
  const double s2 = m_.kernel.support * m_.kernel.support;
  double num = 0, den = 0;
  for (std::size_t j = 0; j < p.size(); ++j) {
    const double rx = x - p.x[j], ry = y - p.y[j], rz = z - p.z[j];
    const double r2 = rx * rx + ry * ry + rz * rz;
    if (r2 >= s2) continue;
    const double w = m_.kernel.value(std::sqrt(r2)) * p.mass[j] / p.density[j];
    num += w * p.pressure[j];
    den += w;
  }
  return den > 0 ? num / den : 0.0;
}

}  // namespace snow_sph

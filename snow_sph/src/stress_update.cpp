// Stress update: the material stage between the two pair loops (calls into
// mdpc.hpp for snow and water_eos.hpp for water).
#include <cmath>

#include <Eigen/Dense>

#include "snow_sph/stages.hpp"

namespace snow_sph {

// Density, then stress: Jaumann rotation of sigma^n and the constitutive
// update with the strain increment D dt (snow: mdpc_update), or the equation
// of state (water). Records stress power for the energy balance.
void update_stress(Model& m, const ActiveDomain& domain, const PairRates& rates, double dt,
                   SymmetricField& artificial_stress, StepPowers& powers) {
  Particles& p = m.particles;
  const double eps_as = m.settings.artificial_stress_epsilon;
  for_active(domain, p.n_real, "sph.material", [&](std::size_t i) {
    const MaterialModel& mat = m.materials[p.material[i]];
    const double rho_old = p.density[i];
    // The continuity equation as d(ln rho)/dt = -tr(L) (the rate is rho_i
    // times a strain rate, compute_pair_rates), integrated over the step with the rate
    // held: rho^{n+1} = rho^n exp(dt drho/dt / rho^n). It agrees with
    // rho^n + dt drho/dt to first order and stays positive under any
    // expansion: the forward step drove a splash particle of the hydroplaning
    // run to -19.8 kg/m^3 (1.15 GPa by the Us-Up law) once dt tr(L) passed 1
    // (docs/water.md).
    const double rho = rho_old * std::exp(dt * p.density_rate[i] / rho_old);
    p.density[i] = rho;
    Eigen::Matrix3d L;
    L << rates.lxx[i], rates.lxy[i], rates.lxz[i], rates.lyx[i], rates.lyy[i], rates.lyz[i], rates.lzx[i],
        rates.lzy[i], rates.lzz[i];
    const Eigen::Matrix3d D = 0.5 * (L + L.transpose());
    Eigen::Matrix3d s;
    s << p.sxx[i], p.sxy[i], p.sxz[i], p.sxy[i], p.syy[i], p.syz[i], p.sxz[i], p.syz[i], p.szz[i];
    const Eigen::Matrix3d s_old = s;
    double plastic = 0.0;
    int surface = 0;  // the return's surface (mdpc.hpp); 2: the cap
    if (mat.kind == MaterialModel::Kind::snow) {
      const Eigen::Matrix3d W = 0.5 * (L - L.transpose());
      s += dt * (W * s - s * W);  // objective (Jaumann) rotation
      const MdpcStepResult r = mdpc_update(mat.mdpc, D * dt, s, p.eps_vol_pl[i]);
      plastic = r.plastic_work_density_J_per_m3 * p.mass[i] / rho;
      surface = r.surface;
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
    powers.plastic_increment[i] = plastic;
    powers.plastic_cap_increment[i] = surface == 2 ? plastic : 0.0;
    // Stress power with the mid-step stress and mid-step volume.
    const double volume = p.mass[i] * 0.5 * (1.0 / rho_old + 1.0 / rho);
    powers.stress[i] = volume * (0.5 * (s_old + s)).cwiseProduct(D).sum();
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
      SymmetricField& r = artificial_stress;
      r.xx[i] = R(0, 0), r.yy[i] = R(1, 1), r.zz[i] = R(2, 2);
      r.xy[i] = R(0, 1), r.yz[i] = R(1, 2), r.xz[i] = R(0, 2);
    }
  });
}

}  // namespace snow_sph

// Pair forces: the second pair loop of a step, after the ghosts (and halos)
// took the new stress; it reuses the pair factors of the rates pass.
#include <algorithm>
#include <cmath>

#include "cosim/parallel.hpp"
#include "snow_sph/boundaries.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {
namespace {

// Ghosts carry the artificial stress of their source, mirrored like stress.
void mirror_artificial_stress(const Model& m, SymmetricField& R) {
  const Particles& p = m.particles;
  if (R.xx.size() < p.size())
    for (auto* v : R.all()) v->resize(p.size(), 0.0);
  for (std::size_t gi = p.n_real; gi < p.size(); ++gi) {
    const auto s = p.ghost_source[gi];
    const ShearFlips f = ghost_shear_flips(m, p.ghost_planes[gi]);
    R.xx[gi] = R.xx[s], R.yy[gi] = R.yy[s], R.zz[gi] = R.zz[s];
    R.xy[gi] = f.xy * R.xy[s], R.yz[gi] = f.yz * R.yz[s], R.xz[gi] = f.xz * R.xz[s];
  }
}

// sigma / rho^2 of every particle and ghost, once per step.
void compute_stress_over_rho2(const Particles& p, SymmetricField& Q) {
  const std::size_t n_all = p.size();
  for (auto* v : Q.all()) v->resize(n_all);
  cosim::parallel_for("sph.stress_over_rho2", n_all, [&](std::size_t i) {
    const double inv = 1.0 / (p.density[i] * p.density[i]);
    Q.xx[i] = p.sxx[i] * inv, Q.yy[i] = p.syy[i] * inv, Q.zz[i] = p.szz[i] * inv;
    Q.xy[i] = p.sxy[i] * inv, Q.yz[i] = p.syz[i] * inv, Q.xz[i] = p.sxz[i] * inv;
  });
}

// The force pass on one particle i: what it reads of the step, and its sums.
template <KernelType T>
struct ParticleForce {
  Particles& p;
  const Kernel k;
  const double h, alpha, beta;
  const double* g;
  const bool art;
  const double inv_wdx;
  const std::uint32_t* off;
  const std::uint32_t* nb;
  const PairRates& rates;
  const double *qxx, *qyy, *qzz, *qxy, *qyz, *qxz;
  const bool any_water;
  const double damping;
  const double *rxx, *ryy, *rzz, *rxy, *ryz, *rxz;
  const double* water_viscosity;
  const bool domain;
  const double* frozen;
  double* boundary_power;
  double* viscous_power;
  // The parts of viscous_power: Pi_ij, the quasi-static damping, water's viscosity.
  double* artificial_viscous_power;
  double* damping_power;
  double* water_viscous_power;

  // Particle i's viscous power and its parts [W], from its velocity v, the
  // artificial viscosity's acceleration a_pi and the viscous acceleration
  // before the damping a (a - a_pi: water's, exactly 0 without water).
  void book_viscous_powers(std::size_t i, const double (&v)[3], const double (&a_pi)[3], const double (&a)[3]) const {
    const double mi = p.mass[i];
    const double ax = a[0] - damping * v[0], ay = a[1] - damping * v[1], az = a[2] - damping * v[2];
    viscous_power[i] = -mi * (v[0] * ax + v[1] * ay + v[2] * az);
    artificial_viscous_power[i] = -mi * (v[0] * a_pi[0] + v[1] * a_pi[1] + v[2] * a_pi[2]);
    water_viscous_power[i] = -mi * (v[0] * (a[0] - a_pi[0]) + v[1] * (a[1] - a_pi[1]) + v[2] * (a[2] - a_pi[2]));
    damping_power[i] = mi * damping * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }

  void operator()(std::size_t i) const {
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
      const std::uint32_t first = off[i];
      const int n_pairs = static_cast<int>(off[i + 1] - first);
      const std::uint32_t* __restrict nbi = nb + first;
      const float* __restrict pfi = rates.pair_f.data() + first;
      const float* __restrict pinvi = rates.pair_inv.data() + first;
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
      const double avx = vx_, avy = vy_, avz = vz_;  // Pi_ij's part: all the viscous sum holds so far
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
        boundary_power[i] = p.mass[i] * (vxi * bx + vyi * by + vzi * bz);
      }
      book_viscous_powers(i, {vxi, vyi, vzi}, {avx, avy, avz}, {vx_, vy_, vz_});
      // Quasi-static damping (dynamic relaxation), counted as viscous.
      vx_ -= damping * vxi, vy_ -= damping * vyi, vz_ -= damping * vzi;
      p.ax[i] = fx + vx_ + g[0];
      p.ay[i] = fy + vy_ + g[1];
      p.az[i] = fz + vz_ + g[2];
  }
};

template <KernelType T>
void forces_pass(Model& m, const NeighbourList& list, const MaterialFlags& flags, const PairRates& rates,
                 SymmetricField& artificial_stress, SymmetricField& stress_over_rho2, StepPowers& powers,
                 ActiveDomain& active) {
  Particles& p = m.particles;
  const Kernel k = m.kernel;
  const bool art = flags.any_artificial_stress;
  SymmetricField& R = artificial_stress;
  if (art) mirror_artificial_stress(m, R);
  SymmetricField& Q = stress_over_rho2;
  compute_stress_over_rho2(p, Q);
  const ParticleForce<T> force{p,
                               k,
                               k.h,
                               m.settings.av_alpha,
                               m.settings.av_beta,
                               m.settings.gravity,
                               art,
                               1.0 / flags.w_dx,
                               list.offsets.data(),
                               list.index.data(),
                               rates,
                               Q.xx.data(),
                               Q.yy.data(),
                               Q.zz.data(),
                               Q.xy.data(),
                               Q.yz.data(),
                               Q.xz.data(),
                               flags.any_water,
                               m.settings.damping_per_s,
                               R.xx.data(),
                               R.yy.data(),
                               R.zz.data(),
                               R.xy.data(),
                               R.yz.data(),
                               R.xz.data(),
                               flags.water_viscosity.data(),
                               active.on,
                               active.frozen.data(),
                               active.boundary_power.data(),
                               powers.viscous.data(),
                               powers.artificial_viscous.data(),
                               powers.damping.data(),
                               powers.water_viscous.data()};
  for_active(active, p.n_real, "sph.forces", force);
}

}  // namespace

// a_i = sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + (R_i + R_j) f_ij^4) grad_i W_ij
//       + viscous term (Morris et al. 1997) + g.
// Pi_ij: Monaghan (1992) artificial viscosity.
void compute_pair_forces(Model& m, const NeighbourList& list, const MaterialFlags& flags, const PairRates& rates,
                         SymmetricField& artificial_stress, SymmetricField& stress_over_rho2, StepPowers& powers,
                         ActiveDomain& active) {
  switch (m.kernel.type) {
    case KernelType::cubic:
      return forces_pass<KernelType::cubic>(m, list, flags, rates, artificial_stress, stress_over_rho2, powers, active);
    case KernelType::quadratic:
      return forces_pass<KernelType::quadratic>(m, list, flags, rates, artificial_stress, stress_over_rho2, powers, active);
    case KernelType::quintic:
      return forces_pass<KernelType::quintic>(m, list, flags, rates, artificial_stress, stress_over_rho2, powers, active);
  }
}

}  // namespace snow_sph

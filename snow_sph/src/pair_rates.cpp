// Pair rates: the first pair loop of a step, over the neighbour list with
// ghosts (and, with a decomposed terrain, halo particles) current.
#include <cmath>

#include "snow_sph/gradient_correction.hpp"
#include "snow_sph/stages.hpp"

namespace snow_sph {
namespace {

template <KernelType T, bool Correct>
void rates_pass(Model& m, const NeighbourList& list, const MaterialFlags& flags, const ActiveDomain& domain,
                PairRates& rates) {
  Particles& p = m.particles;
  const Kernel k = m.kernel;
  const double s2 = k.support * k.support;
  const double* g = m.settings.gravity;
  const double delta = m.settings.density_diffusion_delta;
  const double eta2 = 0.01 * k.h * k.h;
  rates.pair_f.resize(list.index.size());
  rates.pair_inv.resize(list.index.size());
  const auto* off = list.offsets.data();
  const auto* nb = list.index.data();
  const double* is_water = flags.is_water.data();
  for_active(domain, p.n_real, "sph.rates", [&](std::size_t i) {
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i];
    const double vxi = p.vx[i], vyi = p.vy[i], vzi = p.vz[i];
    const MaterialModel& mi = m.materials[p.material[i]];
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
    float* pf = rates.pair_f.data();
    float* pinv = rates.pair_inv.data();
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
    rates.lxx[i] = l[0] * inv_rho, rates.lxy[i] = l[1] * inv_rho, rates.lxz[i] = l[2] * inv_rho;
    rates.lyx[i] = l[3] * inv_rho, rates.lyy[i] = l[4] * inv_rho, rates.lyz[i] = l[5] * inv_rho;
    rates.lzx[i] = l[6] * inv_rho, rates.lzy[i] = l[7] * inv_rho, rates.lzz[i] = l[8] * inv_rho;
    p.density_rate[i] = -(l[0] + l[4] + l[8]) + c_diff * diffusion;
    p.neighbour_count[i] = static_cast<std::uint32_t>(count);
  });
}

}  // namespace

// Velocity gradient L_i = (1/rho_i) sum_j m_j (v_j - v_i) (x) grad_i W_ij and
// continuity drho_i/dt = -rho_i tr(L_i) (the pair that conserves energy with
// the momentum equation in compute_pair_forces), plus delta-SPH diffusion for water.
void compute_pair_rates(Model& m, const NeighbourList& list, const MaterialFlags& flags, const ActiveDomain& domain,
                        PairRates& rates) {
  const bool correct = m.settings.kernel_gradient_correction;
  switch (m.kernel.type) {
    case KernelType::cubic:
      return correct ? rates_pass<KernelType::cubic, true>(m, list, flags, domain, rates)
                     : rates_pass<KernelType::cubic, false>(m, list, flags, domain, rates);
    case KernelType::quadratic:
      return correct ? rates_pass<KernelType::quadratic, true>(m, list, flags, domain, rates)
                     : rates_pass<KernelType::quadratic, false>(m, list, flags, domain, rates);
    case KernelType::quintic:
      return correct ? rates_pass<KernelType::quintic, true>(m, list, flags, domain, rates)
                     : rates_pass<KernelType::quintic, false>(m, list, flags, domain, rates);
  }
}

}  // namespace snow_sph

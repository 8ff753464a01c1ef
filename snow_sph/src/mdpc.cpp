// Modified Drucker-Prager/Cap return mapping (thesis section 1.5, eqs 1.6-1.10;
// Abaqus Analysis User's Guide 23.3.2). Equations are collected in mdpc.hpp.
//
// Algorithm (backward Euler, flow rules of Abaqus 23.3.2):
//  1. Elastic predictor, isotropic Hooke: sigma_tr = sigma_n + C : d_eps.
//  2. With K = 1 (t = q), eq 1.7, every yield function and potential depends on
//     sigma through p and q only, and d_eps_p = dlam (dG/dp (-I/3) + dG/dq (3/2) s/q).
//     The deviatoric flow is along s, so the return is radial in the deviatoric
//     plane, s = (q/q_tr) s_tr, and the whole update lives in the p-q plane:
//        p   = p_tr - K_bulk de,        de = dlam dG/dp  (plastic compaction)
//        q   = q_tr - 3 G dlam dG/dq
//        eps = eps_n + de               (the active surface's volumetric plastic
//                                        strain drives pb: compaction on the cap
//                                        hardens, dilation on the shear surface softens)
//  3. Region from the trial state: p_tr <= pa_n -> shear side (Fs, eq 1.6, or the
//     transition Ft, eq 1.8, non-associated with Gs, eq 1.10), else cap side
//     (Fc, eq 1.9, associated). The end state stays in the region it started in
//     (shear flow moves p towards pa from below while pa can only fall; cap
//     flow compacts, so pa can only rise towards p), so no region switching and,
//     since the normals of both potentials are vertical at p = pa, no separate
//     corner return exists, even for alpha = 0.
//  4. Each return is one scalar equation in a bounded unknown with a guaranteed
//     sign-change bracket, solved by Brent's method (no Newton divergence, no
//     substepping needed, never NaN, at most 200 evaluations, typically 2-4):
//        shear side: v = 1 - q/q_tr in [0, 1];
//        cap side:   u = sin(theta) in [u_min, u_hi], theta the angle on the cap ellipse.
//     For a given unknown, the coupling of p with pa(eps) is linear on each
//     segment of the hardening table and is solved exactly (solve_segments).
//     A hydrostatic trial on the cap gives u = 0 and p = pb(eps) exactly.
//  5. Tension: a trial state beyond the apex (p_tr < -d / tan beta) is returned
//     along Gs like any shear-side state. Gs is smooth at the apex with a purely
//     volumetric normal there, so the deviator shrinks by 1/(1 + 3 G dlam/(c^2 Gs))
//     and a hydrostatic trial lands exactly on the apex (p = -d/tan beta, q = 0);
//     such returns are flagged surface 4.
//  Plastic work sigma : d_eps_p = p de + q (q_tr - q) / (3G) is >= 0 on the cap
//  (associated) but, with the non-associated Gs, negative on the shear side when
//  q^2 / c^2 < p tan^2(beta) (pa - p): a strongly over-consolidated state (cap far to
//  the right of p) sheared dilates faster than friction can dissipate. This is a
//  property of the Abaqus potential, reproduced faithfully, not clipped.
#include "snow_sph/mdpc.hpp"

#include "cosim/error.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace snow_sph {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Table {
  const double* e;  // volumetric plastic strain, strictly increasing
  const double* P;  // pb, strictly increasing
  int n;
};

Table table_of(const MdpcParameters& m) {
  const int n = static_cast<int>(std::min(m.hardening_pressure_Pa.size(),
                                          m.hardening_volumetric_plastic_strain.size()));
  return {m.hardening_volumetric_plastic_strain.data(), m.hardening_pressure_Pa.data(), n};
}

// Index j with e[j] <= x < e[j+1]; -1 below the table.
int segment_of(const Table& t, double x) {
  return static_cast<int>(std::upper_bound(t.e, t.e + t.n, x) - t.e) - 1;
}

double last_slope(const Table& t) {
  return (t.P[t.n - 1] - t.P[t.n - 2]) / (t.e[t.n - 1] - t.e[t.n - 2]);
}

// Piecewise linear hardening law pb(eps) (Abaqus 23.3.2, *CAP HARDENING).
double table_pb(const Table& t, double x) {
  if (!(x > t.e[0])) return t.P[0];                  // below the table: first pressure
  const int k = std::min(segment_of(t, x), t.n - 2);  // beyond it: last slope
  return t.P[k] + (t.P[k + 1] - t.P[k]) / (t.e[k + 1] - t.e[k]) * (x - t.e[k]);
}

// Root of phi(x) = A (x - x0) + B pb(x) + C, with A, B >= 0 (phi nondecreasing).
// phi is linear between table points, so walking the segments from x0 gives the
// root exactly. Without a root (A = 0 below the table) the table end is returned.
double solve_segments(const Table& t, double x0, double A, double B, double C) {
  double a = x0, fa = B * table_pb(t, x0) + C;
  if (fa == 0.0) return x0;
  const int j = segment_of(t, x0);
  if (fa < 0.0) {  // walk up
    for (int k = j + 1; k < t.n; ++k) {
      const double fb = A * (t.e[k] - x0) + B * t.P[k] + C;
      if (fb >= 0.0) return a - fa * (t.e[k] - a) / (fb - fa);
      a = t.e[k], fa = fb;
    }
    const double slope = A + B * last_slope(t);
    return slope > 0.0 ? a - fa / slope : a;
  }
  for (int k = j; k >= 0; --k) {  // walk down
    if (!(t.e[k] < a)) continue;
    const double fb = A * (t.e[k] - x0) + B * t.P[k] + C;
    if (fb <= 0.0) return t.e[k] - fb * (a - t.e[k]) / (fa - fb);
    a = t.e[k], fa = fb;
  }
  return A > 0.0 ? a - fa / A : a;  // pb is constant below the table
}

struct Bracket {
  double x, fx;        // best estimate
  double other, fother;  // opposite end of the final bracket (fx * fother <= 0)
};

// Brent's method (Brent 1973, ch. 4) on a bracket fa * fb <= 0. Stops at
// relative x precision ~ 2 DBL_EPSILON, at |f| <= ftol, or after max_iter.
template <class F>
Bracket brent(F&& f, double a, double fa, double b, double fb, double ftol, int max_iter = 200) {
  double c = b, fc = fb, d = b - a, e = d;
  for (int it = 0;; ++it) {
    if ((fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0)) c = a, fc = fa, d = e = b - a;
    if (std::fabs(fc) < std::fabs(fb)) a = b, b = c, c = a, fa = fb, fb = fc, fc = fa;
    const double tol = 2.0 * DBL_EPSILON * std::fabs(b) + 1e-300;
    const double m = 0.5 * (c - b);
    if (std::fabs(m) <= tol || std::fabs(fb) <= ftol || it >= max_iter) return {b, fb, c, fc};
    if (std::fabs(e) >= tol && std::fabs(fa) > std::fabs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {  // secant
        p = 2.0 * m * s, q = 1.0 - s;
      } else {  // inverse quadratic interpolation
        const double qq = fa / fc, r = fb / fc;
        p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
        q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::min(3.0 * m * q - std::fabs(tol * q), std::fabs(e * q))) {
        e = d, d = p / q;
      } else {
        d = m, e = m;  // bisection
      }
    } else {
      d = m, e = m;
    }
    a = b, fa = fb;
    b += std::fabs(d) > tol ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
  }
}

// Constants derived from the parameters.
struct Derived {
  double K, G, d, tb, R, alpha, sb, cb;
  double c;       // 1 + alpha - alpha / cos beta (eqs 1.9, 1.10)
  double a1, a0;  // pa = a1 pb + a0, from pb = pa + R (d + pa tan beta)
};

Derived derive(const MdpcParameters& m) {
  Derived r;
  r.K = m.bulk_modulus_Pa(), r.G = m.shear_modulus_Pa();
  r.d = m.cohesion_Pa, r.tb = std::tan(m.friction_angle_rad);
  r.R = m.cap_eccentricity, r.alpha = m.transition_alpha;
  r.sb = 0.0, r.cb = 1.0, r.c = 1.0;  // only needed for alpha > 0 (saves trig per call)
  if (r.alpha > 0.0) {
    r.sb = std::sin(m.friction_angle_rad), r.cb = std::cos(m.friction_angle_rad);
    r.c = 1.0 + r.alpha - r.alpha / r.cb;
  }
  r.a1 = 1.0 / (1.0 + r.R * r.tb), r.a0 = -r.R * r.d * r.a1;
  return r;
}

// Yield stress q_y(p) on the shear side (p <= pa): Drucker-Prager line (eq 1.6)
// up to the tangent point p_T = pa - alpha X sin beta, then the upper arc of the
// transition surface (eq 1.8 solved for q). X = d + pa tan beta.
double shear_side_qy(const Derived& m, double p, double pa) {
  if (m.alpha > 0.0) {
    const double X = m.d + pa * m.tb;
    if (p > pa - m.alpha * X * m.sb) {
      const double dp = std::min(p, pa) - pa, r = m.alpha * X;
      return (1.0 - m.alpha / m.cb) * X + std::sqrt(std::max(r * r - dp * dp, 0.0));
    }
  }
  return p * m.tb + m.d;
}

// Cap function Fc (eq 1.9) at pressure p, Mises stress q and hardening eps; the
// single implementation shared by cap_strain_enclosing and mdpc_invariants, so
// that "Fc <= 0" answers agree to the last bit.
double cap_function(const Derived& m, const Table& t, double p, double q, double eps) {
  const double pa = m.a1 * table_pb(t, eps) + m.a0, g = p - pa, rq = m.R * q / m.c;
  return std::sqrt(g * g + rq * rq) - m.R * (m.d + pa * m.tb);
}

// p (compression positive) and q (Mises) of a stress tensor.
void p_q(const Eigen::Matrix3d& stress, double& p, double& q) {
  p = -stress.trace() / 3.0;
  Eigen::Matrix3d s = stress;
  s.diagonal().array() += p;
  q = std::sqrt(1.5 * s.squaredNorm());
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("MdpcParameters: " + what);
}

}  // namespace

double MdpcParameters::bulk_modulus_Pa() const {
  return youngs_modulus_Pa / (3.0 * (1.0 - 2.0 * poisson_ratio));
}
double MdpcParameters::shear_modulus_Pa() const {
  return youngs_modulus_Pa / (2.0 * (1.0 + poisson_ratio));
}
double MdpcParameters::cap_hydrostatic_yield_Pa(double eps_vol_pl) const {
  const Table t = table_of(*this);
  if (t.n == 0) return 0.0;
  if (t.n == 1) return t.P[0];
  return table_pb(t, eps_vol_pl);
}
double MdpcParameters::cap_pa_Pa(double eps_vol_pl) const {
  const double R = cap_eccentricity, tb = std::tan(friction_angle_rad);
  return (cap_hydrostatic_yield_Pa(eps_vol_pl) - R * cohesion_Pa) / (1.0 + R * tb);
}

void check_parameters(const MdpcParameters& m) {
  auto finite = [](double x) { return std::isfinite(x); };
  require(finite(m.youngs_modulus_Pa) && m.youngs_modulus_Pa > 0.0,
          "youngs_modulus_Pa must be finite and > 0");
  require(finite(m.poisson_ratio) && m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5,
          "poisson_ratio must be in [0, 0.5)");
  require(finite(m.cohesion_Pa) && m.cohesion_Pa >= 0.0, "cohesion_Pa (d) must be finite and >= 0");
  // beta = 0 is the pressure-independent limit, von Mises with yield stress d
  // (no tension apex, a deviatoric-only return): the Tresca-like cohesive
  // material of the bearing-capacity checks (docs/validation.md).
  require(finite(m.friction_angle_rad) && m.friction_angle_rad >= 0.0 && m.friction_angle_rad < 0.5 * kPi,
          "friction_angle_rad (beta) must be in [0, pi/2) radians");
  require(finite(m.cap_eccentricity) && m.cap_eccentricity > 0.0,
          "cap_eccentricity (R) must be finite and > 0");
  require(finite(m.initial_cap_volumetric_plastic_strain),
          "initial_cap_volumetric_plastic_strain must be finite");
  require(finite(m.transition_alpha) && m.transition_alpha >= 0.0 && m.transition_alpha < 1.0,
          "transition_alpha must be in [0, 1)");
  require(1.0 + m.transition_alpha - m.transition_alpha / std::cos(m.friction_angle_rad) > 0.0,
          "transition_alpha too large for beta: 1 + alpha - alpha/cos(beta) must be > 0");
  require(m.flow_stress_ratio_K == 1.0,
          "flow_stress_ratio_K must be 1 (the only option in Abaqus/Explicit), got " +
              cosim::number_text(m.flow_stress_ratio_K));
  const auto& P = m.hardening_pressure_Pa;
  const auto& e = m.hardening_volumetric_plastic_strain;
  require(P.size() == e.size(), "hardening tables have unequal lengths (" +
                                    std::to_string(P.size()) + " pressures, " +
                                    std::to_string(e.size()) + " strains)");
  require(P.size() >= 2, "the hardening table needs at least 2 points");
  for (std::size_t i = 0; i < P.size(); ++i) {
    require(finite(P[i]) && finite(e[i]), "non-finite hardening table entry " + std::to_string(i));
    if (i > 0) {
      require(P[i] > P[i - 1], "hardening_pressure_Pa must be strictly increasing (row " +
                                   std::to_string(i) + ")");
      require(e[i] > e[i - 1], "hardening_volumetric_plastic_strain must be strictly increasing (row " +
                                   std::to_string(i) + ")");
    }
  }
  require(P[0] >= 0.0, "hardening_pressure_Pa must be >= 0 (compression positive)");
  require(m.cohesion_Pa + P[0] * std::tan(m.friction_angle_rad) > 0.0,
          "d + pb tan(beta) must be > 0 (the cap would have zero height)");
}

namespace {

// The state a plastic return reaches: pressure p, Mises stress q, volumetric
// plastic strain eps and the surface (1: Fs, 2: Fc, 3: Ft, 4: beyond the
// tension apex; mdpc.hpp).
struct ReturnPoint {
  double p = 0.0, q = 0.0, eps = 0.0;
  int surface = 0;
};

// 2a. Shear side: Fs (1.6) or Ft (1.8) with the non-associated potential Gs (1.10).
// False if the trial state (p_tr, q_tr) is elastic.
bool shear_side_return(const Derived& m, const Table& tab, double p_tr, double q_tr, double eps_n, double pa_n,
                       ReturnPoint& out) {
  double& p = out.p;
  double& q = out.q;
  double& eps = out.eps;
  int& surface = out.surface;
  const double f0 = q_tr - shear_side_qy(m, p_tr, pa_n);
  if (f0 <= 0.0) return false;
  // With mu = dlam/Gs: de = -mu tan^2(beta) (pa - p), q = q_tr / (1 + 3 G mu / c^2).
  // Unknown v = 1 - q/q_tr; for given v, eliminating mu leaves
  //   (1 - v + v k1 K)(eps - eps_n) + v k1 (pa(eps) - p_tr) = 0,  k1 = c^2 tan^2(beta) / (3 G),
  // linear per table segment. f(0) = f0 > 0; f(1) = -q_y(pa) < 0 (p -> pa, q -> 0).
  const double k1 = m.c * m.c * m.tb * m.tb / (3.0 * m.G);
  auto state = [&](double v, double& pv, double& ev) {
    ev = solve_segments(tab, eps_n, 1.0 - v + v * k1 * m.K, v * k1 * m.a1, v * k1 * (m.a0 - p_tr));
    pv = p_tr - m.K * (ev - eps_n);
  };
  auto f = [&](double v) {
    double pv, ev;
    state(v, pv, ev);
    return (1.0 - v) * q_tr - shear_side_qy(m, pv, m.a1 * table_pb(tab, ev) + m.a0);
  };
  const double ftol = 1e-14 * (q_tr + std::fabs(p_tr) * m.tb + m.d);
  const Bracket r = brent(f, 0.0, f0, 1.0, f(1.0), ftol);
  state(r.x, p, eps);
  q = (1.0 - r.x) * q_tr;
  const double pa = m.a1 * table_pb(tab, eps) + m.a0;
  surface = (m.alpha > 0.0 && p > pa - m.alpha * (m.d + pa * m.tb) * m.sb) ? 3 : 1;
  if (p_tr * m.tb < -m.d) surface = 4;  // trial beyond the tension apex
  return true;
}

// 2b. Cap side: Fc (1.9), associated flow. Parametrize the cap by its angle theta,
// with unknown u = sin(theta), cs = cos(theta) = sqrt(1 - u^2):
//   g = p - pa = R X cs,  q = c X u,  X = d + pa tan(beta),
// where dFc/dp = cs, dFc/dq = (R/c) u. Then
//   de = dlam cs,  q = q_tr - 3 G (R/c) dlam u,
// and for given u, p_tr - K de = pa(eps) + R X cs is linear per table segment.
// Flow residual (times cs, to stay bounded at the cap top):
//   F(u) = q_tr cs - u (3 G (R/c) de + c X cs).
// On [u_min, 1], where de >= 0 (u_min^2 = 1 - min(1, g0 / (R X_n))^2), F / cs is
// strictly decreasing and F(u_min) > 0 for a trial outside the cap: a unique root.
// Upper bracket: u_hi = q_tr / (c X_n) has F <= 0 (X only grows and q only falls),
// and is close to the root for small increments; else u_hi = 1, F(1) = -3G(R/c) de < 0.
// A hydrostatic trial gives u = 0 and p = pb(eps) exactly.
// False if the trial state (p_tr, q_tr) is elastic.
bool cap_side_return(const Derived& m, const Table& tab, double p_tr, double q_tr, double eps_n, double pa_n,
                     ReturnPoint& out) {
  double& p = out.p;
  double& q = out.q;
  double& eps = out.eps;
  int& surface = out.surface;
  const double X_n = m.d + pa_n * m.tb;
  const double g0 = p_tr - pa_n;
  const double rq0 = m.R * q_tr / m.c;
  const double f0 = std::sqrt(g0 * g0 + rq0 * rq0) - m.R * X_n;
  if (f0 <= 0.0) return false;
  const double k2 = 3.0 * m.G * m.R / m.c;
  auto state = [&](double u, double& ev, double& cs) {
    cs = std::sqrt(std::max(0.0, 1.0 - u * u));
    const double h = 1.0 + m.R * m.tb * cs;
    ev = solve_segments(tab, eps_n, m.K, m.a1 * h, m.a0 * h + m.R * m.d * cs - p_tr);
  };
  auto F = [&](double u) {
    double ev, cs;
    state(u, ev, cs);
    const double X = m.d + (m.a1 * table_pb(tab, ev) + m.a0) * m.tb;
    return q_tr * cs - u * (k2 * (ev - eps_n) + m.c * X * cs);
  };
  const double c_min = std::min(1.0, g0 / (m.R * X_n));
  const double u_min = std::sqrt(std::max(0.0, 1.0 - c_min * c_min));
  const double u_hi = std::min(1.0, q_tr / (m.c * X_n));
  const double f_min = F(u_min), f_hi = F(u_hi);
  double u = u_min;  // f_min <= 0: trial on the cap within round-off
  if (f_hi >= 0.0) {
    u = u_hi;  // only from round-off: u_hi exact, or p_tr ~ pa_n above the cap (corner)
  } else if (f_min > 0.0) {
    u = brent(F, u_min, f_min, u_hi, f_hi, 1e-14 * (q_tr + m.c * X_n)).x;
  }
  double cs;
  state(u, eps, cs);
  p = p_tr - m.K * (eps - eps_n);
  q = std::min(q_tr, m.c * (m.d + (m.a1 * table_pb(tab, eps) + m.a0) * m.tb) * u);
  surface = 2;
  return true;
}

}  // namespace

MdpcStepResult mdpc_update(const MdpcParameters& prm, const Eigen::Matrix3d& strain_increment,
                           Eigen::Matrix3d& stress, double& eps_vol_pl) {
  const Table tab = table_of(prm);
  if (tab.n < 2 || !strain_increment.allFinite() || !stress.allFinite() ||
      !std::isfinite(eps_vol_pl))
    return {0.0, -1};
  const Derived m = derive(prm);

  // 1. Elastic predictor (linear isotropic elasticity, Abaqus 22.2.1).
  const Eigen::Matrix3d de = 0.5 * (strain_increment + strain_increment.transpose());
  Eigen::Matrix3d sig_tr = stress + 2.0 * m.G * de;
  sig_tr.diagonal().array() += (m.K - 2.0 / 3.0 * m.G) * de.trace();
  const double p_tr = -sig_tr.trace() / 3.0;
  Eigen::Matrix3d s_tr = sig_tr;
  s_tr.diagonal().array() += p_tr;
  const double q_tr = std::sqrt(1.5 * s_tr.squaredNorm());

  const double eps_n = eps_vol_pl;
  const double pa_n = m.a1 * table_pb(tab, eps_n) + m.a0;
  // 2. A trial beyond the yield surface returns to it: on the shear side of the
  //    cap's top (p_tr <= pa) or on the cap.
  ReturnPoint r;
  const bool plastic = p_tr <= pa_n ? shear_side_return(m, tab, p_tr, q_tr, eps_n, pa_n, r)
                                    : cap_side_return(m, tab, p_tr, q_tr, eps_n, pa_n, r);
  if (!plastic) {
    stress = sig_tr;
    return {0.0, 0};
  }
  const double p = r.p, q = r.q, eps = r.eps;

  // 3. Stress update (radial in the deviatoric plane) and plastic work
  //    sigma : d eps_p = p de + s : (s_tr - s)/(2G) = p de + q (q_tr - q)/(3G).
  stress = (q_tr > 0.0 ? q / q_tr : 0.0) * s_tr;
  stress.diagonal().array() -= p;
  const double dvol = eps - eps_n;
  eps_vol_pl = eps;
  return {p * dvol + q * (q_tr - q) / (3.0 * m.G), r.surface};
}

ConfinedLayerState confined_layer_state(const MdpcParameters& prm, double sv) {
  const double sh = prm.poisson_ratio / (1.0 - prm.poisson_ratio) * sv;
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  s(0, 0) = s(1, 1) = sh, s(2, 2) = sv;
  return {sh, cap_strain_enclosing(prm, s)};
}

double cap_strain_enclosing(const MdpcParameters& prm, const Eigen::Matrix3d& stress) {
  const double eps0 = prm.initial_cap_volumetric_plastic_strain;
  const Table tab = table_of(prm);
  if (tab.n < 2 || !stress.allFinite()) return eps0;
  const Derived m = derive(prm);
  double p, q;
  p_q(stress, p, q);
  // Fc (eq 1.9) as a function of eps: decreasing while pa(eps) <= p.
  auto fc = [&](double e) { return cap_function(m, tab, p, q, e); };
  if (p <= m.a1 * table_pb(tab, eps0) + m.a0) return eps0;  // shear side: cap not involved
  const double f0 = fc(eps0);
  if (f0 <= 0.0) return eps0;
  // eps at which pa = p: beyond it the stress is on the shear side of any cap.
  const double e_hi = solve_segments(tab, eps0, 0.0, m.a1, m.a0 - p);
  const double f_hi = fc(e_hi);
  if (f_hi > 0.0) return e_hi;  // above the cap top: outside the shear surface anyway
  const Bracket r = brent(fc, eps0, f0, e_hi, f_hi, 0.0);
  return r.fx <= 0.0 ? r.x : r.other;  // the end of the bracket inside the cap
}

MdpcInvariants mdpc_invariants(const MdpcParameters& prm, const Eigen::Matrix3d& stress,
                               double eps_vol_pl) {
  double p, q;
  p_q(stress, p, q);
  const Table tab = table_of(prm);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (tab.n < 2) return {p, q, nan, nan, nan};
  const Derived m = derive(prm);
  const double pa = m.a1 * table_pb(tab, eps_vol_pl) + m.a0;
  return {p, q, q - p * m.tb - m.d /* eq 1.6 */, cap_function(m, tab, p, q, eps_vol_pl), pa};
}

}  // namespace snow_sph

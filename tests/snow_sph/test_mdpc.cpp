// Tests of the modified Drucker-Prager/Cap update (snow_sph/mdpc.hpp; thesis
// section 1.5, eqs 1.6-1.10; Abaqus Analysis User's Guide 23.3.2).
// Parameters come from the reference CSV files (thesis Tables 3.1, 3.2 and the
// hard snow of section 6), read at run time from $COSIM_TEST_DATA (default
// tests/data/reference relative to the working directory).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/scene_io.hpp"
#include "snow_sph/mdpc.hpp"
#include "test_support.hpp"

using snow_sph::MdpcParameters;
using Mat3 = Eigen::Matrix3d;

namespace {

// ---- tolerances -------------------------------------------------------------
// Brief/validation target: pressure at each table point within 2 % (the
// precision at which the thesis model reproduces its hardening input).
constexpr double kTablePressureRelTol = 0.02;
// Hydrostatic return is solved exactly on the table segment: only round-off
// (a few ulps of p, amplified by the table/elastic subtraction) is allowed.
constexpr double kHydrostaticExactRelTol = 1e-12;
// Return mapping stops at |F| <= 1e-14 of the stress scale (Brent); rebuilding
// p and q from the tensor costs a few ulps more. 1e-10 still flags any real overshoot.
constexpr double kOnSurfaceRelTol = 1e-10;
// Elastic steps are sigma + C:d_eps evaluated once: differences are round-off.
constexpr double kElasticRoundoffRelTol = 1e-13;
// sigma : d_eps_p recomputed in the test from d_eps - C^-1 : d_sigma suffers
// cancellation of order eps_machine * |d_eps| / |d_eps_p|; 1e-9 relative to
// |sigma| (|d_eps| + |C^-1 d_sigma|) is still far below any physical error.
constexpr double kWorkConsistencyRelTol = 1e-9;
// ... and d_sigma = sigma_new - sigma_old itself carries ~eps_machine |sigma|, i.e.
// an error |sigma|^2 / (2G) * eps_machine in the work: allow ~500 ulps of that.
constexpr double kStressDifferenceRoundoff = 1e-13;
// Table interpolation and pa/pb algebra are a handful of flops: round-off only.
constexpr double kTableAlgebraRelTol = 1e-12;
// Summing ~7e4 log-strain increments and splitting them into p/K + eps_p
// accumulates ~1e4 ulps at most.
constexpr double kStrainSplitRelTol = 1e-9;
// Return maps are Lipschitz continuous (non-expansive in the energy norm for the
// associated cap); 10x the trial separation leaves margin for the p-q scaling.
constexpr double kReturnMapLipschitz = 10.0;
// Sign of the shear-side work is asserted only where the closed form
// q^2/c^2 - p tan^2(beta) (pa - p) is clearly away from zero (not round-off).
constexpr double kWorkSignDeadBand = 1e-9;

// ---- reference data -----------------------------------------------------------
std::string data_dir() {
  const char* env = std::getenv("COSIM_TEST_DATA");
  return (env && *env) ? std::string(env) : std::string("tests/data/reference");
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Rows of a comma-separated file, header dropped.
std::vector<std::vector<std::string>> read_csv(const std::string& name) {
  const std::string path = data_dir() + "/" + name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path + " (set COSIM_TEST_DATA)");
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (trim(line).empty()) continue;
    if (header) { header = false; continue; }
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(trim(cell));
    rows.push_back(cells);
  }
  return rows;
}

struct Snow {
  MdpcParameters prm;
  double density;
};

// parameter,symbol,value,unit  +  hydrostatic_pressure_Pa,volumetric_plastic_strain
Snow load_snow(const std::string& file) {
  std::map<std::string, double> v;
  for (const auto& r : read_csv(file)) {
    if (r.size() < 4) throw std::runtime_error("malformed row in " + file);
    double x = std::stod(r[2]);
    if (r[3] == "deg") x *= M_PI / 180.0;
    v[r[0]] = x;
  }
  auto get = [&](const char* k) {
    const auto it = v.find(k);
    if (it == v.end()) throw std::runtime_error(std::string("missing ") + k + " in " + file);
    return it->second;
  };
  Snow s;
  s.density = get("initial_density");
  s.prm.youngs_modulus_Pa = get("youngs_modulus");
  s.prm.poisson_ratio = get("poisson_ratio");
  s.prm.cohesion_Pa = get("cohesion");
  s.prm.friction_angle_rad = get("friction_angle");
  s.prm.cap_eccentricity = get("cap_eccentricity");
  s.prm.initial_cap_volumetric_plastic_strain = get("initial_cap_volumetric_plastic_strain");
  s.prm.transition_alpha = get("transition_surface_parameter");
  s.prm.flow_stress_ratio_K = get("flow_stress_ratio");
  for (const auto& r : read_csv("snow_cap_hardening.csv")) {
    s.prm.hardening_pressure_Pa.push_back(std::stod(r.at(0)));
    s.prm.hardening_volumetric_plastic_strain.push_back(std::stod(r.at(1)));
  }
  return s;
}

const std::vector<std::string> kSnowFiles = {"snow_mdpc_soft.csv", "snow_mdpc_hard.csv"};

// ---- helpers ------------------------------------------------------------------
Mat3 hooke(const MdpcParameters& m, const Mat3& de) {  // C : d_eps
  const double K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
  return 2.0 * G * de + (K - 2.0 / 3.0 * G) * de.trace() * Mat3::Identity();
}
Mat3 compliance(const MdpcParameters& m, const Mat3& ds) {  // C^-1 : d_sigma
  const double K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
  const double tr = ds.trace();
  return (ds - tr / 3.0 * Mat3::Identity()) / (2.0 * G) + tr / (9.0 * K) * Mat3::Identity();
}
Mat3 volumetric(double dv) { return dv / 3.0 * Mat3::Identity(); }  // tension positive
Mat3 deviatoric(double d) { return d * Eigen::Vector3d(-1.0, 0.5, 0.5).asDiagonal(); }

// Yield check of eqs 1.6, 1.8, 1.9 written out independently of mdpc.cpp:
// returns the violation (> 0 outside) of the active segment, in Pa.
double violation(const MdpcParameters& m, const Mat3& s, double eps) {
  const auto inv = snow_sph::mdpc_invariants(m, s, eps);
  const double tb = std::tan(m.friction_angle_rad), al = m.transition_alpha;
  const double X = m.cohesion_Pa + inv.pa_Pa * tb;
  if (inv.p_Pa > inv.pa_Pa) return inv.cap_Fc_Pa;
  if (al > 0.0 && inv.p_Pa > inv.pa_Pa - al * X * std::sin(m.friction_angle_rad)) {
    // eq 1.8 is a circle about (pa, qc); only its upper arc bounds the elastic
    // domain, points below the centre are inside.
    const double qc = (1.0 - al / std::cos(m.friction_angle_rad)) * X;
    if (inv.q_Pa <= qc) return inv.q_Pa - qc - al * X;
    return std::hypot(inv.p_Pa - inv.pa_Pa, inv.q_Pa - qc) - al * X;
  }
  return inv.shear_Fs_Pa;
}

// Hydrostatic compression/extension in log-strain steps until p crosses target.
void hydro_to(const MdpcParameters& m, Mat3& s, double& eps, double p_target, double step) {
  const bool load = -s.trace() / 3.0 < p_target;
  for (int i = 0; i < 10000000; ++i) {
    const double p = -s.trace() / 3.0;
    if (load ? p >= p_target : p <= p_target) return;
    snow_sph::mdpc_update(m, volumetric(load ? -step : step), s, eps);
  }
}

}  // namespace

TEST(Mdpc, ReferenceDataAndTable) {
  for (const auto& f : kSnowFiles) {
    const Snow s = load_snow(f);
    EXPECT_NO_THROW(snow_sph::check_parameters(s.prm)) << f;
    const auto& P = s.prm.hardening_pressure_Pa;
    const auto& e = s.prm.hardening_volumetric_plastic_strain;
    EXPECT_EQ(s.prm.cap_hydrostatic_yield_Pa(-1.0), P.front());  // below the table
    for (std::size_t i = 0; i < P.size(); ++i) EXPECT_DOUBLE_EQ(s.prm.cap_hydrostatic_yield_Pa(e[i]), P[i]);
    const std::size_t n = P.size();
    const double slope = (P[n - 1] - P[n - 2]) / (e[n - 1] - e[n - 2]);
    EXPECT_NEAR(s.prm.cap_hydrostatic_yield_Pa(e[n - 1] + 0.01), P[n - 1] + 0.01 * slope,
                kTableAlgebraRelTol * (P[n - 1] + 0.01 * slope));
    // pb = pa + R (d + pa tan beta)
    const double eps0 = s.prm.initial_cap_volumetric_plastic_strain;
    const double pa = s.prm.cap_pa_Pa(eps0), R = s.prm.cap_eccentricity;
    EXPECT_NEAR(pa + R * (s.prm.cohesion_Pa + pa * std::tan(s.prm.friction_angle_rad)),
                s.prm.cap_hydrostatic_yield_Pa(eps0), kTableAlgebraRelTol * s.prm.cap_hydrostatic_yield_Pa(eps0));
  }
}

TEST(Mdpc, HydrostaticCompressionFollowsHardeningTable) {
  constexpr double kLogStrainStep = 1e-4;  // d ln(V) per increment
  for (const auto& f : kSnowFiles) {
    const MdpcParameters m = load_snow(f).prm;
    const auto& P = m.hardening_pressure_Pa;
    const auto& E = m.hardening_volumetric_plastic_strain;
    const double eps0 = m.initial_cap_volumetric_plastic_strain, K = m.bulk_modulus_Pa();
    Mat3 s = Mat3::Zero();
    double eps = eps0, log_strain = 0.0, worst_table = 0.0, worst_exact = 0.0, worst_split = 0.0;
    double eps_prev = eps, p_prev = 0.0;
    std::vector<bool> hit(P.size(), false);
    while (eps < E.back() + 0.002) {
      snow_sph::mdpc_update(m, volumetric(-kLogStrainStep), s, eps);
      log_strain += kLogStrainStep;
      const double p = -s.trace() / 3.0;
      ASSERT_TRUE(std::isfinite(p));
      if (eps > eps_prev) {
        // Plastic step: on the cap, p = pb(eps) exactly; and the compaction splits
        // into elastic p/K and plastic eps - eps0.
        worst_exact = std::max(worst_exact, std::fabs(p - m.cap_hydrostatic_yield_Pa(eps)) / p);
        worst_split = std::max(worst_split, std::fabs(log_strain - p / K - (eps - eps0)) / log_strain);
        for (std::size_t i = 0; i < E.size(); ++i) {
          if (E[i] > eps_prev && E[i] <= eps) {  // crossed a table point: interpolate in eps
            const double p_i = p_prev + (p - p_prev) * (E[i] - eps_prev) / (eps - eps_prev);
            const double err = std::fabs(p_i - P[i]) / P[i];
            EXPECT_LE(err, kTablePressureRelTol) << f << " table point " << i;
            worst_table = std::max(worst_table, err);
            hit[i] = true;
          }
        }
      }
      eps_prev = eps, p_prev = p;
      ASSERT_LT(log_strain, 20.0) << "cap never reached the end of the table";
    }
    for (std::size_t i = 0; i < E.size(); ++i) {
      if (E[i] > eps0) {
        EXPECT_TRUE(hit[i]) << f << " table point " << i << " not reached";
      }
    }
    EXPECT_LE(worst_exact, kHydrostaticExactRelTol) << f;
    EXPECT_LE(worst_split, kStrainSplitRelTol) << f;
    // One huge increment gives the same exact answer (no substepping needed).
    Mat3 s1 = Mat3::Zero();
    double e1 = eps0;
    const auto r = snow_sph::mdpc_update(m, volumetric(-3.0), s1, e1);
    const double p1 = -s1.trace() / 3.0;
    EXPECT_EQ(r.surface, 2);
    EXPECT_NEAR(p1, m.cap_hydrostatic_yield_Pa(e1), kHydrostaticExactRelTol * p1);
    EXPECT_NEAR(3.0 - p1 / K, e1 - eps0, kTableAlgebraRelTol * 3.0);
    std::printf("[hydrostatic %s] worst |p-P|/P at table points %.3e, worst |p-pb(eps)|/p %.3e, "
                "final p %.4g Pa eps %.4f\n", f.c_str(), worst_table, worst_exact, -s.trace() / 3.0, eps);
  }
}

TEST(Mdpc, ShearLoadingStopsOnDruckerPragerLine) {
  constexpr double kDeviatoricStep = 1e-5;  // axial strain per increment, isochoric
  for (const auto& f : kSnowFiles) {
    const MdpcParameters m = load_snow(f).prm;
    const double tb = std::tan(m.friction_angle_rad), d = m.cohesion_Pa;
    Mat3 s = Mat3::Zero();
    double eps = m.initial_cap_volumetric_plastic_strain;
    hydro_to(m, s, eps, 50e3, 1e-4);  // pre-compression onto the cap
    const double eps_pre = eps;
    hydro_to(m, s, eps, 20e3, 1e-4);  // unloading: elastic, inside the surface
    ASSERT_EQ(eps, eps_pre);
    ASSERT_LT(violation(m, s, eps), 0.0);
    const double p_start = -s.trace() / 3.0;
    double worst_excess = 0.0;
    int plastic = 0;
    for (int i = 0; i < 4000; ++i) {
      const auto r = snow_sph::mdpc_update(m, deviatoric(kDeviatoricStep), s, eps);
      const auto inv = snow_sph::mdpc_invariants(m, s, eps);
      if (r.surface != 0) {
        ++plastic;
        EXPECT_EQ(r.surface, 1) << f << " step " << i;
        EXPECT_GE(r.plastic_work_density_J_per_m3, 0.0);
      }
      EXPECT_LE(inv.p_Pa, inv.pa_Pa) << "left the shear side, step " << i;
      const double excess = (inv.q_Pa - (inv.p_Pa * tb + d)) / inv.q_Pa;
      worst_excess = std::max(worst_excess, excess);
      ASSERT_LE(excess, kOnSurfaceRelTol) << f << " step " << i;
    }
    const auto inv = snow_sph::mdpc_invariants(m, s, eps);
    const double off = std::fabs(inv.q_Pa - (inv.p_Pa * tb + d)) / inv.q_Pa;
    EXPECT_LE(off, kOnSurfaceRelTol) << f;
    EXPECT_GT(plastic, 1000) << f;
    // Gs (eq 1.10) dilates for p < pa: under isochoric strain p rises, and the
    // dilation softens the cap (Abaqus 23.3.2).
    EXPECT_GT(inv.p_Pa, p_start) << f;
    EXPECT_LT(eps, eps_pre) << f;
    std::printf("[shear %s] final p %.1f q %.1f Pa pa %.1f, |q-line|/q %.2e, worst excess %.2e, "
                "eps %.5f -> %.5f\n", f.c_str(), inv.p_Pa, inv.q_Pa, inv.pa_Pa, off, worst_excess,
                eps_pre, eps);
  }
}

TEST(Mdpc, UnloadingIsElastic) {
  for (const auto& f : kSnowFiles) {
    const MdpcParameters m = load_snow(f).prm;
    Mat3 s = Mat3::Zero();
    double eps = m.initial_cap_volumetric_plastic_strain;
    // (a) on the cap after hydrostatic loading, (b) on the shear line after shear.
    const Mat3 load_cap = volumetric(-1e-3) + deviatoric(2e-5);
    hydro_to(m, s, eps, 30e3, 1e-4);
    ASSERT_EQ(snow_sph::mdpc_update(m, load_cap, s, eps).surface, 2);
    Mat3 s_shear = s;
    double eps_shear = eps;
    hydro_to(m, s_shear, eps_shear, 10e3, 1e-4);
    for (int i = 0; i < 2000; ++i) snow_sph::mdpc_update(m, deviatoric(1e-5), s_shear, eps_shear);
    ASSERT_EQ(snow_sph::mdpc_update(m, deviatoric(1e-5), s_shear, eps_shear).surface, 1);
    struct Case { Mat3 s; double eps; Mat3 back; const char* what; };
    for (const Case& c : {Case{s, eps, -load_cap, "cap"}, Case{s_shear, eps_shear, deviatoric(-1e-5), "shear"}}) {
      Mat3 s1 = c.s;
      double e1 = c.eps;
      const auto r = snow_sph::mdpc_update(m, c.back, s1, e1);
      EXPECT_EQ(r.surface, 0) << f << " " << c.what;
      EXPECT_EQ(r.plastic_work_density_J_per_m3, 0.0);
      EXPECT_EQ(e1, c.eps) << "hardening variable changed on unloading";
      const Mat3 expected = c.s + hooke(m, c.back);
      EXPECT_LE((s1 - expected).cwiseAbs().maxCoeff(), kElasticRoundoffRelTol * c.s.norm())
          << f << " " << c.what;
    }
  }
}

TEST(Mdpc, TensionReturnsToApex) {
  for (const auto& f : kSnowFiles) {
    const MdpcParameters m = load_snow(f).prm;
    const double apex = -m.cohesion_Pa / std::tan(m.friction_angle_rad);
    Mat3 s = Mat3::Zero();
    double eps = m.initial_cap_volumetric_plastic_strain;
    const double eps0 = eps;
    const auto r = snow_sph::mdpc_update(m, volumetric(0.02), s, eps);  // p_tr ~ -230 kPa
    const auto inv = snow_sph::mdpc_invariants(m, s, eps);
    EXPECT_EQ(r.surface, 4);
    EXPECT_NEAR(inv.p_Pa, apex, kOnSurfaceRelTol * std::fabs(apex)) << f;
    EXPECT_LE(inv.q_Pa, kOnSurfaceRelTol * std::fabs(apex));
    EXPECT_LT(eps, eps0);  // dilation softens the cap
    EXPECT_GT(r.plastic_work_density_J_per_m3, 0.0);
    // With a deviator the Gs normal (smooth at the apex) shrinks q but keeps it on the line.
    const auto r2 = snow_sph::mdpc_update(m, volumetric(0.02) + deviatoric(1e-3), s, eps);
    const auto inv2 = snow_sph::mdpc_invariants(m, s, eps);
    EXPECT_EQ(r2.surface, 4);
    EXPECT_LE(std::fabs(inv2.shear_Fs_Pa), kOnSurfaceRelTol * std::fabs(apex));
    EXPECT_LT(inv2.q_Pa, 3.0 * m.shear_modulus_Pa() * 1e-3);
  }
}

TEST(Mdpc, CornerBetweenShearAndCapIsContinuous) {
  // Trial states just left and right of p = pa with a large deviator: the shear
  // return (Gs) and the cap return (Fc) must meet at the corner (pa, d + pa tan beta).
  for (const auto& f : kSnowFiles) {
    const MdpcParameters m = load_snow(f).prm;
    Mat3 s0 = Mat3::Zero();
    double eps0 = m.initial_cap_volumetric_plastic_strain;
    hydro_to(m, s0, eps0, 50e3, 1e-4);
    const double pa = m.cap_pa_Pa(eps0), X = m.cohesion_Pa + pa * std::tan(m.friction_angle_rad);
    const Mat3 de = deviatoric(2.0 * X / (3.0 * m.shear_modulus_Pa()));  // q_tr = 2 X
    constexpr double kOffset = 1e-6;  // Pa either side of pa
    double p_out[2], q_out[2];
    int surf[2];
    for (int k = 0; k < 2; ++k) {
      Mat3 s = -(pa + (k == 0 ? -kOffset : kOffset)) * Mat3::Identity();
      double eps = eps0;
      surf[k] = snow_sph::mdpc_update(m, de, s, eps).surface;
      const auto inv = snow_sph::mdpc_invariants(m, s, eps);
      p_out[k] = inv.p_Pa, q_out[k] = inv.q_Pa;
      EXPECT_LE(violation(m, s, eps), kOnSurfaceRelTol * X);
    }
    EXPECT_EQ(surf[0], 1);
    EXPECT_EQ(surf[1], 2);
    EXPECT_NEAR(p_out[0], p_out[1], kReturnMapLipschitz * 2.0 * kOffset) << f;
    EXPECT_NEAR(q_out[0], q_out[1], kReturnMapLipschitz * 2.0 * kOffset) << f;
    EXPECT_NEAR(q_out[1], X, kOnSurfaceRelTol * X) << f;  // lands on the corner (pa, X)
    std::printf("[corner %s] dp %.3e dq %.3e Pa, q-X %.3e Pa, p-pa %.3e %.3e Pa\n", f.c_str(),
                p_out[0] - p_out[1], q_out[0] - q_out[1], q_out[1] - X, p_out[0] - pa, p_out[1] - pa);
  }
}

TEST(Mdpc, CapStrainEnclosingGeostaticState) {
  constexpr double kGravity = 9.81;
  for (const auto& f : kSnowFiles) {
    const Snow snow = load_snow(f);
    const MdpcParameters& m = snow.prm;
    const double eps0 = m.initial_cap_volumetric_plastic_strain;
    const double k0 = m.poisson_ratio / (1.0 - m.poisson_ratio);  // oedometric rest
    for (double depth : {0.05, 0.2, 0.5, 1.0, 3.0}) {
      const double sv = -snow.density * kGravity * depth;
      const Mat3 sigma = Eigen::Vector3d(k0 * sv, k0 * sv, sv).asDiagonal();
      const double e = snow_sph::cap_strain_enclosing(m, sigma);
      ASSERT_TRUE(std::isfinite(e));
      EXPECT_GE(e, eps0);
      const auto inv = snow_sph::mdpc_invariants(m, sigma, e);
      const double cap_size = m.cap_eccentricity * (m.cohesion_Pa + inv.pa_Pa * std::tan(m.friction_angle_rad));
      if (e > eps0) {
        EXPECT_LE(inv.cap_Fc_Pa, 0.0) << f << " depth " << depth;
        EXPECT_GE(inv.cap_Fc_Pa, -kOnSurfaceRelTol * inv.p_Pa) << "not the smallest enclosing cap";
      } else {
        EXPECT_TRUE(inv.p_Pa <= inv.pa_Pa || inv.cap_Fc_Pa <= 0.0);
      }
      EXPECT_LE(violation(m, sigma, e), 0.0);
      // Starting there, a zero increment is elastic and leaves everything unchanged.
      Mat3 s = sigma;
      double eps = e;
      EXPECT_EQ(snow_sph::mdpc_update(m, Mat3::Zero(), s, eps).surface, 0);
      EXPECT_EQ(eps, e);
      std::printf("[geostatic %s] depth %.2f m: p %.1f Pa q %.1f Pa eps %.6f Fc %.2e (cap %.2f Pa)\n",
                  f.c_str(), depth, inv.p_Pa, inv.q_Pa, e, inv.cap_Fc_Pa, cap_size);
    }
    // Hydrostatic: the enclosing cap has pb(eps) = p.
    const double e = snow_sph::cap_strain_enclosing(m, -2e5 * Mat3::Identity());
    EXPECT_NEAR(m.cap_hydrostatic_yield_Pa(e), 2e5, kOnSurfaceRelTol * 2e5);
  }
}

TEST(Mdpc, FuzzNoNaNAndPlasticWork) {
  constexpr int kSteps = 100000, kResetEvery = 400;
  std::mt19937_64 rng(0x5eed2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<std::pair<std::string, MdpcParameters>> sets;
  for (const auto& f : kSnowFiles) sets.push_back({f, load_snow(f).prm});
  sets.push_back({"soft, alpha = 0.05", load_snow("snow_mdpc_soft.csv").prm});
  sets.back().second.transition_alpha = 0.05;  // exercises the transition surface (eq 1.8)
  for (const auto& [name, m] : sets) {
    snow_sph::check_parameters(m);
    const double tb = std::tan(m.friction_angle_rad), G = m.shear_modulus_Pa();
    const double c = 1.0 + m.transition_alpha - m.transition_alpha / std::cos(m.friction_angle_rad);
    Mat3 s = Mat3::Zero();
    double eps = 0.0;
    int count[5] = {0, 0, 0, 0, 0}, negative_work = 0;
    double min_work_ratio = 0.0, max_violation = 0.0, seconds = 0.0;
    for (int i = 0; i < kSteps; ++i) {
      if (i % kResetEvery == 0) s.setZero(), eps = m.initial_cap_volumetric_plastic_strain;
      Mat3 a;
      for (int k = 0; k < 9; ++k) a(k) = normal(rng);
      Mat3 de = 0.5 * (a + a.transpose());
      de *= std::pow(10.0, -9.0 + 9.0 * uni(rng)) / de.norm();  // |d_eps| from 1e-9 to 1
      const double u = uni(rng);
      if (u < 0.3) de += volumetric(-de.norm());       // bias to compaction (cap)
      else if (u < 0.4) de += volumetric(de.norm());   // and some tension (apex)
      const Mat3 s_old = s;
      const auto t0 = std::chrono::steady_clock::now();
      const auto r = snow_sph::mdpc_update(m, de, s, eps);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ASSERT_TRUE(s.allFinite() && std::isfinite(eps) && std::isfinite(r.plastic_work_density_J_per_m3))
          << name << " step " << i;
      ASSERT_GE(r.surface, 0);
      ASSERT_LE(r.surface, 4);
      ++count[r.surface];
      const auto inv = snow_sph::mdpc_invariants(m, s, eps);
      const double scale = std::fabs(inv.p_Pa) + inv.q_Pa + m.cohesion_Pa;
      const double viol = violation(m, s, eps) / scale;
      max_violation = std::max(max_violation, viol);
      ASSERT_LE(viol, kOnSurfaceRelTol) << name << " step " << i << " surface " << r.surface;
      // The returned work is sigma_{n+1} : d_eps_p with d_eps_p = d_eps - C^-1 : d_sigma.
      const Mat3 dep = de - compliance(m, s - s_old);
      const double w = r.plastic_work_density_J_per_m3, w_ref = s.cwiseProduct(dep).sum();
      const double wtol = kWorkConsistencyRelTol * s.norm() * (de.norm() + compliance(m, s - s_old).norm()) +
                          kStressDifferenceRoundoff * s.norm() * (s.norm() + s_old.norm()) / (2.0 * G);
      ASSERT_NEAR(w, w_ref, wtol) << name << " step " << i;
      if (r.surface == 0) {
        ASSERT_EQ(w, 0.0);
      } else if (r.surface == 2) {
        ASSERT_GE(w, -wtol) << "negative work on the (associated) cap";
      } else {
        // Shear side, non-associated Gs (eq 1.10): w = dlam/Gs (q^2/c^2 - p tan^2(beta) (pa - p)).
        // It is negative when the cap is far ahead of p (strongly dilatant Gs normal):
        // a property of the Abaqus potential, not of the integration. Check the sign.
        const double D = inv.q_Pa * inv.q_Pa / (c * c) - inv.p_Pa * tb * tb * (inv.pa_Pa - inv.p_Pa);
        const double Dscale = inv.q_Pa * inv.q_Pa + std::fabs(inv.p_Pa) * tb * tb * std::fabs(inv.pa_Pa - inv.p_Pa);
        if (D > kWorkSignDeadBand * Dscale) {
          ASSERT_GE(w, -wtol) << name << " step " << i;
        }
        if (D < -kWorkSignDeadBand * Dscale) {
          ASSERT_LE(w, wtol) << name << " step " << i;
          ++negative_work;
          min_work_ratio = std::min(min_work_ratio, w / (s.norm() * dep.norm()));
        }
      }
    }
    EXPECT_GT(count[1], 100) << name;
    EXPECT_GT(count[2], 100) << name;
    EXPECT_GT(count[4], 100) << name;
    if (m.transition_alpha > 0.0) {
      EXPECT_GT(count[3], 10) << name;
    }
    std::printf("[fuzz %s] elastic %d shear %d cap %d transition %d apex %d; worst violation %.2e; "
                "shear steps with W<0 (Gs dilatancy) %d, min W/(|s||dep|) %.3f; %.0f ns/call\n",
                name.c_str(), count[0], count[1], count[2], count[3], count[4], max_violation,
                negative_work, min_work_ratio, 1e9 * seconds / kSteps);
  }
}

TEST(Mdpc, ShearWorkSignFollowsGsPotential) {
  // Heavily over-consolidated soft snow (cap at 1 MPa, p = 100 kPa) sheared:
  // the Gs normal is so dilatant that sigma : d_eps_p < 0 (released energy), as
  // predicted by q^2 < p tan^2(beta) (pa - p). Documented model property.
  const MdpcParameters m = load_snow("snow_mdpc_soft.csv").prm;
  Mat3 s = Mat3::Zero();
  double eps = m.initial_cap_volumetric_plastic_strain;
  hydro_to(m, s, eps, 1e6, 1e-4);
  hydro_to(m, s, eps, 1e5, 1e-4);
  int i = 0;
  snow_sph::MdpcStepResult r{0.0, 0};
  while (r.surface == 0 && i++ < 10000) r = snow_sph::mdpc_update(m, deviatoric(1e-5), s, eps);
  ASSERT_EQ(r.surface, 1);
  EXPECT_LT(r.plastic_work_density_J_per_m3, 0.0);
}

TEST(Mdpc, BadParametersThrow) {
  const MdpcParameters good = load_snow("snow_mdpc_soft.csv").prm;
  auto expect_throw = [&](const char* what, auto&& edit) {
    MdpcParameters m = good;
    edit(m);
    try {
      snow_sph::check_parameters(m);
      ADD_FAILURE() << "no exception for " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_throw("flow_stress_ratio_K", [](MdpcParameters& m) { m.flow_stress_ratio_K = 0.9; });
  expect_throw("poisson_ratio", [](MdpcParameters& m) { m.poisson_ratio = 0.5; });
  expect_throw("poisson_ratio", [](MdpcParameters& m) { m.poisson_ratio = -0.1; });
  expect_throw("youngs_modulus_Pa", [](MdpcParameters& m) { m.youngs_modulus_Pa = 0.0; });
  expect_throw("youngs_modulus_Pa", [](MdpcParameters& m) { m.youngs_modulus_Pa = NAN; });
  expect_throw("cohesion_Pa", [](MdpcParameters& m) { m.cohesion_Pa = -1.0; });
  expect_throw("friction_angle_rad", [](MdpcParameters& m) { m.friction_angle_rad = -0.01; });
  expect_throw("friction_angle_rad", [](MdpcParameters& m) { m.friction_angle_rad = 22.5; });  // degrees
  expect_throw("cap_eccentricity", [](MdpcParameters& m) { m.cap_eccentricity = 0.0; });
  expect_throw("transition_alpha", [](MdpcParameters& m) { m.transition_alpha = -0.01; });
  expect_throw("unequal lengths", [](MdpcParameters& m) { m.hardening_pressure_Pa.pop_back(); });
  expect_throw("at least 2 points", [](MdpcParameters& m) {
    m.hardening_pressure_Pa.clear();
    m.hardening_volumetric_plastic_strain.clear();
  });
  expect_throw("hardening_pressure_Pa must be strictly increasing",
               [](MdpcParameters& m) { std::swap(m.hardening_pressure_Pa[2], m.hardening_pressure_Pa[3]); });
  expect_throw("hardening_volumetric_plastic_strain must be strictly increasing", [](MdpcParameters& m) {
    std::swap(m.hardening_volumetric_plastic_strain[4], m.hardening_volumetric_plastic_strain[5]);
  });
  expect_throw("initial_cap_volumetric_plastic_strain",
               [](MdpcParameters& m) { m.initial_cap_volumetric_plastic_strain = INFINITY; });
}

// beta = 0: the von Mises limit (the bearing-capacity checks' Tresca-like
// material). Plane-strain simple shear (only the 0-2 rate; the 1 axis zero) of
// an elastic-perfectly plastic Mises solid: tau = G gamma up to the yield
// stress tau_y = d / sqrt(3) (q = sqrt(3) tau in pure shear), then held there
// with no volume change, whatever the pressure the state carries. Closed form
// independent of the return mapping; round-off tolerance.
TEST(Mdpc, ZeroFrictionAngleIsVonMises) {
  MdpcParameters m;
  m.youngs_modulus_Pa = 10e6, m.poisson_ratio = 0.3, m.cohesion_Pa = 17000.0, m.friction_angle_rad = 0.0;
  m.cap_eccentricity = 0.5, m.hardening_pressure_Pa = {1e12, 2e12}, m.hardening_volumetric_plastic_strain = {0.0, 1.0};
  snow_sph::check_parameters(m);
  const double G = m.shear_modulus_Pa(), tau_y = m.cohesion_Pa / std::sqrt(3.0);
  for (double pressure : {0.0, 50e3, -5e3}) {
    Eigen::Matrix3d stress = -pressure * Eigen::Matrix3d::Identity();
    double eps = 0.0, gamma = 0.0;
    for (int k = 0; k < 40; ++k) {
      Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
      d(0, 2) = d(2, 0) = 0.5 * 1e-4;  // engineering shear increment 1e-4
      gamma += 1e-4;
      const auto step = snow_sph::mdpc_update(m, d, stress, eps);
      EXPECT_NEAR(stress(0, 2), std::min(G * gamma, tau_y), 1e-9 * tau_y) << "p " << pressure << " step " << k;
      EXPECT_NEAR(-stress.trace() / 3.0, pressure, 1e-9 * tau_y);
      EXPECT_EQ(eps, 0.0);
      EXPECT_EQ(step.surface, G * gamma > tau_y * (1 + 1e-12) ? 1 : 0);
    }
  }
}

// Drained triaxial compression (sigma_2 = sigma_3 held, axial strain increased)
// against the Mohr-Coulomb strength it is matched to, a closed form independent of
// the Drucker-Prager code: sigma_1 = sigma_3 (1 + sin phi) / (1 - sin phi)
// + 2 c cos phi / (1 - sin phi) (compression positive). The soft snow's cone
// (Table 3.1: beta = 22.538 deg, d = 5 kPa) is the plane-strain match of phi = 14.0
// deg, c = 3.0 kPa; re-matched in triaxial compression (tan beta = 6 sin phi /
// (3 - sin phi), d = 6 c cos phi / (3 - sin phi), as in
// configs/materials/snow_soft_triaxial.textproto) the update must fail at the
// Mohr-Coulomb stress. The snow is first compacted to 50 kPa and unloaded to the
// confining pressure, so that the path meets the cone well before the cap.
namespace {

struct Triaxial {
  double confining_Pa, peak_q_Pa;
};

Triaxial drained_triaxial(const MdpcParameters& m, double confining_Pa) {
  Mat3 s = Mat3::Zero();
  double eps = m.initial_cap_volumetric_plastic_strain;
  hydro_to(m, s, eps, 50e3, 1e-4);
  hydro_to(m, s, eps, confining_Pa, 1e-5);
  const double lateral = s(1, 1);  // held (tension positive)
  const double K = m.bulk_modulus_Pa(), G = m.shear_modulus_Pa();
  const double lateral_stiffness = 2.0 * (K + G / 3.0);  // d sigma_22 / d (eps_22 = eps_33), elastic
  double peak = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const Mat3 s0 = s;
    const double e0 = eps;
    // Secant iteration on the lateral strain increment for sigma_22 = sigma_33 = lateral.
    double x0 = 0.0, f0 = 0.0, x1 = 0.0;
    for (int it = 0; it < 60; ++it) {
      Mat3 de = Mat3::Zero();
      de(0, 0) = -1e-5, de(1, 1) = de(2, 2) = x1;
      s = s0, eps = e0;
      snow_sph::mdpc_update(m, de, s, eps);
      const double f1 = s(1, 1) - lateral;
      if (std::fabs(f1) <= 1e-10 * confining_Pa) break;
      const double slope = (it == 0 || x1 == x0) ? lateral_stiffness : (f1 - f0) / (x1 - x0);
      x0 = x1, f0 = f1;
      x1 -= f1 / slope;
    }
    peak = std::max(peak, s(1, 1) - s(0, 0));
  }
  return {-lateral, peak};
}

}  // namespace

TEST(Mdpc, DrainedTriaxialCompressionFailsAtTheMohrCoulombStressItIsMatchedTo) {
  MdpcParameters m = load_snow("snow_mdpc_soft.csv").prm;
  // phi and c of Table 3.1's cone, inverting Abaqus's plane-strain match.
  const double T = std::tan(m.friction_angle_rad);
  const double tan_phi = 3.0 * T / std::sqrt(27.0 - 12.0 * T * T);
  const double c = m.cohesion_Pa * std::sqrt(9.0 + 12.0 * tan_phi * tan_phi) / (3.0 * std::sqrt(3.0));
  const double sin_phi = std::sin(std::atan(tan_phi)), cos_phi = std::cos(std::atan(tan_phi));
  EXPECT_NEAR(std::atan(tan_phi) * 180.0 / M_PI, 14.0, 0.01);  // the thesis's snow: phi 14 deg,
  EXPECT_NEAR(c, 3000.0, 10.0);                               // c 3 kPa (to its 3 digits)
  const double plane_strain_beta = m.friction_angle_rad, plane_strain_d = m.cohesion_Pa;
  m.friction_angle_rad = std::atan(6.0 * sin_phi / (3.0 - sin_phi));
  m.cohesion_Pa = 6.0 * c * cos_phi / (3.0 - sin_phi);
  for (double confining : {5e3, 10e3, 20e3}) {
    const Triaxial t = drained_triaxial(m, confining);
    const double sigma1 = t.confining_Pa * (1.0 + sin_phi) / (1.0 - sin_phi) + 2.0 * c * cos_phi / (1.0 - sin_phi);
    // The lateral stress is held to 1e-10 and the return map lands on the cone to
    // 1e-10 (kOnSurfaceRelTol): 1e-8 of the deviator is rounding, not model.
    EXPECT_NEAR(t.peak_q_Pa, sigma1 - t.confining_Pa, 1e-8 * (sigma1 - t.confining_Pa)) << "confining " << confining;
    // Table 3.1's own cone is weaker in triaxial compression (phi 11.2 deg, c 2.38 kPa).
    MdpcParameters table = m;
    table.friction_angle_rad = plane_strain_beta, table.cohesion_Pa = plane_strain_d;
    const Triaxial weaker = drained_triaxial(table, confining);
    std::printf("[triaxial, sigma_3 %.0f Pa] Mohr-Coulomb q_f %.1f Pa; triaxial-matched cone %.1f; Table 3.1 cone %.1f (%.1f %%)\n",
                t.confining_Pa, sigma1 - t.confining_Pa, t.peak_q_Pa, weaker.peak_q_Pa,
                100.0 * (weaker.peak_q_Pa / (sigma1 - t.confining_Pa) - 1.0));
  }
}

// The shipped triaxial-matched snows (configs/materials/snow_*_triaxial.textproto)
// follow from their presets (Table 3.1's soft snow, section 6.3's hard snow) by
// the formulas of the test above and nothing else: the preset's cone inverted to
// Mohr-Coulomb phi and c (plane strain), re-matched in triaxial compression, and
// every other field equal. Tolerances: the files give beta to 0.001 deg and d to
// 1 Pa (half a unit of their last digit).
TEST(Mdpc, TriaxialMatchedSnowFilesFollowFromTheirPresets) {
  for (const std::string snow : {"soft", "hard"}) {
    const std::string dir = test_support::source_dir() + "/configs/materials/";
    cosim::scene::Material preset, matched;
    cosim::parse_text_file(dir + "snow_" + snow + ".textproto", preset, nullptr);
    cosim::parse_text_file(dir + "snow_" + snow + "_triaxial.textproto", matched, nullptr);
    const double T = std::tan(preset.snow().friction_angle_deg() * M_PI / 180.0);
    const double tan_phi = 3.0 * T / std::sqrt(27.0 - 12.0 * T * T);
    const double c = preset.snow().cohesion_pa() * std::sqrt(9.0 + 12.0 * tan_phi * tan_phi) / (3.0 * std::sqrt(3.0));
    const double sin_phi = std::sin(std::atan(tan_phi)), cos_phi = std::cos(std::atan(tan_phi));
    EXPECT_NEAR(matched.snow().friction_angle_deg(), std::atan(6.0 * sin_phi / (3.0 - sin_phi)) * 180.0 / M_PI, 5e-4)
        << snow;
    EXPECT_NEAR(matched.snow().cohesion_pa(), 6.0 * c * cos_phi / (3.0 - sin_phi), 0.5) << snow;
    cosim::scene::Material rest = matched;
    rest.mutable_snow()->set_friction_angle_deg(preset.snow().friction_angle_deg());
    rest.mutable_snow()->set_cohesion_pa(preset.snow().cohesion_pa());
    rest.mutable_snow()->set_source(preset.snow().source());
    EXPECT_EQ(rest.SerializeAsString(), preset.SerializeAsString()) << snow << ": a field besides the cone differs";
  }
}

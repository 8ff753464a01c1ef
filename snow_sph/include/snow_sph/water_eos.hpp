#pragma once
// Water: linear Us-Up Hugoniot in Mie-Grueneisen form (Abaqus Analysis User's
// Guide 25.2.1; thesis Table 4.1):
//   p = rho0 c0^2 eta / (1 - s eta)^2 * (1 - Gamma0 eta / 2) + Gamma0 rho0 Em,
//   eta = 1 - rho0 / rho.
// The internal energy Em is not tracked, so Gamma0 must be 0 (the thesis
// value); validation refuses anything else.
// With tension_limit > 0 the pressure does not fall below -tension_limit: water
// cavitates near its vapour pressure instead of pulling without limit (Abaqus's
// hydrostatic tensile cutoff, *TENSILE FAILURE; Radioss's Pmin of a fluid).
#include <algorithm>
#include <cmath>

namespace snow_sph {

struct WaterEos {
  double rho0 = 996.0;      // kg/m^3
  double c0 = 1500.0;       // m/s (possibly lowered; see WaterModel)
  double s = 0.0;           // Hugoniot slope
  double tension_limit = 0.0;  // Pa; 0: none

  double eta(double rho) const { return 1.0 - rho0 / rho; }

  // The Hugoniot's pressure at eta, before the tension limit.
  double hugoniot_pressure(double e) const {
    const double d = 1.0 - s * e;
    return rho0 * c0 * c0 * e / (d * d);
  }

  // dp/deta along the law.
  double hugoniot_dp_deta(double e) const {
    const double d = 1.0 - s * e;
    return rho0 * c0 * c0 * (1.0 + s * e) / (d * d * d);
  }

  // Whether the law at eta pulls harder than the tension limit holds.
  bool beyond_tension_limit(double e) const { return tension_limit > 0.0 && hugoniot_pressure(e) < -tension_limit; }

  double pressure(double rho) const {
    const double e = eta(rho);
    return beyond_tension_limit(e) ? -tension_limit : hugoniot_pressure(e);
  }

  // Bulk sound speed sqrt(dp/drho). Beyond the tension limit the pressure is
  // flat and the law's own speed, c0 rho0 / rho for s = 0, would grow without
  // bound as a splash thins (3,200 m/s at 46 kg/m^3 set the hydroplaning
  // terrain's step): the speed stays that at the limit, so the step and the
  // artificial viscosity see the water as at the limit.
  double sound_speed(double rho) const {
    if (beyond_tension_limit(eta(rho))) rho = density_for_pressure(-tension_limit);
    const double c2 = hugoniot_dp_deta(eta(rho)) * rho0 / (rho * rho);
    return std::sqrt(std::max(c2, 0.0));
  }

  // Density giving pressure p (inverse of pressure(), s = 0 closed form,
  // otherwise Newton).
  double density_for_pressure(double p) const {
    double e = p / (rho0 * c0 * c0);
    for (int it = 0; it < 30 && s != 0.0; ++it) {
      e -= (hugoniot_pressure(e) - p) / hugoniot_dp_deta(e);
    }
    return rho0 / (1.0 - e);
  }

  // Elastic energy per unit mass, integral of p / rho^2 drho from rho0
  // (s = 0: c0^2 eta^2 / 2). Used in the energy balance.
  double energy_per_mass(double rho) const {
    const double e = eta(rho);
    if (beyond_tension_limit(e)) {
      // Along the law up to the limit, then at the constant -tension_limit.
      const double e_lim = eta(density_for_pressure(-tension_limit));
      return hugoniot_energy(e_lim) + tension_limit * (e_lim - e) / rho0;
    }
    return hugoniot_energy(e);
  }

  // Integral of p deta / rho0 along the law (d eta = rho0/rho^2 drho).
  double hugoniot_energy(double e) const {
    if (s == 0.0) return 0.5 * c0 * c0 * e * e;
    const int n = 16;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      const double ek = (k + 0.5) * e / n;
      const double d = 1.0 - s * ek;
      sum += c0 * c0 * ek / (d * d);
    }
    return sum * e / n;
  }
};

}  // namespace snow_sph

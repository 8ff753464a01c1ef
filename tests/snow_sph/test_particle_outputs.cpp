// Per-particle quantities written to the VTK frames for a snow engineer to look
// at: the von Mises stress against stress states whose equivalent stress is
// known by hand (Hill, The Mathematical Theory of Plasticity, 1950, ch. 2).
#include <gtest/gtest.h>

#include <cmath>

#include "snow_sph/particles.hpp"

namespace {

// Round-off of a few products of kPa-sized stresses: 1e-9 Pa is far below any
// stress of interest and far above the rounding (~1e-12 Pa).
constexpr double kRounding = 1e-9;

TEST(ParticleOutputs, VonMisesStressOfKnownStates) {
  snow_sph::Particles p;
  p.resize(4);
  p.szz[0] = -44.9e3;  // uniaxial compression: q = |sigma|
  p.sxy[1] = 10e3;     // pure shear: q = sqrt(3) tau
  p.sxx[2] = p.syy[2] = p.szz[2] = -30e3;  // hydrostatic: q = 0
  p.sxx[3] = -20e3, p.syy[3] = -20e3, p.szz[3] = -50e3;  // triaxial: q = sigma_1 - sigma_3
  EXPECT_NEAR(snow_sph::von_mises_stress_Pa(p, 0), 44.9e3, kRounding);
  EXPECT_NEAR(snow_sph::von_mises_stress_Pa(p, 1), std::sqrt(3.0) * 10e3, kRounding);
  EXPECT_NEAR(snow_sph::von_mises_stress_Pa(p, 2), 0.0, kRounding);
  EXPECT_NEAR(snow_sph::von_mises_stress_Pa(p, 3), 30e3, kRounding);
}

}  // namespace

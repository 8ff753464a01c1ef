// Footprint (issue: tyre_fe, item 2): the inflated tyre pressed on a rigid road by
// 4000 N comes to rest with the rim carrying the load (within 1 %), a positive
// deflection and contact area; a softer tyre (170 kPa) deflects more.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>

#include "tyre_support.hpp"

namespace {

// Coarser than the scene (same physics) to keep the suite fast: 20 mm elements,
// 48 circumferential divisions, more mass scaling (the end state is static).
// Each run sets the inflation pressure.
const tyre_support::Variation footprint{"tyre_footprint",
                                        {"tyre.mesh.element_size_m=0.02", "tyre.tread.elements_per_pitch=1",
                                         "tyre.tread.pitch_count=48", "tyre.mass_scaling_target_dt_s=2e-6"},
                                        "tyre.inflation_pressure_Pa"};

TEST(TyreFootprint, LoadedTyreComesToRestCarryingTheWheelLoad) {
  const auto s200 = footprint(200e3, "tyre_footprint_200");
  ASSERT_EQ(s200["status"], "completed");
  const auto& r = s200["results"];
  std::printf("200 kPa: deflection %.2f mm, contact area %.1f cm^2, rim force %.1f N, road force %.1f N\n",
              r["vertical_deflection_m"].get<double>() * 1e3, r["contact_area_m2"].get<double>() * 1e4,
              r["rim_vertical_force_N"].get<double>(), r["road_vertical_force_N"].get<double>());
  EXPECT_NEAR(r["rim_vertical_force_N"].get<double>(), 4000.0, 40.0);   // issue: within 1 % at rest
  EXPECT_NEAR(r["road_vertical_force_N"].get<double>(), 4000.0, 40.0);
  EXPECT_GT(r["vertical_deflection_m"].get<double>(), 5e-3);
  EXPECT_LT(r["vertical_deflection_m"].get<double>(), 60e-3);
  EXPECT_GT(r["contact_area_m2"].get<double>(), 50e-4);
  EXPECT_TRUE(std::filesystem::exists(tyre_support::scratch_path("tyre_footprint_200") + "/footprint.csv"));

  const auto s170 = footprint(170e3, "tyre_footprint_170");
  ASSERT_EQ(s170["status"], "completed");
  std::printf("170 kPa: deflection %.2f mm, contact area %.1f cm^2\n",
              s170["results"]["vertical_deflection_m"].get<double>() * 1e3,
              s170["results"]["contact_area_m2"].get<double>() * 1e4);
  EXPECT_GT(s170["results"]["vertical_deflection_m"].get<double>(), r["vertical_deflection_m"].get<double>());
}

}  // namespace

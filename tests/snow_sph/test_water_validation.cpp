// Water validations:
//  - a column at rest: floor pressure within 2 % of rho g H (issue requirement);
//  - dam break, a = 57.15 mm, height 2a: surge front against Martin & Moyce
//    (1952), tests/data/martin_moyce_1952_n2_front.csv, at the experiment's own
//    time origin (no fitted time shift).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "csv_lines.hpp"
#include "test_support.hpp"

namespace {

// The acceptance bound for the hydrostatic floor pressure.
constexpr double kFloorPressureTolerance = 0.02;
// Dam break, compared with Martin & Moyce at their own time origin (no shift: the
// data we hold document no gate-opening time, and a shift fitted to our front would
// hide any error in its timing). The error budget of the comparison:
//  - the data: two independent transcriptions of Table 2 differ by <= 0.02 in T
//    (tests/data/martin_moyce_1952_n2_front.csv, "Cross-checks"); Z are fixed stations;
//  - our front: farthest particle + dx/2, so it is known to +-dx/2 (a/40 here),
//    which is dx / (2 a v) in arrival time where the front moves at dZ/dT = v.
constexpr double kDataTimeUncertainty = 0.02;
// The one physical unknown is when the experiment's column was actually free. Its
// first station bounds it without reference to any simulation: no dam-break front is
// faster than Ritter's ideal shallow-water front, dx/dt = 2 sqrt(g h0), which is
// dZ/dT = 2 in these units (h0 = 2a), so a front at Z1 at T1 was released no later
// than T1 - (Z1 - 1) / 2 (= 0.355 for the first station, T = 0.41, Z = 1.11).
constexpr double kRitterFrontSpeed = 2.0;

struct Point {
  double t, z;
};

std::vector<Point> read_pairs(const std::string& path, bool skip_header) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<Point> out;
  for (const std::string& line : test_support::csv_data_lines(in, skip_header)) {
    std::stringstream ss(line);
    Point p;
    char comma;
    ss >> p.t >> comma >> p.z;
    out.push_back(p);
  }
  return out;
}

// Linear interpolation of the member `to` at `from` = x along v (monotone in `from`);
// the last value beyond the end.
double interpolate_along(const std::vector<Point>& v, double Point::*from, double Point::*to, double x) {
  for (std::size_t k = 1; k < v.size(); ++k)
    if (v[k].*from >= x)
      return v[k - 1].*to + (v[k].*to - v[k - 1].*to) * (x - v[k - 1].*from) / (v[k].*from - v[k - 1].*from);
  return v.back().*to;
}

double interpolate(const std::vector<Point>& v, double t) { return interpolate_along(v, &Point::t, &Point::z, t); }

TEST(WaterValidation, ColumnFloorPressureIsHydrostatic) {
  const auto out = test_support::scratch("water_column");
  const auto s = test_support::run(test_support::scene_path("water_column"), {}, out);
  const double bottom = s["results"]["bottom_pressure_Pa"], hydro = s["results"]["hydrostatic_pressure_Pa"];
  EXPECT_NEAR(hydro, 996.0 * 9.81 * 0.4, 0.02 * hydro);  // the reference itself is rho g H
  EXPECT_LT(std::abs(bottom - hydro) / hydro, kFloorPressureTolerance) << bottom << " vs " << hydro;
  EXPECT_TRUE(s["materials"][0]["sound_speed_lowered"].get<bool>());
}

// Time at which the (monotone) front first reaches z.
double arrival(const std::vector<Point>& v, double z) { return interpolate_along(v, &Point::z, &Point::t, z); }

TEST(WaterValidation, DamBreakFrontFollowsMartinMoyce) {
  const auto out = test_support::scratch("dam_break");
  const auto s = test_support::run(test_support::scene_path("dam_break"), {}, out);
  const double a = s["results"]["column_width_m"];
  EXPECT_DOUBLE_EQ(s["results"]["column_height_m"].get<double>(), 2 * a);
  const double dx = s["particle_spacing_m"];
  const double g = 9.81, scale = std::sqrt(2 * g / a);  // T = t sqrt(2g/a)
  auto front = read_pairs(out + "/front.csv", true);
  ASSERT_GT(front.size(), 10u);
  for (auto& p : front) p.t *= scale, p.z /= a;
  const auto experiment = read_pairs(test_support::data_dir() + "/martin_moyce_1952_n2_front.csv", true);
  ASSERT_EQ(experiment.size(), 15u);
  const double latest_release = experiment[0].t - (experiment[0].z - 1.0) / kRitterFrontSpeed;
  // At every station, the simulated front (released at T = 0, instantaneously) arrives
  //  - not later than the experiment's, within the uncertainty: every effect the model
  //    leaves out (a release that takes time, floor friction, surface tension) can only
  //    delay the real front, and the model's own numerical viscosity delays its front;
  //  - not earlier than the experiment's by more than the latest release time plus the
  //    uncertainty. A front that is too slow or too fast fails one of the two.
  // The simulated front gains about 0.25 in T on the experiment while it accelerates
  // (0.84 < T < 1.43) and keeps that lead; at the first station they agree. The upper
  // bound accepts the lead as no larger than a late release could explain; it does not
  // show that the release is its cause.
  for (const auto& e : experiment) {
    const double t_sim = arrival(front, e.z);
    const double v = (interpolate(front, t_sim + 0.1) - interpolate(front, t_sim - 0.1)) / 0.2;  // local dZ/dT
    const double uncertainty = kDataTimeUncertainty + dx / (2 * a) / v;
    const double lead = e.t - t_sim;
    std::printf("dam break: Z = %.2f, experiment T = %.2f, simulation T = %.3f, lead %+.3f (allowed %+.3f .. %+.3f)\n",
                e.z, e.t, t_sim, lead, -uncertainty, latest_release + uncertainty);
    EXPECT_GE(lead, -uncertainty) << "front behind the experiment at Z = " << e.z;
    EXPECT_LE(lead, latest_release + uncertainty) << "front ahead of any release delay at Z = " << e.z;
  }
  // The mean front speed after the initial acceleration, from Z = 1.67 (T = 1.43) to
  // Z = 4.11: the distance between two stations over the time the front takes to go from
  // one to the other, in the experiment and in the simulation. A difference of arrival
  // times, so it holds whatever the release time. Tolerance: the worst case of both
  // error sources at both stations, the data's +-0.02 in T and our front's +-dx/2
  // (dx / (2 a v) in time), over the travel time (4.3 % here); a front speed further
  // than that from the experiment's, e.g. from excess viscosity, fails.
  const auto& e0 = experiment[3];  // T = 1.43: past the initial acceleration
  const auto& e1 = experiment.back();
  const double t0 = arrival(front, e0.z), t1 = arrival(front, e1.z);
  const double v0 = (interpolate(front, t0 + 0.1) - interpolate(front, t0 - 0.1)) / 0.2;
  const double v1 = (interpolate(front, t1 + 0.1) - interpolate(front, t1 - 0.1)) / 0.2;
  const double speed_exp = (e1.z - e0.z) / (e1.t - e0.t);
  const double speed_sim = (e1.z - e0.z) / (t1 - t0);
  const double speed_tolerance =
      2 * kDataTimeUncertainty / (e1.t - e0.t) + (dx / (2 * a)) * (1 / v0 + 1 / v1) / (t1 - t0);
  std::printf("dam break: front speed dZ/dT from Z = %.2f to %.2f: %.3f (experiment %.3f), allowed %.1f %%\n",
              e0.z, e1.z, speed_sim, speed_exp, 100 * speed_tolerance);
  EXPECT_LT(std::abs(speed_sim - speed_exp) / speed_exp, speed_tolerance);
}

}  // namespace

// Water validations:
//  - a column at rest: floor pressure within 2 % of rho g H (issue requirement);
//  - dam break, a = 57.15 mm, height 2a: surge front against Martin & Moyce
//    (1952), tests/data/martin_moyce_1952_n2_front.csv.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace {

// The acceptance bound for the hydrostatic floor pressure.
constexpr double kFloorPressureTolerance = 0.02;
// Martin & Moyce's release time is uncertain (the gate takes time to clear);
// published comparisons shift the experiment by ~0.2 in T (Lethe uses 0.175).
// We allow a shift in [0, 0.4] and require the front to follow the data
// within 0.12 a (RMS) after it, and the mean front speed dZ/dT over the
// measured range to be within 12 % of the experiment's.
constexpr double kMaxTimeShift = 0.4;
constexpr double kFrontRmsTolerance = 0.12;
constexpr double kFrontSpeedTolerance = 0.12;

struct Point {
  double t, z;
};

std::vector<Point> read_pairs(const std::string& path, bool skip_header) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<Point> out;
  std::string line;
  bool header = skip_header;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) { header = false; continue; }
    std::stringstream ss(line);
    Point p;
    char comma;
    ss >> p.t >> comma >> p.z;
    out.push_back(p);
  }
  return out;
}

double interpolate(const std::vector<Point>& v, double t) {
  for (std::size_t k = 1; k < v.size(); ++k)
    if (v[k].t >= t) return v[k - 1].z + (v[k].z - v[k - 1].z) * (t - v[k - 1].t) / (v[k].t - v[k - 1].t);
  return v.back().z;
}

TEST(WaterValidation, ColumnFloorPressureIsHydrostatic) {
  const auto out = test_support::scratch("water_column");
  const auto s = test_support::run(test_support::scene_path("water_column"), {}, out);
  const double bottom = s["results"]["bottom_pressure_Pa"], hydro = s["results"]["hydrostatic_pressure_Pa"];
  EXPECT_NEAR(hydro, 996.0 * 9.81 * 0.4, 0.02 * hydro);  // the reference itself is rho g H
  EXPECT_LT(std::abs(bottom - hydro) / hydro, kFloorPressureTolerance) << bottom << " vs " << hydro;
  EXPECT_TRUE(s["materials"][0]["sound_speed_lowered"].get<bool>());
}

TEST(WaterValidation, DamBreakFrontFollowsMartinMoyce) {
  const auto out = test_support::scratch("dam_break");
  const auto s = test_support::run(test_support::scene_path("dam_break"), {}, out);
  const double a = s["results"]["column_width_m"];
  EXPECT_DOUBLE_EQ(s["results"]["column_height_m"].get<double>(), 2 * a);
  const double g = 9.81, scale = std::sqrt(2 * g / a);  // T = t sqrt(2g/a)
  auto front = read_pairs(out + "/front.csv", true);
  ASSERT_GT(front.size(), 10u);
  for (auto& p : front) p.t *= scale, p.z /= a;
  const auto experiment = read_pairs(test_support::data_dir() + "/martin_moyce_1952_n2_front.csv", true);
  ASSERT_EQ(experiment.size(), 15u);
  double best_rms = 1e9, best_shift = 0;
  for (double shift = 0.0; shift <= kMaxTimeShift + 1e-9; shift += 0.01) {
    double sum = 0;
    for (const auto& e : experiment) sum += std::pow(interpolate(front, e.t - shift) - e.z, 2);
    const double rms = std::sqrt(sum / experiment.size());
    if (rms < best_rms) best_rms = rms, best_shift = shift;
  }
  std::printf("dam break: best time shift %.2f, RMS front error %.3f a\n", best_shift, best_rms);
  EXPECT_LT(best_rms, kFrontRmsTolerance);
  const auto& e0 = experiment[3];  // T = 1.43: past the initial acceleration
  const auto& e1 = experiment.back();
  const double speed_exp = (e1.z - e0.z) / (e1.t - e0.t);
  const double speed_sim = (interpolate(front, e1.t - best_shift) - interpolate(front, e0.t - best_shift)) / (e1.t - e0.t);
  std::printf("dam break: front speed dZ/dT %.3f (experiment %.3f)\n", speed_sim, speed_exp);
  EXPECT_LT(std::abs(speed_sim - speed_exp) / speed_exp, kFrontSpeedTolerance);
}

}  // namespace

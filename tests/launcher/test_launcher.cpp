// The launcher as a user runs it: cosim check / run / study, through the
// real executables (cosim starts snow_sph as a child process).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "test_support.hpp"

namespace {

using test_support::bin;
using test_support::shell;

TEST(Launcher, CheckAcceptsAGoodSceneAndRefusesABadOne) {
  auto [ok, out] = shell(bin() + "/cosim check " + test_support::scene_path("plate_sinkage"));
  EXPECT_EQ(ok, 0) << out;
  auto [bad, msg] = shell(bin() + "/cosim check " + test_support::scene_path("plate_sinkage") +
                          " --set sph.particle_spacing_m=-1");
  EXPECT_EQ(bad, 2) << msg;
  EXPECT_NE(msg.find("--set sph.particle_spacing_m=-1: must be > 0"), std::string::npos) << msg;
}

TEST(Launcher, RunStartsOnlyTheTerrainSolver) {
  const auto dir = test_support::scratch("launcher_run");
  auto [code, out] = shell(bin() + "/cosim run " + test_support::scene_path("dam_break") + " --out " + dir +
                           " --set time.end_time_s=0.005 --quiet --no-vtk");
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("needs: snow_sph alone (no tyre, no DDS)"), std::string::npos) << out;
  EXPECT_NE(out.find("final_front_m"), std::string::npos) << out;  // results printed
  const auto summary = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["overrides"]["time.end_time_s"], "0.005");
}

// A tyre on the rigid road starts tyre_fe alone; --mesh-only writes the four tread
// variants' meshes with their counts (issue: tyre_fe, item 4).
TEST(Launcher, TyreSceneStartsOnlyTheTyreSolverAndWritesEachTreadVariant) {
  long previous_sipe_walls = -1;
  for (const char* variant : {"SMOOTH", "RIB", "BLOCK", "BLOCK_SIPES_MESHED"}) {
    const auto dir = test_support::scratch(std::string("launcher_tyre_") + variant);
    auto [code, out] = shell(bin() + "/cosim run " + test_support::scene_path("tyre_tread_variants") + " --out " +
                             dir + " --mesh-only --set tyre.tread.variant=" + variant);
    ASSERT_EQ(code, 0) << out;
    EXPECT_NE(out.find("needs: tyre_fe alone (tyre on a rigid road: no SPH, no DDS)"), std::string::npos) << out;
    const auto summary = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
    const auto& r = summary["results"];
    EXPECT_GT(r["elements"].get<long>(), 0);
    EXPECT_GT(r["facets_by_tag"]["tread_top"].get<long>(), 0);
    const long grooves = r["facets_by_tag"]["groove_wall"].get<long>();
    const long sipes = r["facets_by_tag"]["sipe_wall"].get<long>();
    EXPECT_EQ(grooves > 0, std::string(variant) != "SMOOTH") << variant;
    EXPECT_EQ(sipes > 0, std::string(variant) == "BLOCK_SIPES_MESHED") << variant;
    EXPECT_GT(std::filesystem::file_size(dir + "/mesh3d.vtk"), 1000u);
    previous_sipe_walls = sipes;
  }
  EXPECT_GT(previous_sipe_walls, 0);
}

// BLOCK_SIPES is the thesis's treatment (block mesh, equivalent friction on the
// tread top): slit fields with it would count the sipes twice, and are refused
// with the field and the variant that cuts slits named.
TEST(Launcher, TheThesisSipesRefuseSlitFields) {
  auto [code, out] = shell(bin() + "/cosim check " + test_support::scene_path("tyre_tread_variants") +
                           " --set tyre.tread.variant=BLOCK_SIPES");
  EXPECT_NE(code, 0) << out;
  EXPECT_NE(out.find("sipes_per_block"), std::string::npos) << out;
  EXPECT_NE(out.find("BLOCK_SIPES_MESHED"), std::string::npos) << out;
}

// A study's later cases take settings from earlier cases' results: the spin of a
// slip ratio from the rolling radius a towed case measured (thesis eq. 5.1:
// w = v / (r (1 - sigma)), v = 2.7778 m/s in the scene), and a field as a multiple
// of a result. The values the cases ran with are their overrides, printed to 17
// digits, so they match the formula to rounding (1e-14 relative).
TEST(Launcher, StudyCasesDeriveTheirSettingsFromEarlierCases) {
  const auto dir = test_support::scratch("launcher_study_derived");
  auto [code, out] = shell("OMP_NUM_THREADS=1 " + bin() + "/cosim study " + test_support::source_dir() +
                           "/tests/launcher/test_launcher_derived.textproto --out " + dir + " --no-vtk");
  ASSERT_EQ(code, 0) << out;
  auto summary = [&](const std::string& c) { return nlohmann::json::parse(std::ifstream(dir + "/" + c + "/summary.json")); };
  const auto towed = summary("towed"), slip = summary("slip20"), derived = summary("derived");
  const double r = towed["results"]["rolling_radius_m"];
  ASSERT_GT(r, 0.3);
  const double w = std::stod(slip["overrides"]["tyre.rim.angular_velocity_rad_per_s"].get<std::string>());
  EXPECT_NEAR(w, 2.7778 / (r * (1.0 - 0.2)), 1e-14 * w);
  const double torque = std::stod(derived["overrides"]["tyre.rim.drive_torque_Nm"].get<std::string>());
  EXPECT_NEAR(torque, -2.0 * towed["results"]["rm2_Nm"].get<double>(), 1e-14 * std::fabs(torque));

  // A case that takes its radius from a case that has not run yet is refused
  // before anything runs, naming the field.
  const std::string bad = dir + "/bad_study.textproto";
  std::ofstream(bad) << "name: \"bad\" scene: \"none.textproto\" result_field: \"x\"\n"
                        "cases { label: \"a\" slip_ratio: 0.1 rolling_radius_case: \"b\" }\n"
                        "cases { label: \"b\" }\n";
  auto [bad_code, bad_out] = shell(bin() + "/cosim study " + bad + " --out " + dir + "/bad");
  EXPECT_NE(bad_code, 0);
  EXPECT_NE(bad_out.find("cases[0].rolling_radius_case"), std::string::npos) << bad_out;
  EXPECT_NE(bad_out.find("earlier case"), std::string::npos) << bad_out;
}

TEST(Launcher, StudyWritesTableAndPlot) {
  const auto dir = test_support::scratch("launcher_study");
  auto [code, out] = shell(bin() + "/cosim study " + test_support::source_dir() +
                           "/tests/launcher/test_launcher.textproto --out " + dir + " --no-vtk");
  ASSERT_EQ(code, 0) << out;
  std::ifstream table(dir + "/table.csv");
  std::string header, row1, row2;
  std::getline(table, header), std::getline(table, row1), std::getline(table, row2);
  EXPECT_EQ(header, "case,particle_spacing_m,size,time_step_s,steps,wall_time_s,front_m,reference,relative_error");
  EXPECT_EQ(row1.rfind("coarse,0.0057,", 0), 0u) << row1;
  // The result column holds the run's final_front_m (named front_m by the study file).
  std::vector<std::string> cells;
  for (std::stringstream ss(row1); cells.size() < 9 && ss.good();) std::getline(ss, cells.emplace_back(), ',');
  ASSERT_EQ(cells.size(), 9u) << row1;
  EXPECT_GT(std::stod(cells[6]), 0.0) << row1;
  EXPECT_EQ(row2.rfind("fine,0.0028575,", 0), 0u) << row2;
  EXPECT_GT(std::filesystem::file_size(dir + "/error_vs_runtime.png"), 1000u);
}

// --resume keeps a case that completed with the same overrides (its row, wall time
// included, is the earlier run's) and runs the one whose summary is missing.
TEST(Launcher, StudyResumeKeepsCompletedCasesAndRunsTheRest) {
  const auto dir = test_support::scratch("launcher_study_resume");
  const std::string study = bin() + "/cosim study " + test_support::source_dir() +
                            "/tests/launcher/test_launcher.textproto --out " + dir + " --no-vtk";
  auto [code, out] = shell(study);
  ASSERT_EQ(code, 0) << out;
  auto rows = [&] {
    std::ifstream table(dir + "/table.csv");
    std::vector<std::string> lines;
    for (std::string line; std::getline(table, line);) lines.push_back(line);
    return lines;
  };
  const auto first = rows();
  ASSERT_EQ(first.size(), 3u);
  std::filesystem::remove(dir + "/fine/summary.json");
  std::tie(code, out) = shell(study + " --resume");
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("case 1/2 'coarse' completed before"), std::string::npos) << out;
  EXPECT_EQ(out.find("case 2/2 'fine' completed before"), std::string::npos) << out;
  const auto second = rows();
  ASSERT_EQ(second.size(), 3u);
  EXPECT_EQ(second[1], first[1]);                 // kept as it was
  EXPECT_EQ(second[2].rfind("fine,", 0), 0u);     // run again
  // Resumed again, both are kept.
  std::tie(code, out) = shell(study + " --resume");
  EXPECT_NE(out.find("case 2/2 'fine' completed before"), std::string::npos) << out;
  // A case run by hand on another DDS domain, with checkpoints, is still the
  // case; one with a setting that changes what it computes is not.
  auto add_override = [&](const std::string& key, const std::string& value) {
    const std::string file = dir + "/fine/summary.json";
    auto summary = nlohmann::json::parse(std::ifstream(file));
    summary["overrides"][key] = value;
    std::ofstream(file) << summary.dump(2);
  };
  add_override("coupling.domain_id", "77");
  add_override("output.checkpoint_interval_s", "0.005");
  std::tie(code, out) = shell(study + " --resume");
  EXPECT_NE(out.find("case 2/2 'fine' completed before"), std::string::npos) << out;
  add_override("sph.cfl", "0.2");
  std::tie(code, out) = shell(study + " --resume");
  EXPECT_EQ(out.find("case 2/2 'fine' completed before"), std::string::npos) << out;
}

TEST(Launcher, InterruptedRunKeepsItsOutputs) {
  const auto dir = test_support::scratch("launcher_interrupt");
  // SIGTERM two seconds into a long run: the run must stop cleanly.
  auto [code, out] = shell("bash -c '" + bin() + "/snow_sph " + test_support::scene_path("dam_break") +
                           " --out " + dir + " --quiet --no-vtk & pid=$!; sleep 2; kill -TERM $pid; wait $pid; exit $?'");
  EXPECT_EQ(code, 2) << out;
  EXPECT_NE(out.find("interrupted by a signal at step"), std::string::npos) << out;
  const auto summary = nlohmann::json::parse(std::ifstream(dir + "/summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_GT(summary["steps"].get<long>(), 0);
  std::ifstream front(dir + "/front.csv");
  std::string line;
  int rows = 0;
  while (std::getline(front, line)) ++rows;
  EXPECT_GT(rows, 2);
}

}  // namespace

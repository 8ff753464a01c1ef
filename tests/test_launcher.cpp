// The launcher as a user runs it: cosim check / run / study, through the
// real executables (cosim starts snow_sph as a child process).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
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

TEST(Launcher, StudyWritesTableAndPlot) {
  const auto dir = test_support::scratch("launcher_study");
  auto [code, out] = shell(bin() + "/cosim study " + test_support::source_dir() +
                           "/tests/test_launcher.textproto --out " + dir + " --no-vtk");
  ASSERT_EQ(code, 0) << out;
  std::ifstream table(dir + "/table.csv");
  std::string header, row1, row2;
  std::getline(table, header), std::getline(table, row1), std::getline(table, row2);
  EXPECT_EQ(header, "case,particle_spacing_m,size,time_step_s,steps,wall_time_s,final_front_m,reference,relative_error");
  EXPECT_EQ(row1.rfind("coarse,0.0057,", 0), 0u) << row1;
  EXPECT_EQ(row2.rfind("fine,0.0028575,", 0), 0u) << row2;
  EXPECT_GT(std::filesystem::file_size(dir + "/error_vs_runtime.png"), 1000u);
}

// --resume keeps a case that completed with the same overrides (its row, wall time
// included, is the earlier run's) and runs the one whose summary is missing.
TEST(Launcher, StudyResumeKeepsCompletedCasesAndRunsTheRest) {
  const auto dir = test_support::scratch("launcher_study_resume");
  const std::string study = bin() + "/cosim study " + test_support::source_dir() + "/tests/test_launcher.textproto --out " +
                            dir + " --no-vtk";
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

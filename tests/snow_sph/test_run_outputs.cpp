// Run behaviour: the same result on 1 and 2 threads, summary/CSV/VTK outputs,
// and a failing run keeps everything written up to its last step.
#include <gtest/gtest.h>

#include <fstream>
#include <omp.h>

#include "cosim/error.hpp"
#include "test_support.hpp"

namespace {

std::size_t lines_in(const std::string& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  std::string line;
  while (std::getline(in, line)) ++n;
  return n;
}

TEST(RunOutputs, SameResultOnOneAndTwoThreads) {
  const auto scene = test_support::scene_path("dam_break");
  const std::vector<std::string> sets{"time.end_time_s=0.02"};
  omp_set_num_threads(1);
  const auto one = test_support::run(scene, sets, test_support::scratch("threads1"));
  omp_set_num_threads(2);
  const auto two = test_support::run(scene, sets, test_support::scratch("threads2"));
  // Every parallel loop gathers into its own particle: bit-identical.
  EXPECT_EQ(one["results"]["final_front_m"].get<double>(), two["results"]["final_front_m"].get<double>());
  EXPECT_EQ(one["energy"]["kinetic_J"].get<double>(), two["energy"]["kinetic_J"].get<double>());
  EXPECT_EQ(one["steps"], two["steps"]);
}

TEST(RunOutputs, WritesSummaryCsvAndVtk) {
  const auto out = test_support::scratch("outputs");
  const auto s = test_support::run(test_support::scene_path("dam_break"),
                                   {"time.end_time_s=0.01", "output.vtk_interval_s=0.005"}, out, true);
  for (const char* key : {"scene", "revision", "wall_time_s", "sim_time_s", "steps", "particles", "dt_s", "energy", "results"})
    EXPECT_TRUE(s.contains(key)) << key;
  EXPECT_GT(s["dt_s"]["min"].get<double>(), 0.0);
  EXPECT_LE(s["dt_s"]["min"].get<double>(), s["dt_s"]["mean"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(out + "/summary.json"));
  EXPECT_GT(lines_in(out + "/energy.csv"), 2u);
  EXPECT_GT(lines_in(out + "/front.csv"), 2u);
  EXPECT_TRUE(std::filesystem::exists(out + "/vtk/particles_00000.vtk"));
  EXPECT_TRUE(std::filesystem::exists(out + "/vtk/particles.vtk.series"));
}

TEST(RunOutputs, FailedRunKeepsOutputsUpToLastStep) {
  // A fixed step just under the limit at rest: as the column collapses the
  // particle speed lowers the limit below it and the run must stop cleanly.
  const auto out = test_support::scratch("failure");
  const auto scene = test_support::scene_path("dam_break");
  const double h = 1.2 * 0.0028575, c = 20.0;
  const std::string dt = "time.fixed_dt_s=" + std::to_string(0.99 * h / c);
  std::string message;
  try {
    test_support::run(scene, {dt}, out);
  } catch (const cosim::Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("exceeds the stable limit"), std::string::npos) << message;
  const auto summary = nlohmann::json::parse(std::ifstream(out + "/summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_GT(summary["steps"].get<long>(), 10);
  // One CSV row per completed step (csv interval 1 ms; at least the rows up to the failure).
  const double t_fail = summary["sim_time_s"];
  EXPECT_GE(lines_in(out + "/front.csv"), static_cast<std::size_t>(t_fail / 0.001));
}

}  // namespace

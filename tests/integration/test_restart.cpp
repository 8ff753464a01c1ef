// Restart of a run from its checkpoint (docs/reliability.md): the SPH terrain
// on its own (the coarse plate sinkage) and the tyre on its road (coarse rolling),
// stopped by a signal or killed, then continued with --restart, write the same
// CSV series, byte for byte, and the same results as the runs never stopped. Byte equality is the test's
// tolerance because the restarted state is the saved bits: any difference, down
// to the last digit of the CSV's ten, is a piece of state the checkpoint missed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "cosim/checkpoint.hpp"
#include "cosim/process.hpp"
#include "test_paths.hpp"

namespace {

using test_support::read_file;

// The plate sinkage at 40 mm to 0.3 s: about 700 particles, a few seconds, the
// plate still sinking (the load ramps over 0.15 s), a checkpoint every 0.05 s.
std::vector<std::string> plate_args(const std::string& out) {
  return {test_support::scene_path("plate_sinkage"), "--out", out, "--quiet", "--no-vtk",
          "--set", "sph.particle_spacing_m=0.04", "--set", "time.end_time_s=0.3",
          "--set", "output.checkpoint_interval_s=0.05", "--set", "output.csv_interval_s=0.002"};
}

std::string snow_sph() { return test_support::bin() + "/snow_sph"; }

// Starts the run, waits for its first periodic checkpoint, then sends `signal`;
// returns the exit code.
int stopped_run(const std::string& program, const std::vector<std::string>& args, const std::string& out,
                int signal) {
  const pid_t pid = cosim::start_child(test_support::bin() + "/" + program, args, {out + ".log", out + ".log"});
  const auto start = std::chrono::steady_clock::now();
  while (cosim::list_checkpoints(out, program).empty() &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(pid, signal);
  return cosim::wait_child(pid);
}
int stopped_run(const std::string& out, int signal) { return stopped_run("snow_sph", plate_args(out), out, signal); }

// Runs snow_sph with these arguments; its exit code and output.
std::pair<int, std::string> run_snow_sph(const std::vector<std::string>& args) {
  std::string line = snow_sph();
  for (const auto& a : args) line += " '" + a + "'";
  return test_support::shell(line);
}

nlohmann::json summary(const std::string& out) { return nlohmann::json::parse(read_file(out + "/summary.json")); }

class Restart : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    whole_ = test_support::scratch("restart_whole");
    ASSERT_EQ(cosim::run_child(snow_sph(), plate_args(whole_)), 0);
  }
  static void expect_same_series(const std::string& out) {
    for (const char* file : {"energy.csv", "bodies.csv"}) {
      const std::string a = read_file(whole_ + "/" + file), b = read_file(out + "/" + file);
      EXPECT_GT(a.size(), 1000u) << file;
      EXPECT_TRUE(a == b) << file << ": the restarted run's series differs from the uninterrupted one's ("
                          << a.size() << " and " << b.size() << " bytes)";
    }
    const auto x = summary(whole_), y = summary(out);
    EXPECT_EQ(y["status"], "completed");
    EXPECT_EQ(x["steps"], y["steps"]);
    EXPECT_EQ(x["results"]["plate_displacement_m"], y["results"]["plate_displacement_m"]);
    EXPECT_EQ(x["energy"]["relative_error"], y["energy"]["relative_error"]);
    EXPECT_TRUE(y.contains("restarted_from"));
  }
  static std::string whole_;
};
std::string Restart::whole_;

TEST_F(Restart, AStopSignalWritesACheckpointAndTheRestartContinuesBitForBit) {
  const std::string out = test_support::scratch("restart_term");
  EXPECT_EQ(stopped_run(out, SIGTERM), 2);  // the run's "interrupted" failure
  const auto stopped = summary(out);
  EXPECT_EQ(stopped["status"], "failed");
  EXPECT_NE(stopped["error"].get<std::string>().find("checkpoint written"), std::string::npos);
  const double stopped_at = stopped["sim_time_s"];
  EXPECT_LT(stopped_at, 0.3);
  auto args = plate_args(out);
  args.push_back("--restart");
  ASSERT_EQ(cosim::run_child(snow_sph(), args), 0);
  // From the signal's checkpoint, not the periodic one before it.
  EXPECT_EQ(summary(out)["restarted_from"]["time_s"].get<double>(), stopped_at);
  expect_same_series(out);
}

// energy.csv's length saved in the newest checkpoint of the run in `out` (0: none yet).
std::uint64_t checkpointed_length(const std::string& out) {
  const auto files = cosim::list_checkpoints(out, "snow_sph");
  if (files.empty()) return 0;
  return cosim::CheckpointReader(files.back().path).get_value<std::uint64_t>("record.series.energy.csv");
}

TEST_F(Restart, AKilledRunRestartsFromItsLastPeriodicCheckpoint) {
  const std::string out = test_support::scratch("restart_kill");
  // Killed once rows past its newest checkpoint are on disk (the CSV flushes
  // every second), so that the restart must cut them back. The run is stopped
  // (SIGSTOP) while it is looked at: a checkpoint written between the look and
  // the kill would otherwise cover every row, as it once did in CI.
  const pid_t pid = cosim::start_child(snow_sph(), plate_args(out), {out + ".log", out + ".log"});
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    ::kill(pid, SIGSTOP);
    const std::uint64_t saved = checkpointed_length(out);
    if (saved > 0 && std::filesystem::file_size(out + "/energy.csv", ec) > saved) break;
    ::kill(pid, SIGCONT);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(pid, SIGKILL);
  EXPECT_EQ(cosim::wait_child(pid), 128 + SIGKILL);
  EXPECT_GT(std::filesystem::file_size(out + "/energy.csv"), checkpointed_length(out));
  auto args = plate_args(out);
  args.push_back("--restart");
  ASSERT_EQ(cosim::run_child(snow_sph(), args), 0);
  EXPECT_GE(summary(out)["restarted_from"]["time_s"].get<double>(), 0.05);  // a periodic checkpoint
  expect_same_series(out);
}

TEST_F(Restart, ACheckpointOfAnotherSceneOrNoneIsRefusedWithItsReason) {
  const std::string out = test_support::scratch("restart_other");
  EXPECT_EQ(stopped_run(out, SIGTERM), 2);
  auto args = plate_args(out);
  args.insert(args.end(), {"--set", "sph.quasi_static_damping_per_s=100", "--restart"});
  const auto [code, output] = run_snow_sph(args);
  EXPECT_EQ(code, 2);
  EXPECT_NE(output.find("another scene"), std::string::npos) << output;
  EXPECT_NE(output.find("/checkpoints/snow_sph-"), std::string::npos) << output;
  auto none = plate_args(test_support::scratch("restart_none"));
  none.push_back("--restart");
  const auto [code2, output2] = run_snow_sph(none);
  EXPECT_EQ(code2, 2);
  EXPECT_NE(output2.find("no checkpoint of snow_sph to restart from"), std::string::npos) << output2;
}

// The tyre on its road, coarse (30 mm elements, 36 pitches): transfer check,
// loading, 0.1 s of rolling, a checkpoint every 0.02 s (the first in the
// loading stage, so that the restarted run goes through a stage change).
std::vector<std::string> tyre_args(const std::string& out) {
  return {test_support::scene_path("tyre_rolling_road"), "--out", out, "--quiet", "--no-vtk",
          "--set", "tyre.mesh.element_size_m=0.03", "--set", "tyre.tread.pitch_count=36",
          "--set", "tyre.stages.rolling_s=0.1", "--set", "tyre.stages.average_last_s=0.05",
          "--set", "output.checkpoint_interval_s=0.02", "--set", "output.csv_interval_s=0.0005"};
}

TEST(RestartTyre, AStoppedTyreRunContinuesBitForBit) {
  const std::string whole = test_support::scratch("restart_tyre_whole");
  ASSERT_EQ(cosim::run_child(test_support::bin() + "/tyre_fe", tyre_args(whole)), 0);
  const std::string out = test_support::scratch("restart_tyre_term");
  EXPECT_EQ(stopped_run("tyre_fe", tyre_args(out), out, SIGTERM), 2);
  auto args = tyre_args(out);
  args.push_back("--restart");
  ASSERT_EQ(cosim::run_child(test_support::bin() + "/tyre_fe", args), 0);
  const std::string a = read_file(whole + "/tyre.csv"), b = read_file(out + "/tyre.csv");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "tyre.csv of the restarted run differs (" << a.size() << " and " << b.size() << " bytes)";
  const auto x = summary(whole), y = summary(out);
  EXPECT_EQ(y["status"], "completed");
  EXPECT_LT(y["restarted_from"]["time_s"].get<double>(), x["sim_time_s"].get<double>());
  // Every result, the stages finished before the stop included (the summary so far is in the checkpoint).
  for (const auto& [key, value] : x["results"].items()) EXPECT_EQ(value, y["results"][key]) << key;
}

}  // namespace

// Restart of a coupled run (docs/reliability.md, "Coupled runs"): the coarse
// torque scene, shortened (0.02 s of loading, 0.02 s of rolling under the
// torque ramp, about 1,800 coupling windows), with a checkpoint every 0.01 s
// (446 windows), run three ways:
//  - uninterrupted (the reference);
//  - stopped by SIGTERM to the launcher in the rolling stage, which every process
//    answers with a checkpoint at one exchange named by the coupler, then
//    `cosim run --restart`;
//  - with the terrain killed (SIGKILL) after a periodic checkpoint and
//    `--restart-on-failure 1`, so that the launcher starts the run again from
//    the newest checkpoint common to the three processes.
// Both continued runs must write forces.csv (the coupler's decomposition of
// every window), tyre.csv and the terrain's energy.csv byte for byte as the
// reference: the tolerance is byte equality because every process restores the
// bits it saved and the three are deterministic on a fixed thread count; any
// difference is a piece of state a checkpoint missed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <thread>

#include <nlohmann/json.hpp>

#include "cosim/process.hpp"
#include "coupled_run.hpp"
#include "test_paths.hpp"

namespace {

using test_support::read_file;

std::vector<std::string> run_args(const std::string& out, int domain) {
  return {"run", test_support::scene_path("tyre_torque_snow"), "--out", out, "--quiet", "--no-vtk",
          "--domain", std::to_string(domain),
          "--set", "tyre.stages.loading_rest_tolerance=0", "--set", "tyre.stages.loading_s=0.02", "--set", "tyre.stages.rolling_s=0.02",
          "--set", "tyre.stages.average_last_s=0.01", "--set", "coupling.average_last_s=0.01",
          "--set", "output.checkpoint_interval_s=0.01"};
}
std::string cosim_bin() { return test_support::bin() + "/cosim"; }

nlohmann::json summary(const std::string& path) { return nlohmann::json::parse(read_file(path)); }

// The exchange `cosim run --restart` would continue the run in `out` from (0: none yet).
std::uint64_t common_checkpoint(const std::string& out) {
  std::string listing;
  return cosim::newest_common_checkpoint(out, listing);
}

bool wait_for_checkpoint(const std::string& out, std::uint64_t exchange) {
  const auto start = std::chrono::steady_clock::now();
  while (common_checkpoint(out) < exchange) {
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(300)) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

class CoupledRestart : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    whole_ = test_support::scratch("coupled_restart_whole");
    ASSERT_EQ(cosim::run_child(cosim_bin(), run_args(whole_, 40)), 0);
  }
  static void expect_same_run(const std::string& out) {
    for (const char* file : {"coupler/forces.csv", "tyre/tyre.csv", "terrain/energy.csv"}) {
      const std::string a = read_file(whole_ + "/" + file), b = read_file(out + "/" + file);
      EXPECT_GT(a.size(), 5000u) << file;  // the files hold the run (tens of rows at least)
      EXPECT_TRUE(a == b) << file << ": the continued run differs from the uninterrupted one (" << a.size()
                          << " and " << b.size() << " bytes)";
    }
    const auto x = summary(whole_ + "/summary.json"), y = summary(out + "/summary.json");
    EXPECT_EQ(y["status"], "completed");
    // Every result: the steady means (the coupler's rows before the stop are in its checkpoint), the rut, the tyre's.
    for (const auto& [key, value] : x["results"].items()) EXPECT_EQ(value, y["results"][key]) << key;
  }
  static std::string whole_;
};
std::string CoupledRestart::whole_;

TEST_F(CoupledRestart, AStopSignalCheckpointsEveryProcessAtOneExchangeAndTheRestartContinuesBitForBit) {
  const std::string out = test_support::scratch("coupled_restart_term");
  const pid_t pid = cosim::start_child(cosim_bin(), run_args(out, 41), {out + ".log", out + ".log"});
  ASSERT_TRUE(wait_for_checkpoint(out, 3 * 446));  // the third periodic checkpoint: the tyre is rolling
  ::kill(pid, SIGTERM);
  EXPECT_EQ(cosim::wait_child(pid), 2) << read_file(out + ".log");
  // One exchange, named by the coupler after the periodic one, in all three.
  const std::uint64_t stop = common_checkpoint(out);
  EXPECT_GT(stop, 3u * 446u) << read_file(out + ".log");
  for (const auto& process : cosim::coupled_processes) {
    const std::string dir = process.role;
    const auto s = summary(out + "/" + dir + "/summary.json");
    EXPECT_EQ(s["status"], "failed") << dir;
    EXPECT_NE(s["error"].get<std::string>().find("stopped by a signal at exchange " + std::to_string(stop)),
              std::string::npos)
        << dir << ": " << s["error"];
  }
  const double stopped_wall_s = summary(out + "/summary.json")["wall_time_s"].get<double>();
  EXPECT_GT(stopped_wall_s, 0.0);
  auto args = run_args(out, 41);
  args.push_back("--restart");
  ASSERT_EQ(cosim::run_child(cosim_bin(), args), 0) << read_file(out + ".log");
  const auto restarted = summary(out + "/summary.json");
  EXPECT_EQ(restarted["restarted_from_exchange"], stop);
  // The run's wall time is what the whole run cost: this attempt's and the
  // stopped one's up to the checkpoint it continued from. The checkpoint was
  // written before the stopped attempt's summary, which followed it within its
  // finalize (plots, the last VTK frame: under 2 s on this scene).
  const double before_s =
      restarted["wall_time_s"].get<double>() - restarted["wall_time_this_attempt_s"].get<double>();
  EXPECT_LE(before_s, stopped_wall_s);
  EXPECT_GT(before_s, stopped_wall_s - 2.0);
  expect_same_run(out);
}

TEST_F(CoupledRestart, AKilledTerrainIsRestartedWithItsPeersFromTheirCommonCheckpoint) {
  const std::string out = test_support::scratch("coupled_restart_kill");
  auto args = run_args(out, 42);
  args.insert(args.end(), {"--restart-on-failure", "1"});
  const pid_t pid = cosim::start_child(cosim_bin(), args, {out + ".log", out + ".log"});
  ASSERT_TRUE(wait_for_checkpoint(out, 2 * 446));
  // Killed in the window after the checkpoint: rows past it are on disk and must be cut.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  test_support::shell("pkill -KILL -f -- '[c]osim_test_coupled_restart_kill/terrain '");
  ASSERT_EQ(cosim::wait_child(pid), 0) << read_file(out + ".log");
  const auto s = summary(out + "/summary.json");
  ASSERT_TRUE(s.contains("restarts_after_failure")) << s.dump(2);
  EXPECT_EQ(s["restarts_after_failure"].size(), 1u);
  EXPECT_EQ(s["restarts_after_failure"][0]["failed"], "snow_sph");
  EXPECT_GE(s["restarts_after_failure"][0]["from_exchange"].get<std::uint64_t>(), 2u * 446u);
  expect_same_run(out);
}

TEST(CoupledRestartRefusal, NoCommonCheckpointIsRefusedNamingWhatEachProcessHas) {
  const std::string out = test_support::scratch("coupled_restart_none");
  std::string line = cosim_bin();
  for (const auto& a : run_args(out, 43)) line += " '" + a + "'";
  const auto [code, output] = test_support::shell(line + " --restart");
  EXPECT_NE(code, 0);
  EXPECT_NE(output.find("no checkpoint common to the coupler, the terrain and the tyre"), std::string::npos) << output;
  EXPECT_NE(output.find("snow_sph: none"), std::string::npos) << output;
}

}  // namespace

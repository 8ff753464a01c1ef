// cosim monitor: joins a run on the domain, shows and records its force samples,
// ignores another run's samples, and ends when the run says it stopped. The
// publisher is a Fast DDS participant and the monitor a Cyclone DDS one, as a
// monitor on another host may well be.
#include <cstdio>
#include <fstream>
#include <future>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "monitor.hpp"
#include "test_paths.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using namespace test_support;

// Domain ids of this program (see transport_test_support.hpp for the others).
DomainIds domains(190, 199);

TEST(Monitor, SparklineScalesBetweenMinimumAndMaximum) {
  EXPECT_EQ(cosim::sparkline({0, 1, 2, 3, 4, 5, 6, 7}),
            "\u2581\u2582\u2583\u2584\u2585\u2586\u2587\u2588");
  EXPECT_EQ(cosim::sparkline({5, 5, 5}), "\u2581\u2581\u2581");
  EXPECT_EQ(cosim::sparkline({}), "");
}

TEST(Monitor, RecordsOneRunAndStopsWithIt) {
  if (available_vendors().size() < 2) GTEST_SKIP() << "needs both DDS vendors in this build";
  const int domain = domains.next();
  constexpr std::uint64_t kRun = 0x5eed, kOtherRun = 0xbad;
  constexpr int kSteps = 40;
  const std::string csv = test_support::scratch("monitor") + "/forces.csv";

  cosim::MonitorOptions options;
  options.vendor = Vendor::cyclone;
  options.transport = loopback(domain);
  options.csv_path = csv;
  options.run_id = kRun;
  options.refresh_s = 0.05;
  options.idle_timeout_s = 20.0;  // the test's own guard
  std::promise<void> joined;
  options.on_joined = [&] { joined.set_value(); };
  std::FILE* screen = std::tmpfile();
  auto monitor = std::async(std::launch::async, [&] { return cosim::run_monitor(options, screen); });

  auto run = make_participant(Vendor::fast, loopback(domain));
  auto forces = run->create_writer<ForceSummary>();
  auto control = run->create_writer<RunControl>();
  ASSERT_TRUE(eventually([&] { return forces->matched_readers() > 0 && control->matched_readers() > 0; }));
  // Discovery is not symmetric: wait until the monitor has found the writers too.
  ASSERT_EQ(joined.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  // A reader that joins a run under way starts at the writer's next heartbeat
  // (Cyclone discards what came before it; Fast heartbeats every 100 ms): a
  // monitor misses at most that first 0.1 s. Here the run announces itself and
  // waits past one heartbeat period so that the test can count every sample.
  forces->announce();
  control->announce();
  std::this_thread::sleep_for(std::chrono::milliseconds(250));
  forces->write(forces_sample(kOtherRun, 0));  // a stale run on the same domain
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  for (int step = 0; step < kSteps; ++step) {
    ForceSummary s = forces_sample(kRun, step);
    s.traction_force_N = 100.0 + step;
    forces->write(s);
    // A run publishes one summary per explicit step; the writer keeps the last 16
    // unacknowledged ones, so a burst faster than delivery would replace some.
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(forces->wait_for_acknowledgments(std::chrono::seconds(5)));
  RunControl stop = control_sample(kRun, kSteps);
  stop.kind = ControlKind::stop;
  stop.reason = "end time reached";
  control->write(stop);

  const cosim::MonitorResult r = monitor.get();
  EXPECT_EQ(r.samples, static_cast<std::uint64_t>(kSteps));
  EXPECT_EQ(r.other_run_samples, 1u);
  EXPECT_EQ(r.end_reason, "run stopped: end time reached");

  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("run_id,step,sim_time_s,traction_force_N", 0), 0u) << line;
  EXPECT_NE(line.find(",rolling_resistance_moment_Nm"), std::string::npos) << line;  // every field of the topic
  int rows = 0;
  while (std::getline(in, line)) {
    const std::string expected = std::to_string(kRun) + "," + std::to_string(rows) + ",";
    EXPECT_EQ(line.rfind(expected, 0), 0u) << line;
    EXPECT_NE(line.find("," + std::to_string(100 + rows) + ","), std::string::npos) << line;
    ++rows;
  }
  EXPECT_EQ(rows, kSteps);
  std::fclose(screen);
}

}  // namespace

// The real solvers are separate processes: two cosim_transport_probe
// processes (ping = tyre side, pong = terrain side), on every vendor pair,
// exchange the durable mesh and 200 lock-step steps with content checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cosim/error.hpp"
#include "cosim/process.hpp"
#include "cosim_transport/transport.hpp"
#include "test_paths.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using namespace test_support;

DomainIds domains(150, 179);

std::string probe_path() {
  const char* bin = std::getenv("COSIM_BIN_DIR");
  return std::string(bin ? bin : "build/bin") + "/cosim_transport_probe";
}

// A child process with stdout and stderr in `log`.
struct Child {
  pid_t pid = -1;
  std::string log;
  int status = -1;
};

Child start(const std::vector<std::string>& args, const std::string& log) {
  Child c;
  c.log = log;
  try {
    c.pid = cosim::start_child(args.front(), {args.begin() + 1, args.end()}, {log, log});
  } catch (const cosim::Error&) {
    c.pid = -1;
  }
  return c;
}

// Waits for both children; kills what is left at the deadline (exit status 128+9).
void wait_all(std::vector<Child*> children, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (Child* c : children) {
    if (c->pid <= 0) continue;
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    c->status = cosim::wait_child_for(c->pid, std::max(left, 0.0));
  }
}

using test_support::read_file;

class TwoProcesses : public testing::TestWithParam<VendorPair> {};

TEST_P(TwoProcesses, LockStepAcrossProcesses) {
  const std::string domain = std::to_string(domains.next());
  const std::string run = std::to_string(new_run_id());
  const std::string dir = scratch(std::string("transport_processes_") + pair_name({GetParam(), 0}));
  const std::vector<std::string> common = {"--domain", domain, "--run-id", run, "--nodes", "2000",
                                           "--steps", "200", "--timeout-ms", "15000"};
  std::vector<std::string> pong_args = {probe_path(), "--dds", vendor_name(GetParam().reader), "--role", "pong"};
  std::vector<std::string> ping_args = {probe_path(), "--dds", vendor_name(GetParam().writer), "--role", "ping"};
  pong_args.insert(pong_args.end(), common.begin(), common.end());
  ping_args.insert(ping_args.end(), common.begin(), common.end());

  // The terrain side starts first; the tyre side's mesh must still reach it.
  Child pong = start(pong_args, dir + "/pong.log");
  ASSERT_GT(pong.pid, 0) << "cannot start " << probe_path();
  Child ping = start(ping_args, dir + "/ping.log");
  ASSERT_GT(ping.pid, 0) << "cannot start " << probe_path();
  wait_all({&ping, &pong}, std::chrono::seconds(40));

  const std::string ping_log = read_file(ping.log), pong_log = read_file(pong.log);
  EXPECT_EQ(ping.status, 0) << "ping: " << ping_log;
  EXPECT_EQ(pong.status, 0) << "pong: " << pong_log;
  EXPECT_NE(ping_log.find("200 steps, 2000 nodes"), std::string::npos) << ping_log;
  EXPECT_NE(ping_log.find("rejected 0"), std::string::npos) << ping_log;
  EXPECT_NE(pong_log.find("200 steps answered, rejected 0"), std::string::npos) << pong_log;
}

INSTANTIATE_TEST_SUITE_P(Pairs, TwoProcesses, testing::ValuesIn(vendor_pairs()), pair_name);

}  // namespace

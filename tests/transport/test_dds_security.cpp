// DDS Security (docs/reliability.md, "DDS Security"): a secured domain made by
// scripts/make_test_ca.sh (PKI-DH authentication, signed governance and
// permissions, AES-GCM-GMAC encryption) on both vendors:
// - a participant without a certificate, or with one from another authority,
//   cannot read ForceSummary from a secured run nor publish ContactLoads into it
//   (every participant of a case on one vendor; each vendor in turn);
// - the monitor's identity may subscribe but not publish (its grant);
// - secured peers exchange across processes (the lock-step probe), on each vendor;
// - a secured coupled run gives the same forces as the open run, row for row,
//   and `cosim run` refuses a secured run across vendors (their secured
//   handshake fails one way, docs/reliability.md).
// Outsiders are judged by what they receive in a time in which the secured
// reader receives every sample: zero is exact, the time (2 s) is 50 times the
// time a matched pair needs on loopback here (~40 ms), so "zero" is not a race.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/process.hpp"
#include "cosim_transport/transport.hpp"
#include "test_paths.hpp"
#include "transport_test_support.hpp"

namespace {

using namespace cosim::transport;
using namespace test_support;

DomainIds domains(210, 230);  // a secured domain id is at most 230 (scripts/make_test_ca.sh)

std::string source_dir() {
  const char* s = std::getenv("COSIM_SOURCE_DIR");
  return s ? s : ".";
}

// A certificate authority of the test program's own, made once by the script
// users run (its output is what the programs read).
const std::string& make_ca(const std::string& name) {
  static std::map<std::string, std::string> made;
  auto it = made.find(name);
  if (it != made.end()) return it->second;
  const std::string dir = scratch("security_" + name);
  const std::string cmd = "bash " + source_dir() + "/scripts/make_test_ca.sh " + dir + " > " + dir + ".log 2>&1";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("make_test_ca.sh failed: " + read_file(dir + ".log"));
  return made[name] = dir;
}

TransportOptions secured(int domain, const std::string& ca_dir, const std::string& identity) {
  TransportOptions o = loopback(domain);
  o.security = {ca_dir, identity};
  return o;
}

// Waits `for_ms` and returns what `reader` took in that time.
template <class T>
std::size_t received_within(Reader<T>& reader, int for_ms) {
  std::vector<T> got;
  eventually([] { return false; }, std::chrono::milliseconds(for_ms));
  return reader.take(got);
}

// Several identities in one process, as the in-process cases need, are Fast
// DDS's alone: Cyclone's security plugins act with one identity per process
// and domain (make_participant refuses a second); Cyclone's outsiders are
// tested in their own processes (LockStepRefusesOutsiders).
class Secured : public testing::TestWithParam<Vendor> {};

bool has_vendor(Vendor v) {
  for (Vendor a : available_vendors())
    if (a == v) return true;
  return false;
}

TEST(SecuredInProcess, CycloneTakesOneIdentityPerProcessAndDomain) {
  if (!has_vendor(Vendor::cyclone)) GTEST_SKIP() << "no Cyclone DDS in this build";
  const std::string& ca = make_ca("ca");
  const int domain = domains.next();
  auto coupler = make_participant(Vendor::cyclone, secured(domain, ca, "coupler"));
  auto same = make_participant(Vendor::cyclone, secured(domain, ca, "coupler"));  // the same identity: allowed
  try {
    make_participant(Vendor::cyclone, secured(domain, ca, "monitor"));
    FAIL() << "a second identity was accepted on one Cyclone domain in one process";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find("one identity"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_participant(Vendor::cyclone, loopback(domain)), cosim::Error);
}

// Four Fast DDS participants on a fresh domain: the coupler's identity, a
// peer of the secured run (`peer_identity`), an open participant and one with
// the same role's certificate from another CA.
struct InProcessCast {
  explicit InProcessCast(const std::string& peer_identity) {
    const std::string& ca = make_ca("ca");
    const int domain = domains.next();
    coupler = make_participant(Vendor::fast, secured(domain, ca, "coupler"));
    peer = make_participant(Vendor::fast, secured(domain, ca, peer_identity));
    open = make_participant(Vendor::fast, loopback(domain));
    impostor = make_participant(Vendor::fast, secured(domain, make_ca("rogue"), peer_identity));
    monitor = [ca, domain] { return make_participant(Vendor::fast, secured(domain, ca, "monitor")); };
  }
  const std::uint64_t run = new_run_id();
  std::unique_ptr<Participant> coupler, peer, open, impostor;
  std::function<std::unique_ptr<Participant>()> monitor;
};

// The coupler's identity publishes ForceSummary, the monitor's reads it; an
// open participant and one whose certificate another CA signed never match and
// never receive a sample.
TEST(SecuredInProcess, OnlyAuthenticatedReadersReceiveForceSummary) {
  if (!has_vendor(Vendor::fast)) GTEST_SKIP() << "several identities in one process need Fast DDS";
  InProcessCast cast("monitor");
  const std::uint64_t run = cast.run;
  auto &coupler = cast.coupler, &monitor = cast.peer, &open = cast.open, &impostor = cast.impostor;

  auto writer = coupler->create_writer<ForceSummary>();
  auto reader = monitor->create_reader<ForceSummary>();
  auto open_reader = open->create_reader<ForceSummary>();
  auto impostor_reader = impostor->create_reader<ForceSummary>();
  ASSERT_TRUE(matched_both(*writer, *reader)) << "the secured pair never matched";
  // Ten samples: within the readers' keep-last depth (16), so none is replaced.
  for (std::uint64_t step = 1; step <= 10; ++step) writer->write(forces_sample(run, step));
  ASSERT_TRUE(writer->wait_for_acknowledgments(std::chrono::milliseconds(5000)));
  std::vector<ForceSummary> got;
  eventually([&] { return reader->take(got), got.size() >= 10; });
  ASSERT_EQ(got.size(), 10u);
  expect_same(got.back(), forces_sample(run, 10));  // decrypted intact

  EXPECT_EQ(received_within(*open_reader, 2000), 0u);
  EXPECT_EQ(received_within(*impostor_reader, 0), 0u);
  EXPECT_EQ(open_reader->matched_writers(), 0);
  EXPECT_EQ(impostor_reader->matched_writers(), 0);
  EXPECT_EQ(writer->matched_readers(), 1) << "only the authenticated reader may match";
}

// The coupler's identity reads ContactLoads; the terrain's publishes them. An
// open participant and an impostor publish too, and nothing of theirs arrives;
// the monitor's identity is refused a writer.
TEST(SecuredInProcess, OnlyGrantedWritersPublishContactLoads) {
  if (!has_vendor(Vendor::fast)) GTEST_SKIP() << "several identities in one process need Fast DDS";
  InProcessCast cast("terrain");
  const std::uint64_t run = cast.run;
  auto &coupler = cast.coupler, &terrain = cast.peer, &open = cast.open, &impostor = cast.impostor;

  auto reader = coupler->create_reader<ContactLoads>();
  auto writer = terrain->create_writer<ContactLoads>();
  auto open_writer = open->create_writer<ContactLoads>();
  auto impostor_writer = impostor->create_writer<ContactLoads>();
  ASSERT_TRUE(matched_both(*writer, *reader)) << "the secured pair never matched";
  // Outsiders publish first, then the terrain: whatever the reader has once
  // the terrain's samples are in is everything that reached it.
  for (std::uint64_t step = 1; step <= 10; ++step) {
    open_writer->write(loads_sample(run, 1000 + step, 8));
    impostor_writer->write(loads_sample(run, 2000 + step, 8));
  }
  eventually([] { return false; }, std::chrono::milliseconds(2000));
  for (std::uint64_t step = 1; step <= 10; ++step) writer->write(loads_sample(run, step, 8));
  ASSERT_TRUE(writer->wait_for_acknowledgments(std::chrono::milliseconds(5000)));
  std::vector<ContactLoads> got;
  eventually([&] { return reader->take(got), got.size() >= 10; });
  reader->take(got);
  ASSERT_EQ(got.size(), 10u) << "samples from outside the secured domain arrived";
  for (const auto& s : got) EXPECT_LE(s.header.step, 10u);
  EXPECT_EQ(reader->matched_writers(), 1);
  EXPECT_EQ(open_writer->matched_readers(), 0);
  EXPECT_EQ(impostor_writer->matched_readers(), 0);

  // The monitor's grant has no publish rule: access control refuses the writer.
  auto monitor = cast.monitor();
  EXPECT_THROW(monitor->create_writer<ContactLoads>(), cosim::Error);
}

// The lock-step probe as two processes (tyre and terrain identities): the
// secured exchange of 200 steps, content checked.
TEST_P(Secured, LockStepAcrossProcesses) {
  const std::string& ca = make_ca("ca");
  const std::string dir = scratch(std::string("security_probe_") + vendor_name(GetParam()));
  const std::vector<std::string> common = {"--dds", vendor_name(GetParam()), "--domain", std::to_string(domains.next()),
                                           "--run-id", std::to_string(new_run_id()), "--nodes", "2000", "--steps",
                                           "200", "--timeout-ms", "20000", "--security", ca};
  const std::string probe = bin() + "/cosim_transport_probe";
  auto pong_args = common, ping_args = common;
  pong_args.insert(pong_args.end(), {"--role", "pong"});
  ping_args.insert(ping_args.end(), {"--role", "ping"});
  const pid_t pong = cosim::start_child(probe, pong_args, {dir + "/pong.log", dir + "/pong.log"});
  const pid_t ping = cosim::start_child(probe, ping_args, {dir + "/ping.log", dir + "/ping.log"});
  EXPECT_EQ(cosim::wait_child_for(ping, 60.0), 0) << read_file(dir + "/ping.log");
  EXPECT_EQ(cosim::wait_child_for(pong, 10.0), 0) << read_file(dir + "/pong.log");
  EXPECT_NE(read_file(dir + "/ping.log").find("200 steps, 2000 nodes"), std::string::npos);
  EXPECT_NE(read_file(dir + "/pong.log").find("200 steps answered, rejected 0"), std::string::npos);
}

// Outsiders in their own processes: an open tyre (no --security), then a tyre
// whose certificate another CA signed, each beside a secured terrain. Neither
// side ever matches the other, and both say so when the handshake times out.
TEST_P(Secured, LockStepRefusesOutsiders) {
  const std::string& ca = make_ca("ca");
  const std::string& rogue = make_ca("rogue");
  const std::string probe = bin() + "/cosim_transport_probe";
  for (const std::string& tyre_folder : {std::string(), rogue}) {
    const std::string dir = scratch(std::string("security_outsider_") + vendor_name(GetParam()) +
                                    (tyre_folder.empty() ? "_open" : "_rogue"));
    const std::vector<std::string> common = {"--dds", vendor_name(GetParam()), "--domain",
                                             std::to_string(domains.next()), "--run-id", std::to_string(new_run_id()),
                                             "--nodes", "200", "--steps", "10", "--timeout-ms", "4000"};
    auto pong_args = common, ping_args = common;
    pong_args.insert(pong_args.end(), {"--role", "pong", "--security", ca});
    ping_args.insert(ping_args.end(), {"--role", "ping"});
    if (!tyre_folder.empty()) ping_args.insert(ping_args.end(), {"--security", tyre_folder});
    const pid_t pong = cosim::start_child(probe, pong_args, {dir + "/pong.log", dir + "/pong.log"});
    const pid_t ping = cosim::start_child(probe, ping_args, {dir + "/ping.log", dir + "/ping.log"});
    EXPECT_EQ(cosim::wait_child_for(ping, 30.0), 1) << read_file(dir + "/ping.log");
    EXPECT_EQ(cosim::wait_child_for(pong, 30.0), 1) << read_file(dir + "/pong.log");
    for (const char* log : {"/ping.log", "/pong.log"})
      EXPECT_NE(read_file(dir + log).find("never matched"), std::string::npos) << dir << log << ": "
                                                                               << read_file(dir + log);
  }
}

INSTANTIATE_TEST_SUITE_P(Vendors, Secured, testing::ValuesIn(available_vendors()), vendor_param_name);

TEST(SecurityFiles, AMissingFileIsNamed) {
  const std::string dir = scratch("security_missing");
  TransportOptions o = secured(domains.next(), dir, "tyre");
  try {
    make_participant(available_vendors().front(), o);
    FAIL() << "a participant was made without its security files";
  } catch (const cosim::Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/identity_ca.pem"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("make_test_ca.sh"), std::string::npos) << e.what();
  }
}

// The coarse torque scene, shortened (0.02 s of loading, 0.005 s of rolling:
// about 1,100 coupling windows), open and secured on one domain id: the
// decomposition of every window (forces.csv) must be byte-identical, because
// security changes what travels on the wire (signed, encrypted) and not one
// bit of what arrives; the three processes are deterministic, and the open
// run's forces are the same on either vendor (docs/coupling.md).
std::vector<std::string> torque_run(const std::string& out, int domain, const std::string& vendors) {
  return {"run", scene_path("tyre_torque_snow"), "--out", out, "--quiet", "--no-vtk", "--domain",
          std::to_string(domain), "--dds", vendors, "--set", "tyre.stages.loading_rest_tolerance=0", "--set", "tyre.stages.loading_s=0.02",
          "--set", "tyre.stages.rolling_s=0.005", "--set", "tyre.stages.average_last_s=0.0025",
          "--set", "coupling.average_last_s=0.0025"};
}

// The open run on Cyclone DDS, then the secured run on each vendor.
TEST(SecuredCoupledRun, GivesTheOpenRunsForces) {
  const std::string& ca = make_ca("ca");
  const std::string open = scratch("security_open_run");
  const int domain = domains.next();
  ASSERT_EQ(cosim::run_child(bin() + "/cosim", torque_run(open, domain, "cyclone")), 0);
  const std::string a = read_file(open + "/coupler/forces.csv");
  EXPECT_GT(a.size(), 5000u);  // the run is in it (hundreds of rows)
  for (Vendor v : available_vendors()) {
    const std::string closed = scratch(std::string("security_secured_run_") + vendor_name(v));
    auto args = torque_run(closed, domain, vendor_name(v));
    args.insert(args.end(), {"--security", ca});
    ASSERT_EQ(cosim::run_child(bin() + "/cosim", args), 0) << vendor_name(v);
    const std::string b = read_file(closed + "/coupler/forces.csv");
    EXPECT_TRUE(a == b) << vendor_name(v) << ": the secured run's forces differ from the open run's (" << a.size()
                        << " and " << b.size() << " bytes)";
    const auto summary = nlohmann::json::parse(read_file(closed + "/summary.json"));
    EXPECT_EQ(summary["status"], "completed");
    EXPECT_EQ(summary["dds_security"], std::filesystem::absolute(ca).string());
  }
}

TEST(SecuredCoupledRun, AcrossVendorsIsRefusedWithTheReason) {
  const std::string& ca = make_ca("ca");
  const std::string out = scratch("security_mixed_run");
  auto args = torque_run(out, domains.next(), "tyre=fast,terrain=cyclone,coupler=cyclone");
  args.insert(args.end(), {"--security", ca});
  const pid_t pid = cosim::start_child(bin() + "/cosim", args, {out + ".log", out + ".log"});
  EXPECT_EQ(cosim::wait_child_for(pid, 60.0), 2);
  EXPECT_NE(read_file(out + ".log").find("a secured run needs one DDS vendor"), std::string::npos)
      << read_file(out + ".log");
}

}  // namespace

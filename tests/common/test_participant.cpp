// The run skeleton (cosim/participant.hpp) on a participant made for the test:
// a normal end writes summary.json with the participant's results and closes
// the CSV series; a failure at step 3 keeps the rows of steps 1-2 on disk, tells
// the peers (abort) with the reason, still records the results reached, says
// "status": "failed" with the error and rethrows it as cosim::Error. Exact
// comparisons: counts and strings, nothing numerical.
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cosim/error.hpp"
#include "cosim/outputs.hpp"
#include "cosim/participant.hpp"
#include "cosim/scene_io.hpp"
#include "test_paths.hpp"

namespace {

class Counter final : public cosim::Participant {
 public:
  explicit Counter(std::uint64_t fail_at) : fail_at_(fail_at) {}  // 0: never
  double initialize(cosim::RunRecord& record) override {
    csv_ = &record.series("count.csv", {"time_s", "step"});
    return 5.0;
  }
  bool advance() override {
    if (step_ == 5) return false;
    ++step_;
    if (step_ == fail_at_) throw cosim::Error("broke at step " + std::to_string(step_));
    return true;
  }
  double time_s() const override { return double(step_); }
  std::uint64_t steps() const override { return step_; }
  void output(cosim::RunRecord&) override { csv_->row({double(step_), double(step_)}); }
  void finalize(cosim::RunRecord& record) override { record.results()["last_step"] = step_; }
  void finish_peers() override { ++stops_; }
  void abort(const std::string& reason) noexcept override { abort_reason_ = reason; }

  std::uint64_t fail_at_;
  std::uint64_t step_ = 0;
  int stops_ = 0;
  std::string abort_reason_;
  cosim::CsvWriter* csv_ = nullptr;
};

std::unique_ptr<cosim::LoadedScene> scene(const std::string& dir) {
  const std::string path = dir + "/scene.textproto";
  std::ofstream(path) << "name: \"counter\"\n";
  return cosim::load_scene(path);
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(std::ifstream(path)); }

}  // namespace

TEST(RunSkeleton, NormalEndWritesTheSummaryAndTheSeries) {
  const std::string dir = test_support::scratch("participant_ok");
  const auto loaded = scene(dir);
  cosim::RunRecord record(*loaded, dir + "/out", "counter");
  Counter p(0);
  const auto summary = cosim::run_participant(p, record, "counter", true);
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(p.stops_, 1);
  EXPECT_TRUE(p.abort_reason_.empty());
  const auto on_disk = read_json(dir + "/out/summary.json");
  EXPECT_EQ(on_disk["status"], "completed");
  EXPECT_EQ(on_disk["steps"], 5);
  EXPECT_EQ(on_disk["results"]["last_step"], 5);
  EXPECT_EQ(on_disk["participants"][0], "counter");
  EXPECT_EQ(lines(dir + "/out/count.csv").size(), 6u);  // header + 5 steps
}

TEST(RunSkeleton, FailureKeepsTheRowsTellsThePeersAndSaysWhy) {
  const std::string dir = test_support::scratch("participant_fail");
  const auto loaded = scene(dir);
  cosim::RunRecord record(*loaded, dir + "/out", "counter");
  Counter p(3);
  try {
    cosim::run_participant(p, record, "counter", true);
    FAIL() << "the failure was not rethrown";
  } catch (const cosim::Error& e) {
    EXPECT_EQ(std::string(e.what()), "broke at step 3");
  }
  EXPECT_EQ(p.abort_reason_, "broke at step 3");
  EXPECT_EQ(p.stops_, 0);  // a failed run sends no normal stop
  const auto on_disk = read_json(dir + "/out/summary.json");
  EXPECT_EQ(on_disk["status"], "failed");
  EXPECT_EQ(on_disk["error"], "broke at step 3");
  EXPECT_EQ(on_disk["results"]["last_step"], 3);  // what the run reached
  EXPECT_EQ(lines(dir + "/out/count.csv").size(), 3u);  // header + steps 1 and 2
}

// A restarted run appends to its series: a build that writes other columns
// (a newer coupler's forces.csv) would put rows of another layout under the old
// header. It is refused with the file, the line and both headers; the same
// columns continue.
TEST(RunSkeleton, ARestartWithOtherColumnsIsRefusedNamingTheFile) {
  const std::string path = test_support::scratch("csv_resume") + "/forces.csv";
  { cosim::CsvWriter first(path, {"time_s", "force_N"}, false); first.row({0.0, 1.0}); }
  EXPECT_NO_THROW(cosim::CsvWriter(path, {"time_s", "force_N"}, true));
  try {
    cosim::CsvWriter other(path, {"time_s", "force_N", "lift_N"}, true);
    FAIL() << "a restart with other columns was accepted";
  } catch (const cosim::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ", line 1"), std::string::npos) << what;
    EXPECT_NE(what.find("'time_s,force_N'"), std::string::npos) << what;
    EXPECT_NE(what.find("'time_s,force_N,lift_N'"), std::string::npos) << what;
  }
}

// The checkpoint file (cosim/checkpoint.hpp): what is written is read back
// exactly, and every kind of file that must not restart a run is refused with
// a message that names it: torn, damaged, of another program or scene, of
// another format version, or missing a record.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>

#include "cosim/checkpoint.hpp"
#include "cosim/error.hpp"
#include "test_paths.hpp"

namespace {

std::string write_sample(const std::string& dir, std::uint64_t hash = 42) {
  cosim::CheckpointWriter out("snow_sph", hash, 1234, 0.0625);
  out.put("x", std::vector<double>{1.5, -0.0, std::numeric_limits<double>::denorm_min(), 1e308});
  out.put("id", std::vector<std::uint32_t>{7, 3, 4294967295u});
  out.put("flags", std::vector<std::uint8_t>{0, 1});
  out.put("empty", std::vector<float>{});
  out.put_value<std::uint64_t>("steps", 1234);
  out.put_text("note", "plate");
  const std::string path = cosim::checkpoint_path(dir, "snow_sph", 1234);
  out.commit(path);
  return path;
}

using test_support::error_of;

TEST(Checkpoint, RecordsComeBackBitForBit) {
  const std::string dir = test_support::scratch("checkpoint_roundtrip");
  const cosim::CheckpointReader in(write_sample(dir));
  EXPECT_EQ(in.program(), "snow_sph");
  EXPECT_EQ(in.step(), 1234u);
  EXPECT_EQ(in.time_s(), 0.0625);
  const auto x = in.get<double>("x");
  ASSERT_EQ(x.size(), 4u);
  EXPECT_TRUE(std::signbit(x[1]));  // -0.0 stays negative zero: bytes, not text
  EXPECT_EQ(x[2], std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(x[3], 1e308);
  EXPECT_EQ(in.get<std::uint32_t>("id"), (std::vector<std::uint32_t>{7, 3, 4294967295u}));
  EXPECT_EQ(in.get<std::uint8_t>("flags"), (std::vector<std::uint8_t>{0, 1}));
  EXPECT_TRUE(in.get<float>("empty").empty());
  EXPECT_EQ(in.get_value<std::uint64_t>("steps"), 1234u);
  EXPECT_EQ(in.get_text("note"), "plate");
  EXPECT_NO_THROW(in.expect("snow_sph", 42));
}

TEST(Checkpoint, ATornOrDamagedFileIsRefused) {
  const std::string dir = test_support::scratch("checkpoint_damaged");
  const std::string path = write_sample(dir);
  const auto size = std::filesystem::file_size(path);
  // Torn: the last 100 bytes missing.
  std::filesystem::copy_file(path, path + ".cut");
  std::filesystem::resize_file(path + ".cut", size - 100);
  EXPECT_NE(error_of([&] { cosim::CheckpointReader r(path + ".cut"); }).find("checksum"), std::string::npos);
  // One bit flipped in the middle of the data.
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(size / 2));
    char c = 0;
    f.read(&c, 1);
    f.seekp(static_cast<std::streamoff>(size / 2));
    c = static_cast<char>(c ^ 0x10);
    f.write(&c, 1);
  }
  const std::string message = error_of([&] { cosim::CheckpointReader r(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("checksum"), std::string::npos) << message;
  // Not a checkpoint at all.
  { std::ofstream(dir + "/other.ckpt") << "time_s,x\n0,1\n"; }
  EXPECT_NE(error_of([&] { cosim::CheckpointReader r(dir + "/other.ckpt"); }).find("not a checkpoint"),
            std::string::npos);
}

TEST(Checkpoint, AnotherProgramSceneOrRecordIsRefusedByName) {
  const std::string dir = test_support::scratch("checkpoint_mismatch");
  const cosim::CheckpointReader in(write_sample(dir, 42));
  EXPECT_NE(error_of([&] { in.expect("tyre_fe", 42); }).find("a checkpoint of snow_sph, not of tyre_fe"),
            std::string::npos);
  EXPECT_NE(error_of([&] { in.expect("snow_sph", 43); }).find("another scene"), std::string::npos);
  EXPECT_NE(error_of([&] { in.get<double>("vx"); }).find("no record 'vx'"), std::string::npos);
  EXPECT_NE(error_of([&] { in.get<float>("x"); }).find("type code"), std::string::npos);
  EXPECT_NE(error_of([&] { in.get<double>("x", 5); }).find("has 4 values, the model 5"), std::string::npos);
}

TEST(Checkpoint, TheSceneHashSeesTheOverridesButNotTheOutputIntervals) {
  cosim::scene::Scene a;
  a.set_name("plate");
  a.mutable_time()->set_end_time_s(1.0);
  cosim::scene::Scene b = a;
  b.mutable_output()->set_csv_interval_s(0.01);
  b.mutable_output()->set_checkpoint_interval_s(0.1);
  EXPECT_EQ(cosim::scene_hash(a), cosim::scene_hash(b));
  b.mutable_time()->set_end_time_s(2.0);
  EXPECT_NE(cosim::scene_hash(a), cosim::scene_hash(b));
}

TEST(Checkpoint, ListingIsByStepAndPruningKeepsTheNewest) {
  const std::string dir = test_support::scratch("checkpoint_list");
  for (std::uint64_t step : {900u, 30u, 12000u}) {
    cosim::CheckpointWriter out("tyre_fe", 1, step, 0.0);
    out.commit(cosim::checkpoint_path(dir, "tyre_fe", step));
  }
  write_sample(dir);  // another program's
  { std::ofstream(cosim::checkpoint_path(dir, "tyre_fe", 99999) + ".tmp") << "half"; }  // a write cut short
  auto files = cosim::list_checkpoints(dir, "tyre_fe");
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].step, 30u);
  EXPECT_EQ(files[2].step, 12000u);
  cosim::prune_checkpoints(dir, "tyre_fe", 2);
  files = cosim::list_checkpoints(dir, "tyre_fe");
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].step, 900u);
  EXPECT_EQ(cosim::list_checkpoints(dir, "snow_sph").size(), 1u);
}

}  // namespace

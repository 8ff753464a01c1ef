#pragma once
// Checkpoints of a run's whole state, for restart (docs/reliability.md).
//
// File format (version 1, little-endian, every integer fixed-width):
//   "COSIMCKP"                      8 bytes, the magic
//   u32 format version              kCheckpointFormatVersion
//   string program                  "snow_sph", "tyre_fe", "coupler"
//   u64 scene hash                  scene_hash(): the scene and its --set overrides
//   u64 step, f64 time_s            the step the state is at (coupled: the exchange)
//   u32 record count, then records:  string name, u8 type, u64 count, count values
//   u64 checksum                    FNV-1a of every byte before it
// A string is a u32 length and its bytes. The file is written beside its final
// name and renamed onto it, so a reader never sees a torn checkpoint; a file
// whose checksum does not match (a disk fault) is refused all the same.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"

namespace cosim {

inline constexpr std::uint32_t kCheckpointFormatVersion = 1;

// FNV-1a (64 bit) of the scene as run: its message with the overrides applied,
// serialized deterministically, without its `output` section (intervals of files,
// which a restart may change without changing the physics).
std::uint64_t scene_hash(const scene::Scene& scene);

namespace detail {
// The record's value type, stored in the file.
template <class T> constexpr std::uint8_t checkpoint_type_code() {
  if constexpr (std::is_same_v<T, double>) return 1;
  else if constexpr (std::is_same_v<T, float>) return 2;
  else if constexpr (std::is_same_v<T, std::uint64_t>) return 3;
  else if constexpr (std::is_same_v<T, std::uint32_t>) return 4;
  else if constexpr (std::is_same_v<T, std::uint16_t>) return 5;
  else if constexpr (std::is_same_v<T, std::uint8_t>) return 6;
  else if constexpr (std::is_same_v<T, std::int64_t>) return 7;
  else static_assert(sizeof(T) == 0, "no checkpoint type code for this type");
}
}  // namespace detail

class CheckpointWriter {
 public:
  CheckpointWriter(const std::string& program, std::uint64_t scene_hash, std::uint64_t step, double time_s);

  template <class T> void put(const std::string& name, const std::vector<T>& values) {
    put_raw(name, detail::checkpoint_type_code<T>(), values.size(), values.data(), sizeof(T));
  }
  template <class T> void put_value(const std::string& name, T value) {
    put_raw(name, detail::checkpoint_type_code<T>(), 1, &value, sizeof(T));
  }
  void put_text(const std::string& name, const std::string& text) {
    put_raw(name, detail::checkpoint_type_code<std::uint8_t>(), text.size(), text.data(), 1);
  }
  // Writes `path` atomically (a temporary file beside it, flushed, renamed onto it).
  void commit(const std::string& path) const;
  std::size_t bytes() const { return body_.size(); }

 private:
  void put_raw(const std::string& name, std::uint8_t type, std::uint64_t count, const void* data, std::size_t size);
  std::vector<char> body_;
  std::size_t count_at_ = 0;  // where the record count goes in body_
  std::vector<std::string> names_;
};

class CheckpointReader {
 public:
  // Reads and checks the file (magic, version, checksum); throws cosim::Error naming it.
  explicit CheckpointReader(const std::string& path);
  // Refuses a checkpoint of another program or of another scene.
  void expect(const std::string& program, std::uint64_t scene_hash) const;

  const std::string& path() const { return path_; }
  const std::string& program() const { return program_; }
  std::uint64_t step() const { return step_; }
  double time_s() const { return time_s_; }
  bool has(const std::string& name) const;

  template <class T> std::vector<T> get(const std::string& name) const {
    const Record& r = find(name, detail::checkpoint_type_code<T>());
    std::vector<T> values(r.count);
    if (r.count) std::memcpy(values.data(), data_.data() + r.offset, r.count * sizeof(T));
    return values;
  }
  // A vector that must have `count` entries (a per-particle field of a known model).
  template <class T> std::vector<T> get(const std::string& name, std::size_t count) const {
    std::vector<T> values = get<T>(name);
    if (values.size() != count) throw_count(name, values.size(), count);
    return values;
  }
  template <class T> T get_value(const std::string& name) const { return get<T>(name, 1)[0]; }
  std::string get_text(const std::string& name) const {
    const std::vector<std::uint8_t> bytes = get<std::uint8_t>(name);
    return std::string(bytes.begin(), bytes.end());
  }
  // Names of the records whose name starts with `prefix`.
  std::vector<std::string> names_with_prefix(const std::string& prefix) const;

 private:
  struct Record {
    std::string name;
    std::uint8_t type = 0;
    std::uint64_t count = 0;
    std::size_t offset = 0;
  };
  const Record& find(const std::string& name, std::uint8_t type) const;
  [[noreturn]] void throw_count(const std::string& name, std::size_t got, std::size_t want) const;
  std::string path_, program_;
  std::uint64_t scene_hash_ = 0, step_ = 0;
  double time_s_ = 0.0;
  std::vector<char> data_;
  std::vector<Record> records_;
};

// The checkpoints of one program in a run's output folder: DIR/checkpoints/PROGRAM-STEP.ckpt.
struct CheckpointFile {
  std::string path;
  std::uint64_t step = 0;
};
std::string checkpoint_path(const std::string& out_dir, const std::string& program, std::uint64_t step);
// Sorted by step, oldest first (files of other programs and temporary files ignored).
std::vector<CheckpointFile> list_checkpoints(const std::string& out_dir, const std::string& program);
// Deletes all but the newest `keep` checkpoints of the program.
void prune_checkpoints(const std::string& out_dir, const std::string& program, std::size_t keep);

}  // namespace cosim

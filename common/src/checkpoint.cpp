#include "cosim/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include "cosim/outputs.hpp"

namespace cosim {
namespace {

constexpr char kMagic[8] = {'C', 'O', 'S', 'I', 'M', 'C', 'K', 'P'};
const char* const kSuffix = ".ckpt";

std::uint64_t fnv1a(const char* data, std::size_t size, std::uint64_t h = 1469598103934665603ull) {
  for (std::size_t i = 0; i < size; ++i) h = (h ^ static_cast<unsigned char>(data[i])) * 1099511628211ull;
  return h;
}

template <class T> void append(std::vector<char>& out, T value) {
  const char* p = reinterpret_cast<const char*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}
void append_text(std::vector<char>& out, const std::string& s) {
  append<std::uint32_t>(out, static_cast<std::uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

std::size_t type_size(std::uint8_t type) {
  switch (type) {
    case 1: case 3: case 7: return 8;
    case 2: case 4: return 4;
    case 5: return 2;
    case 6: return 1;
    default: return 0;
  }
}

// Reads the file's fields in order, naming the file in every error.
class Cursor {
 public:
  Cursor(const std::vector<char>& data, const std::string& path) : data_(data), path_(path) {}
  template <class T> T take() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string text() {
    const std::uint32_t n = take<std::uint32_t>();
    need(n);
    std::string s(data_.data() + at_, n);
    at_ += n;
    return s;
  }
  std::size_t skip(std::uint64_t bytes) {
    need(bytes);
    const std::size_t start = at_;
    at_ += static_cast<std::size_t>(bytes);
    return start;
  }
  std::size_t at() const { return at_; }

 private:
  void need(std::uint64_t bytes) const {
    if (bytes > data_.size() - at_)
      throw Error(path_ + ": checkpoint ends early at byte " + std::to_string(at_) + " (truncated file)");
  }
  const std::vector<char>& data_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

std::uint64_t scene_hash(const scene::Scene& scene) {
  scene::Scene copy = scene;
  copy.clear_output();
  std::string bytes;
  {
    google::protobuf::io::StringOutputStream stream(&bytes);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    copy.SerializeToCodedStream(&coded);
  }
  return fnv1a(bytes.data(), bytes.size());
}

CheckpointWriter::CheckpointWriter(const std::string& program, std::uint64_t hash, std::uint64_t step, double time_s) {
  body_.insert(body_.end(), kMagic, kMagic + 8);
  append<std::uint32_t>(body_, kCheckpointFormatVersion);
  append_text(body_, program);
  append<std::uint64_t>(body_, hash);
  append<std::uint64_t>(body_, step);
  append<double>(body_, time_s);
  count_at_ = body_.size();
  append<std::uint32_t>(body_, 0);  // record count, set by commit()
}

void CheckpointWriter::put_raw(const std::string& name, std::uint8_t type, std::uint64_t count, const void* data,
                               std::size_t size) {
  if (std::find(names_.begin(), names_.end(), name) != names_.end())
    throw Error("checkpoint: record '" + name + "' written twice");
  names_.push_back(name);
  append_text(body_, name);
  append<std::uint8_t>(body_, type);
  append<std::uint64_t>(body_, count);
  const char* p = static_cast<const char*>(data);
  body_.insert(body_.end(), p, p + count * size);
}

void CheckpointWriter::commit(const std::string& path) const {
  std::vector<char> out = body_;
  const auto records = static_cast<std::uint32_t>(names_.size());
  std::memcpy(out.data() + count_at_, &records, 4);
  append<std::uint64_t>(out, fnv1a(out.data(), out.size()));
  make_folder(std::filesystem::path(path).parent_path().string());
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw Error(tmp + ": cannot write checkpoint: " + std::strerror(errno));
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::write(fd, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw Error(tmp + ": checkpoint write failed: " + why);
    }
    done += static_cast<std::size_t>(n);
  }
  // On disk before the rename makes it the checkpoint (a crash leaves the old one or the new one).
  if (::fsync(fd) != 0 || ::close(fd) != 0) throw Error(tmp + ": checkpoint flush failed: " + std::strerror(errno));
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw Error(path + ": cannot rename the checkpoint from " + tmp + ": " + std::strerror(errno));
}

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read checkpoint: " + std::strerror(errno));
  data_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (data_.size() < 8 + 4 + 8 || std::memcmp(data_.data(), kMagic, 8) != 0)
    throw Error(path + ": not a checkpoint (no COSIMCKP header)");
  std::uint64_t stored = 0;
  std::memcpy(&stored, data_.data() + data_.size() - 8, 8);
  if (fnv1a(data_.data(), data_.size() - 8) != stored)
    throw Error(path + ": checkpoint checksum does not match (a damaged or truncated file)");
  Cursor c(data_, path);
  c.skip(8);
  const auto version = c.take<std::uint32_t>();
  if (version != kCheckpointFormatVersion)
    throw Error(path + ": checkpoint format version " + std::to_string(version) + "; this build reads version " +
                std::to_string(kCheckpointFormatVersion));
  program_ = c.text();
  scene_hash_ = c.take<std::uint64_t>();
  step_ = c.take<std::uint64_t>();
  time_s_ = c.take<double>();
  const auto count = c.take<std::uint32_t>();
  for (std::uint32_t k = 0; k < count; ++k) {
    Record r;
    r.name = c.text();
    r.type = c.take<std::uint8_t>();
    r.count = c.take<std::uint64_t>();
    const std::size_t size = type_size(r.type);
    if (size == 0) throw Error(path + ": record '" + r.name + "' has an unknown type code " + std::to_string(r.type));
    if (r.count > (data_.size() - c.at()) / size)
      throw Error(path + ": record '" + r.name + "' runs past the end of the file");
    r.offset = c.skip(r.count * size);
    records_.push_back(std::move(r));
  }
  if (c.at() != data_.size() - 8) throw Error(path + ": checkpoint has trailing bytes after its records");
}

void CheckpointReader::expect(const std::string& program, std::uint64_t hash) const {
  if (program_ != program)
    throw Error(path_ + ": a checkpoint of " + program_ + ", not of " + program);
  if (scene_hash_ != hash)
    throw Error(path_ + ": a checkpoint of another scene (or other --set overrides): scene hash " +
                std::to_string(scene_hash_) + ", this run's " + std::to_string(hash));
}

bool CheckpointReader::has(const std::string& name) const {
  return std::any_of(records_.begin(), records_.end(), [&](const Record& r) { return r.name == name; });
}

std::vector<std::string> CheckpointReader::names_with_prefix(const std::string& prefix) const {
  std::vector<std::string> names;
  for (const Record& r : records_)
    if (r.name.compare(0, prefix.size(), prefix) == 0) names.push_back(r.name);
  return names;
}

const CheckpointReader::Record& CheckpointReader::find(const std::string& name, std::uint8_t type) const {
  for (const Record& r : records_)
    if (r.name == name) {
      if (r.type != type)
        throw Error(path_ + ": checkpoint record '" + name + "' has type code " + std::to_string(r.type) +
                    ", expected " + std::to_string(type));
      return r;
    }
  throw Error(path_ + ": checkpoint has no record '" + name + "' (written by another version?)");
}

void CheckpointReader::throw_count(const std::string& name, std::size_t got, std::size_t want) const {
  throw Error(path_ + ": checkpoint record '" + name + "' has " + std::to_string(got) + " values, the model " +
              std::to_string(want));
}

std::string checkpoint_path(const std::string& out_dir, const std::string& program, std::uint64_t step) {
  std::ostringstream name;
  name << out_dir << "/checkpoints/" << program << "-" << std::setw(12) << std::setfill('0') << step << kSuffix;
  return name.str();
}

std::vector<CheckpointFile> list_checkpoints(const std::string& out_dir, const std::string& program) {
  std::vector<CheckpointFile> files;
  const std::filesystem::path folder = std::filesystem::path(out_dir) / "checkpoints";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return files;
  const std::string head = program + "-";
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    const std::size_t suffix = std::string(kSuffix).size();
    if (name.size() <= head.size() + suffix || name.compare(0, head.size(), head) != 0 ||
        name.compare(name.size() - suffix, suffix, kSuffix) != 0)
      continue;
    const std::string digits = name.substr(head.size(), name.size() - head.size() - suffix);
    if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
      continue;
    files.push_back({entry.path().string(), std::stoull(digits)});
  }
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.step < b.step; });
  return files;
}

void prune_checkpoints(const std::string& out_dir, const std::string& program, std::size_t keep) {
  const auto files = list_checkpoints(out_dir, program);
  for (std::size_t k = 0; k + keep < files.size(); ++k) {
    std::error_code ec;
    std::filesystem::remove(files[k].path, ec);  // a file left behind costs disk, not correctness
  }
}

}  // namespace cosim

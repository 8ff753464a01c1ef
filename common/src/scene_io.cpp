#include "cosim/scene_io.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <google/protobuf/descriptor.h>
#include <google/protobuf/io/tokenizer.h>

#include "cosim/error.hpp"
#include "cosim/strings.hpp"

namespace cosim {
namespace pb = google::protobuf;

// Scene, material and study files are a few kilobytes; the cap keeps a path to
// a device or a huge file (/dev/zero, a mistyped material_file) from reading
// without end (tests/fuzz/fuzz_scene.cpp).
constexpr std::uintmax_t kMaxInputFileBytes = 16u << 20;

std::string read_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw Error(path + ": cannot open file");
  if (!std::filesystem::is_regular_file(status)) throw Error(path + ": not a regular file");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > kMaxInputFileBytes)
    throw Error(path + ": larger than " + std::to_string(kMaxInputFileBytes >> 20) + " MiB; not a scene, study or material file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

namespace {

// "Did you mean ...?" for an unknown field of a message type.
std::string suggestion(const pb::Descriptor* d, const std::string& name) {
  if (!d) return "";
  std::string best;
  std::size_t best_distance = 4;  // suggest only close names
  for (int i = 0; i < d->field_count(); ++i) {
    const std::size_t dist = edit_distance(name, d->field(i)->name());
    if (dist < best_distance) best_distance = dist, best = d->field(i)->name();
  }
  std::string fields;
  for (int i = 0; i < d->field_count(); ++i) fields += (i ? ", " : "") + d->field(i)->name();
  return best.empty() ? " Fields of " + d->name() + ": " + fields + "."
                      : " Did you mean \"" + best + "\"?";
}

class Collector : public pb::io::ErrorCollector {
 public:
  explicit Collector(std::string file) : file_(std::move(file)) {}
  void AddError(int line, int column, const std::string& message) override {
    std::string text = message;
    static const std::regex unknown(R"(Message type \"([\w.]+)\" has no field named \"(\w+)\")");
    std::smatch m;
    if (std::regex_search(message, m, unknown)) {
      const auto* d = pb::DescriptorPool::generated_pool()->FindMessageTypeByName(m[1]);
      text = "unknown field \"" + m[2].str() + "\" in " + m[1].str() + "." +
             suggestion(d, m[2].str());
    }
    errors_.push_back(file_ + ":" + std::to_string(line + 1) + ":" + std::to_string(column + 1) +
                      ": " + text);
  }
  void AddWarning(int, int, const std::string&) override {}
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  std::string file_;
  std::vector<std::string> errors_;
};

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

struct PathToken {
  std::string name;
  int index = -1;
};

std::vector<PathToken> split_path(const std::string& path, const std::string& context) {
  std::vector<PathToken> tokens;
  std::stringstream ss(path);
  std::string part;
  static const std::regex token_re(R"(^([A-Za-z_][A-Za-z0-9_]*)(\[([0-9]+)\])?$)");
  while (std::getline(ss, part, '.')) {
    std::smatch m;
    if (!std::regex_match(part, m, token_re))
      throw Error(context + ": bad field path component \"" + part + "\"");
    tokens.push_back({m[1].str(), m[3].matched ? std::stoi(m[3].str()) : -1});
  }
  if (tokens.empty()) throw Error(context + ": empty field path");
  return tokens;
}

}  // namespace

void parse_text_file(const std::string& path, pb::Message& message,
                     pb::TextFormat::ParseInfoTree* tree) {
  const std::string text = read_file(path);
  Collector collector(path);
  pb::TextFormat::Parser parser;
  parser.RecordErrorsTo(&collector);
  parser.WriteLocationsTo(tree);
  parser.AllowFieldNumber(false);
  if (!parser.ParseFromString(text, &message) || !collector.errors().empty()) {
    throw Error(collector.errors().empty() ? path + ": cannot parse"
                                           : join_lines(collector.errors()));
  }
}

void apply_override(pb::Message& root, const std::string& assignment) {
  const std::string context = "--set " + assignment;
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) throw Error(context + ": expected field.path=value");
  const std::string path = assignment.substr(0, eq);
  std::string value = assignment.substr(eq + 1);
  const auto tokens = split_path(path, context);
  pb::Message* msg = &root;
  for (std::size_t k = 0; k < tokens.size(); ++k) {
    const auto* d = msg->GetDescriptor();
    const auto* field = d->FindFieldByName(tokens[k].name);
    if (!field)
      throw Error(context + ": unknown field \"" + tokens[k].name + "\" in " + d->full_name() +
                  "." + suggestion(d, tokens[k].name));
    const auto* refl = msg->GetReflection();
    const bool last = k + 1 == tokens.size();
    if (field->is_repeated() != (tokens[k].index >= 0))
      throw Error(context + ": field \"" + field->name() +
                  (field->is_repeated() ? "\" is repeated: give an index, e.g. " + field->name() + "[0]"
                                        : "\" is not repeated: no index allowed"));
    if (!last) {
      if (field->cpp_type() != pb::FieldDescriptor::CPPTYPE_MESSAGE)
        throw Error(context + ": \"" + field->name() + "\" is not a message");
      if (field->is_repeated()) {
        const int size = refl->FieldSize(*msg, field);
        if (tokens[k].index > size)
          throw Error(context + ": index " + std::to_string(tokens[k].index) + " out of range (" +
                      field->name() + " has " + std::to_string(size) + " entries)");
        msg = tokens[k].index == size ? refl->AddMessage(msg, field)
                                      : refl->MutableRepeatedMessage(msg, field, tokens[k].index);
      } else {
        msg = refl->MutableMessage(msg, field);
      }
      continue;
    }
    if (field->cpp_type() == pb::FieldDescriptor::CPPTYPE_STRING && !value.empty() &&
        value.front() != '"')
      value = "\"" + value + "\"";
    const int size = field->is_repeated() ? refl->FieldSize(*msg, field) : 0;
    if (field->is_repeated() && tokens[k].index > size)
      throw Error(context + ": index " + std::to_string(tokens[k].index) + " out of range (" + field->name() +
                  " has " + std::to_string(size) + " entries; the next one is [" + std::to_string(size) + "])");
    // A repeated field gets the value appended ...
    if (!pb::TextFormat::ParseFieldValueFromString(value, field, msg))
      throw Error(context + ": \"" + value + "\" is not a valid " + field->type_name() +
                  " for " + field->full_name());
    // ... and moved to its index when it replaces an entry.
    if (field->is_repeated() && tokens[k].index < size) {
      refl->SwapElements(msg, field, tokens[k].index, size);
      refl->RemoveLast(msg, field);
    }
  }
}

FieldLocator::FieldLocator(const pb::Descriptor* descriptor, std::string path,
                           std::vector<Source> sources,
                           const std::map<std::string, std::string>* overrides)
    : descriptor_(descriptor), path_(std::move(path)), sources_(std::move(sources)),
      overrides_(overrides) {}

std::string FieldLocator::field_path(const std::string& field, int index) const {
  std::string p = path_.empty() ? field : path_ + "." + field;
  if (index >= 0) p += "[" + std::to_string(index) + "]";
  return p;
}

std::string FieldLocator::where(const std::string& field, int index) const {
  const std::string p = field_path(field, index);
  if (overrides_) {
    const auto it = overrides_->find(p);
    if (it != overrides_->end()) return "--set " + p + "=" + it->second;
  }
  const auto* fd = descriptor_ ? descriptor_->FindFieldByName(field) : nullptr;
  for (const auto& s : sources_) {
    if (!fd || !s.tree) continue;
    const auto loc = s.tree->GetLocation(fd, fd->is_repeated() ? std::max(index, 0) : -1);
    if (loc.line >= 0)
      return s.file + ":" + std::to_string(loc.line + 1) + ":" + std::to_string(loc.column + 1) +
             ": " + p;
  }
  const std::string file = sources_.empty() ? std::string("scene") : sources_.front().file;
  return file + ": " + p + " (not set in the file)";
}

FieldLocator FieldLocator::child(const std::string& field, int index) const {
  const auto* fd = descriptor_ ? descriptor_->FindFieldByName(field) : nullptr;
  std::vector<Source> nested;
  for (const auto& s : sources_) {
    const pb::TextFormat::ParseInfoTree* t = nullptr;
    if (fd && s.tree) t = s.tree->GetTreeForNested(fd, fd->is_repeated() ? std::max(index, 0) : -1);
    nested.push_back({s.file, t});
  }
  const auto* child_descriptor = fd ? fd->message_type() : nullptr;
  return FieldLocator(child_descriptor, field_path(field, index), std::move(nested), overrides_);
}

void ValidationReport::fail(const std::string& where, const std::string& message) {
  problems_.push_back(where + ": " + message);
}

void ValidationReport::throw_if_failed() const {
  if (!problems_.empty()) throw Error(join_lines(problems_));
}

template <class Msg>
FieldLocator Loaded<Msg>::locator() const {
  return FieldLocator(Msg::descriptor(), "", {{file, trees.empty() ? nullptr : trees[0].get()}},
                      &overrides);
}

namespace {
// Walks the locator down a path, picking up extra sources (material files).
template <class L>
FieldLocator walk(const L& loaded, const std::string& path) {
  FieldLocator loc = loaded.locator();
  if (path.empty()) return loc;
  for (const auto& t : split_path(path, "locator")) loc = loc.child(t.name, t.index);
  return loc;
}
}  // namespace

template <class Msg>
FieldLocator Loaded<Msg>::locator_at(const pb::Descriptor* d, const std::string& path) const {
  FieldLocator base = walk(*this, path);
  const auto it = extra_sources.find(path);
  if (it == extra_sources.end()) return base;
  // Fields set in the scene (or on the command line) take precedence over the
  // referenced file, so they are searched first.
  auto sources = base.sources();
  sources.insert(sources.end(), it->second.begin(), it->second.end());
  return FieldLocator(d, path, sources, &overrides);
}

template struct Loaded<scene::Scene>;
template struct Loaded<scene::Study>;

void fill_schema_defaults(pb::Message& message) {
  const pb::Descriptor* d = message.GetDescriptor();
  const pb::Reflection* r = message.GetReflection();
  for (int i = 0; i < d->field_count(); ++i) {
    const pb::FieldDescriptor* f = d->field(i);
    if (f->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
      // Only the sections the scene has: a default never creates a section.
      if (f->is_repeated()) {
        for (int k = 0; k < r->FieldSize(message, f); ++k) fill_schema_defaults(*r->MutableRepeatedMessage(&message, f, k));
      } else if (r->HasField(message, f)) {
        fill_schema_defaults(*r->MutableMessage(&message, f));
      }
      continue;
    }
    if (!f->options().HasExtension(scene::default_value)) continue;
    if (f->cpp_type() != pb::FieldDescriptor::CPPTYPE_DOUBLE || f->is_repeated())
      throw Error("configs/schema/scene.proto: " + f->full_name() + ": a default_value needs a single double field");
    if (r->GetDouble(message, f) == 0.0) r->SetDouble(&message, f, f->options().GetExtension(scene::default_value));
  }
}

std::unique_ptr<LoadedScene> load_scene(const std::string& path,
                                        const std::vector<std::string>& overrides) {
  auto loaded = std::make_unique<LoadedScene>();
  loaded->file = path;
  loaded->trees.push_back(std::make_unique<pb::TextFormat::ParseInfoTree>());
  parse_text_file(path, loaded->message, loaded->trees.back().get());
  for (const auto& o : overrides) {
    apply_override(loaded->message, o);
    const auto eq = o.find('=');
    loaded->overrides[o.substr(0, eq)] = o.substr(eq + 1);
  }
  // A coupled scene's terrain line fills the blocks without a material of their own.
  auto* sph = loaded->message.has_sph() ? loaded->message.mutable_sph() : nullptr;
  const std::string& terrain = loaded->message.coupling().terrain();
  if (sph && !terrain.empty() && terrain != "rigid_road")
    for (auto& block : *sph->mutable_blocks())
      if (!block.has_material()) block.mutable_material()->set_material_file(terrain);
  // Resolve material files: the file gives the base, fields set inline win.
  // (mutable_sph() would create an empty terrain in a tyre-only scene.)
  for (int b = 0; sph && b < sph->blocks_size(); ++b) {
    auto* material = sph->mutable_blocks(b)->mutable_material();
    if (material->material_file().empty()) continue;
    const std::string& ref = material->material_file();
    const std::string file = ref.front() == '/' ? ref : folder_of(path) + "/" + ref;
    scene::Material from_file;
    loaded->trees.push_back(std::make_unique<pb::TextFormat::ParseInfoTree>());
    parse_text_file(file, from_file, loaded->trees.back().get());
    if (!from_file.material_file().empty())
      throw Error(file + ": a material file may not reference another material file");
    if (from_file.kind_case() == scene::Material::KIND_NOT_SET)
      throw Error(file + ": the material file defines neither snow nor water");
    if (material->kind_case() != scene::Material::KIND_NOT_SET &&
        material->kind_case() != from_file.kind_case())
      throw Error(path + ": sph.blocks[" + std::to_string(b) +
                  "].material: inline material kind differs from " + file);
    scene::Material merged = from_file;
    merged.MergeFrom(*material);
    *material = merged;
    const std::string material_path = "sph.blocks[" + std::to_string(b) + "].material";
    loaded->extra_sources[material_path] = {{file, loaded->trees.back().get()}};
  }
  fill_schema_defaults(loaded->message);
  return loaded;
}

std::unique_ptr<LoadedStudy> load_study(const std::string& path) {
  auto loaded = std::make_unique<LoadedStudy>();
  loaded->file = path;
  loaded->trees.push_back(std::make_unique<pb::TextFormat::ParseInfoTree>());
  parse_text_file(path, loaded->message, loaded->trees.back().get());
  return loaded;
}

bool has_fe_body(const scene::Scene& scene) { return scene.has_tyre() || scene.has_tread_block(); }

double planned_end_time_s(const scene::Scene& scene) {
  if (scene.has_tread_block()) {
    const auto& b = scene.tread_block();
    // tyre_fe::SlideSpec: the load ramped in and held, then the slide.
    if (b.load_n() > 0) return b.push_ramp_time_s() + b.hold_s() + b.slide_s();
    // tyre_fe::PushPath: down by the gap and the depth at the speed, ramped in and out, then held.
    const double v = b.push_speed_m_per_s();
    return (v > 0 ? (b.initial_gap_m() + b.push_depth_m()) / v : 0.0) + b.push_ramp_time_s() + b.hold_s();
  }
  const auto& st = scene.tyre().stages();
  return st.transfer_check_s() + st.loading_s() + st.rolling_s();
}

}  // namespace cosim

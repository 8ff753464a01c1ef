#pragma once
// Loading scene files (protobuf text format) with positions kept for every
// field, so that validation errors name file:line:column and the field path.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include "scene.pb.h"

namespace cosim {

// Where the fields of one message came from: the text files that set them
// (checked in order) and the command-line overrides.
class FieldLocator {
 public:
  struct Source {
    std::string file;
    const google::protobuf::TextFormat::ParseInfoTree* tree;
  };
  FieldLocator(const google::protobuf::Descriptor* descriptor, std::string path,
               std::vector<Source> sources, const std::map<std::string, std::string>* overrides);

  // "file:line:col: path.field" (or "--set path.field=value").
  std::string where(const std::string& field, int index = -1) const;
  FieldLocator child(const std::string& field, int index = -1) const;
  const std::string& path() const { return path_; }
  const std::vector<Source>& sources() const { return sources_; }

 private:
  std::string field_path(const std::string& field, int index) const;
  const google::protobuf::Descriptor* descriptor_;
  std::string path_;
  std::vector<Source> sources_;
  const std::map<std::string, std::string>* overrides_;
};

// Collects every problem found in a scene, then throws one cosim::Error.
class ValidationReport {
 public:
  void fail(const std::string& where, const std::string& message);
  bool ok() const { return problems_.empty(); }
  void throw_if_failed() const;
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// A parsed scene (or study) with the parse trees behind its locator.
template <class Msg>
struct Loaded {
  Msg message;
  std::string file;
  std::vector<std::unique_ptr<google::protobuf::TextFormat::ParseInfoTree>> trees;
  std::map<std::string, std::vector<FieldLocator::Source>> extra_sources;  // by path
  std::map<std::string, std::string> overrides;                            // path -> value
  FieldLocator locator() const;
  FieldLocator locator_at(const google::protobuf::Descriptor* d, const std::string& path) const;
};

using LoadedScene = Loaded<scene::Scene>;
using LoadedStudy = Loaded<scene::Study>;

// Parses a scene file, applies "field.path=value" overrides, and resolves
// material_file references (relative to the scene's folder). Throws
// cosim::Error naming file:line:column for syntax errors, unknown fields and
// wrong types.
std::unique_ptr<LoadedScene> load_scene(const std::string& path,
                                        const std::vector<std::string>& overrides = {});
std::unique_ptr<LoadedStudy> load_study(const std::string& path);

// Gives every numeric field that the schema declares a `default_value` for
// (configs/schema/scene.proto) and that is 0 (left out) its default, in every
// section present; load_scene() does it after the overrides.
void fill_schema_defaults(google::protobuf::Message& message);

// Parses text into `message`; throws cosim::Error with file:line:col.
void parse_text_file(const std::string& path, google::protobuf::Message& message,
                     google::protobuf::TextFormat::ParseInfoTree* tree);

// Sets one field given "a.b[2].c=value" (as the command line does).
void apply_override(google::protobuf::Message& root, const std::string& assignment);

// The FE body of a scene: a tyre or a tread block (tyre_fe runs either).
bool has_fe_body(const scene::Scene& scene);
// When the FE body's stages end [s] (the run's end in a coupled scene): a tyre's
// transfer check, loading and rolling; a tread block's push and hold.
double planned_end_time_s(const scene::Scene& scene);

// A text input (scene, material, study, a run's summary.json); throws
// cosim::Error naming it if it cannot be opened, is not a regular file or is
// larger than 16 MiB.
std::string read_file(const std::string& path);
std::string folder_of(const std::string& path);

}  // namespace cosim

// The table of the wire's fields (cosim/wire_fields.hpp), from which the
// neutral topic structs, both vendors' conversions and the solvers' exchange
// types are expanded, against idl/cosim_topics.idl, the schema both vendors'
// generators compile: the same structs in the same order, and in each the same
// fields (names, types, order). A field added to one and not the other fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cosim/wire_fields.hpp"
#include "test_paths.hpp"

namespace {

struct Field {
  std::string type;  // as the IDL spells it
  std::string name;
};
struct Struct {
  std::string name;
  std::vector<Field> fields;
};

// The IDL spelling of a type of the table.
std::string idl_type(const std::string& cpp) {
  const std::string seq = "std::vector<";
  if (cpp.rfind(seq, 0) == 0 && cpp.back() == '>')
    return "sequence<" + idl_type(cpp.substr(seq.size(), cpp.size() - seq.size() - 1)) + ">";
  static const std::map<std::string, std::string> kNames = {
      {"std::uint32_t", "unsigned long"}, {"std::uint64_t", "unsigned long long"}, {"double", "double"},
      {"std::string", "string"},          {"FacetTag", "FacetTag"},                  {"ControlKind", "ControlKind"},
      {"Role", "Role"},                   {"SampleHeader", "SampleHeader"}};
  const auto it = kNames.find(cpp);
  return it == kNames.end() ? "(no IDL type for " + cpp + ")" : it->second;
}

// The table, every topic led by its header (the IDL's rule; the table lists
// the fields after it).
std::vector<Struct> table_structs() {
  std::vector<Struct> out;
#define COSIM_TABLE_FIELD(type, name, init) out.back().fields.push_back({idl_type(#type), #name});
#define COSIM_TABLE_STRUCT(T)                                                    \
  out.push_back({#T, {}});                                                       \
  if (out.back().name != "SampleHeader") out.back().fields.push_back({"SampleHeader", "header"}); \
  COSIM_WIRE_FIELDS_##T(COSIM_TABLE_FIELD)
  COSIM_WIRE_STRUCTS(COSIM_TABLE_STRUCT)
#undef COSIM_TABLE_STRUCT
#undef COSIM_TABLE_FIELD
  return out;
}

std::string without_comments(const std::string& idl) {
  std::string out;
  for (std::size_t i = 0; i < idl.size(); ++i) {
    if (idl.compare(i, 2, "//") == 0) {
      i = idl.find('\n', i);
      if (i == std::string::npos) break;
    } else if (idl.compare(i, 2, "/*") == 0) {
      i = idl.find("*/", i);
      if (i == std::string::npos) break;
      ++i;
      continue;
    }
    out += idl[i];
  }
  return out;
}

// Each `struct Name { type name; ... };` of an IDL text, in order. Types of
// more than one word ("unsigned long long", "sequence<unsigned long>") are
// kept with single spaces.
std::vector<Struct> idl_structs(const std::string& idl_text) {
  const std::string idl = without_comments(idl_text);
  std::vector<Struct> out;
  for (std::size_t at = idl.find("struct "); at != std::string::npos; at = idl.find("struct ", at + 1)) {
    if (at > 0 && (std::isalnum(static_cast<unsigned char>(idl[at - 1])) || idl[at - 1] == '_')) continue;
    const std::size_t open = idl.find('{', at), close = idl.find('}', open);
    std::istringstream head(idl.substr(at + 7, open - at - 7));
    Struct s;
    head >> s.name;
    std::istringstream body(idl.substr(open + 1, close - open - 1));
    std::string member;
    while (std::getline(body, member, ';')) {
      std::istringstream words(member);
      std::vector<std::string> w;
      for (std::string word; words >> word;) w.push_back(word);
      if (w.empty()) continue;
      Field f{"", w.back()};
      for (std::size_t k = 0; k + 1 < w.size(); ++k) f.type += (k ? " " : "") + w[k];
      s.fields.push_back(f);
    }
    out.push_back(s);
  }
  return out;
}

std::string read_idl() {
  const std::string path = test_support::source_dir() + "/idl/cosim_topics.idl";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Field-by-field differences, one line each (empty: none).
std::vector<std::string> differences(const std::vector<Struct>& idl, const std::vector<Struct>& table) {
  std::vector<std::string> out;
  for (std::size_t s = 0; s < std::max(idl.size(), table.size()); ++s) {
    if (s >= idl.size() || s >= table.size() || idl[s].name != table[s].name) {
      out.push_back("struct " + std::to_string(s) + ": IDL " + (s < idl.size() ? idl[s].name : "(none)") +
                    ", table " + (s < table.size() ? table[s].name : "(none)"));
      continue;
    }
    const auto& a = idl[s].fields;
    const auto& b = table[s].fields;
    for (std::size_t f = 0; f < std::max(a.size(), b.size()); ++f) {
      const std::string in_idl = f < a.size() ? a[f].type + " " + a[f].name : "(none)";
      const std::string in_table = f < b.size() ? b[f].type + " " + b[f].name : "(none)";
      if (in_idl != in_table)
        out.push_back(idl[s].name + " field " + std::to_string(f) + ": IDL " + in_idl + ", table " + in_table);
    }
  }
  return out;
}

TEST(WireFields, TheTableIsTheIdlFieldByField) {
  const std::vector<std::string> d = differences(idl_structs(read_idl()), table_structs());
  std::string all;
  for (const auto& line : d) all += line + "\n";
  EXPECT_TRUE(d.empty()) << "idl/cosim_topics.idl and cosim/wire_fields.hpp differ:\n" << all;
}

TEST(WireFields, TheReaderSeesEveryKindOfField) {
  const auto s = idl_structs(
      "module m { // a comment with struct in it\n"
      "  /* struct Hidden { double no; }; */\n"
      "  @final struct Sample { SampleHeader header; sequence<unsigned long> ids;\n"
      "    unsigned long long count;  // trailing\n"
      "    string reason; };\n"
      "};\n");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].name, "Sample");
  ASSERT_EQ(s[0].fields.size(), 4u);
  EXPECT_EQ(s[0].fields[1].type, "sequence<unsigned long>");
  EXPECT_EQ(s[0].fields[1].name, "ids");
  EXPECT_EQ(s[0].fields[2].type, "unsigned long long");
  EXPECT_EQ(s[0].fields[3].type, "string");
}

TEST(WireFields, ADriftIsNamedByStructAndField) {
  std::vector<Struct> idl = table_structs(), table = table_structs();
  ASSERT_TRUE(differences(idl, table).empty());
  idl[3].fields[2].name = "renamed_N";  // a field renamed in the IDL only
  table[4].fields.push_back({"double", "added_N"});  // a field added to the table only
  const auto d = differences(idl, table);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NE(d[0].find(idl[3].name + " field 2: IDL "), std::string::npos) << d[0];
  EXPECT_NE(d[1].find("IDL (none), table double added_N"), std::string::npos) << d[1];
  EXPECT_EQ(idl_type("std::vector<std::uint32_t>"), "sequence<unsigned long>");
  EXPECT_EQ(idl_type("float"), "(no IDL type for float)");
}

}  // namespace

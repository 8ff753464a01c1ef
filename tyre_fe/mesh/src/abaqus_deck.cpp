// Minimal Abaqus input-deck reader: *NODE, *ELEMENT (4-node axisymmetric types),
// *ELSET, *NSET and *SURFACE; every other keyword block is skipped.
#include "abaqus_deck.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

#include "cosim/error.hpp"

namespace tyre_fe::detail {
namespace {

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(trim(item));
  return out;
}

struct Keyword {
  std::string name;                           // upper case, e.g. "ELEMENT"
  std::map<std::string, std::string> params;  // upper-case keys and values; flags map to ""
};

Keyword parse_keyword(const std::string& line) {
  const auto parts = split_commas(line.substr(1));
  Keyword k;
  k.name = upper(parts.empty() ? std::string() : parts[0]);
  for (size_t i = 1; i < parts.size(); ++i) {
    if (parts[i].empty()) continue;
    const size_t eq = parts[i].find('=');
    std::string key = upper(trim(parts[i].substr(0, eq)));
    std::string value = eq == std::string::npos ? std::string() : trim(parts[i].substr(eq + 1));
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
    k.params[key] = upper(value);
  }
  return k;
}

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {}

  AbaqusDeck read() {
    std::ifstream in(path_);
    if (!in) throw cosim::Error("cannot open Abaqus input deck '" + path_ + "'");
    std::string raw;
    while (std::getline(in, raw)) {
      ++line_;
      const std::string text = trim(raw);
      if (text.empty() || text.compare(0, 2, "**") == 0) continue;
      if (text[0] == '*') {
        finish_element();
        begin(parse_keyword(text));
      } else {
        data(text);
      }
    }
    finish_element();
    for (auto* sets : {&deck_.elsets, &deck_.nsets})
      for (auto& [name, members] : *sets) {
        std::set<int> seen;
        std::vector<int> unique;
        for (int m : members)
          if (seen.insert(m).second) unique.push_back(m);
        members.swap(unique);
      }
    return std::move(deck_);
  }

 private:
  enum class Block { none, node, element, elset, nset, surface, node_surface };

  cosim::Error error(const std::string& what) const {
    return cosim::Error(path_ + ":" + std::to_string(line_) + ": " + what);
  }

  int to_int(const std::string& token, const char* field) const {
    try {
      size_t used = 0;
      const int v = std::stoi(token, &used);
      if (used == token.size()) return v;
    } catch (const std::exception&) {
    }
    throw error(std::string("bad ") + field + " '" + token + "'");
  }

  double to_double(const std::string& token, const char* field) const {
    try {
      size_t used = 0;
      const double v = std::stod(token, &used);
      if (used == token.size()) return v;
    } catch (const std::exception&) {
    }
    throw error(std::string("bad ") + field + " '" + token + "'");
  }

  static bool is_number(const std::string& token) {
    return !token.empty() && (std::isdigit(static_cast<unsigned char>(token[0])) || token[0] == '-' || token[0] == '+');
  }

  void begin(const Keyword& k) {
    block_ = Block::none;
    set_name_.clear();
    generate_ = k.params.count("GENERATE") > 0;
    if (k.name == "NODE") {
      block_ = Block::node;
      if (k.params.count("NSET")) set_name_ = k.params.at("NSET");
    } else if (k.name == "ELEMENT") {
      const std::string type = k.params.count("TYPE") ? k.params.at("TYPE") : std::string();
      static const std::set<std::string> kTypes{"CAX4",  "CAX4R",  "CAX4H",  "CAX4RH",
                                                "CGAX4", "CGAX4R", "CGAX4H", "CGAX4RH"};
      if (!kTypes.count(type))
        throw error("element type '" + type + "' not supported (CAX4, CAX4R, CGAX4, CGAX4R and their H variants)");
      block_ = Block::element;
      if (k.params.count("ELSET")) set_name_ = k.params.at("ELSET");
    } else if (k.name == "ELSET" || k.name == "NSET") {
      const char* key = k.name == "ELSET" ? "ELSET" : "NSET";
      if (!k.params.count(key) || k.params.at(key).empty()) throw error(std::string("*") + k.name + " without " + key + "=");
      block_ = k.name == "ELSET" ? Block::elset : Block::nset;
      set_name_ = k.params.at(key);
    } else if (k.name == "SURFACE") {
      if (!k.params.count("NAME")) throw error("*SURFACE without NAME=");
      set_name_ = k.params.at("NAME");
      const std::string type = k.params.count("TYPE") ? k.params.at("TYPE") : "ELEMENT";
      if (type == "ELEMENT") block_ = Block::surface;
      else if (type == "NODE") block_ = Block::node_surface;
      else throw error("*SURFACE TYPE=" + type + " not supported (ELEMENT or NODE)");
      deck_.surfaces[set_name_];
    } else if (k.name == "INCLUDE") {
      throw error("*INCLUDE not supported: merge the included file into the deck");
    }
  }

  // Members of a set data line: ids, names of earlier sets, or a GENERATE triple.
  void add_members(const std::vector<std::string>& tokens, std::map<std::string, std::vector<int>>& sets) {
    auto& members = sets[set_name_];
    if (generate_) {
      if (tokens.size() < 2 || tokens.size() > 3) throw error("GENERATE expects first, last [, step]");
      const int first = to_int(tokens[0], "first id"), last = to_int(tokens[1], "last id");
      const int step = tokens.size() == 3 ? to_int(tokens[2], "step") : 1;
      if (step <= 0 || last < first) throw error("bad GENERATE range");
      for (int id = first; id <= last; id += step) members.push_back(id);
      return;
    }
    for (const auto& t : tokens) {
      if (is_number(t)) {
        members.push_back(to_int(t, "id"));
      } else {
        const auto it = sets.find(upper(t));
        if (it == sets.end()) throw error("unknown set '" + t + "'");
        const std::vector<int> copy = it->second;
        members.insert(members.end(), copy.begin(), copy.end());
      }
    }
  }

  void data(const std::string& text) {
    std::vector<std::string> tokens = split_commas(text);
    const bool continued = !text.empty() && text.back() == ',';
    tokens.erase(std::remove(tokens.begin(), tokens.end(), std::string()), tokens.end());
    switch (block_) {
      case Block::none: return;
      case Block::node: {
        if (tokens.size() < 3) throw error("*NODE line needs id, r, y");
        const int id = to_int(tokens[0], "node id");
        if (deck_.nodes.count(id)) throw error("node " + tokens[0] + " defined twice");
        deck_.nodes[id] = AbaqusNode{{to_double(tokens[1], "r coordinate"), to_double(tokens[2], "y coordinate")}, line_};
        deck_.node_order.push_back(id);
        if (!set_name_.empty()) deck_.nsets[set_name_].push_back(id);
        return;
      }
      case Block::element: {
        if (pending_.empty()) pending_line_ = line_;
        pending_.insert(pending_.end(), tokens.begin(), tokens.end());
        if (pending_.size() > 5) throw error("too many nodes for a 4-node element");
        if (pending_.size() == 5 || !continued) finish_element();
        return;
      }
      case Block::elset: add_members(tokens, deck_.elsets); return;
      case Block::nset: add_members(tokens, deck_.nsets); return;
      case Block::node_surface: add_members(tokens, deck_.nsets); return;
      case Block::surface: {
        if (tokens.size() != 2) throw error("*SURFACE line needs element (or ELSET), face label S1..S4");
        const std::string label = upper(tokens[1]);
        if (label.size() != 2 || label[0] != 'S' || label[1] < '1' || label[1] > '4')
          throw error("bad face label '" + tokens[1] + "' (S1..S4)");
        std::vector<int> ids;
        if (is_number(tokens[0])) {
          ids.push_back(to_int(tokens[0], "element id"));
        } else {
          const auto it = deck_.elsets.find(upper(tokens[0]));
          if (it == deck_.elsets.end()) throw error("unknown element set '" + tokens[0] + "'");
          ids = it->second;
        }
        for (int id : ids) deck_.surfaces[set_name_].faces.push_back({id, label[1] - '1', line_});
        return;
      }
    }
  }

  void finish_element() {
    if (pending_.empty()) return;
    const int saved = line_;
    line_ = pending_line_;
    if (pending_.size() != 5) throw error("element needs an id and 4 nodes");
    AbaqusElement e;
    e.id = to_int(pending_[0], "element id");
    for (int k = 0; k < 4; ++k) e.nodes[k] = to_int(pending_[k + 1], "node id");
    e.line = pending_line_;
    if (!element_ids_.insert(e.id).second) throw error("element " + pending_[0] + " defined twice");
    deck_.elements.push_back(e);
    if (!set_name_.empty()) deck_.elsets[set_name_].push_back(e.id);
    pending_.clear();
    line_ = saved;
  }

  std::string path_;
  int line_ = 0;
  Block block_ = Block::none;
  std::string set_name_;
  bool generate_ = false;
  std::vector<std::string> pending_;
  int pending_line_ = 0;
  std::set<int> element_ids_;
  AbaqusDeck deck_;
};

}  // namespace

AbaqusDeck read_abaqus_deck(const std::string& path) { return Reader(path).read(); }

}  // namespace tyre_fe::detail

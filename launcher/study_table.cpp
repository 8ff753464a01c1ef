#include "study_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "cosim/csv.hpp"
#include "cosim/error.hpp"
#include "cosim/result_references.hpp"

namespace cosim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end && *end == '\0';
}

double single_number(const StudyRow& row, const std::string& name) {
  if (auto c = row.computed.find(name); c != row.computed.end()) return c->second;
  if (auto p = row.parameters.find(name); p != row.parameters.end()) {
    double v;
    return parse_number(p->second, v) ? v : kNaN;
  }
  if (name == "wall_time_s") {
    const auto& w = row.summary.value("wall_time_s", nlohmann::json());
    return w.is_number() ? w.get<double>() : kNaN;
  }
  if (!row.summary.contains("results")) return kNaN;
  const nlohmann::json* v = result_at(row.summary["results"], name);
  return v && v->is_number() ? v->get<double>() : kNaN;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= s.size(); ++i)
    if (i == s.size() || s[i] == sep) parts.push_back(trim(s.substr(start, i - start))), start = i + 1;
  return parts;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

// The group a row belongs to when `column` varies: its pass and every other parameter.
std::string group_key(const StudyRow& row, const std::string& column) {
  std::string key = row.pass;
  for (const auto& [name, value] : row.parameters)
    if (name != column) key += "|" + name + "=" + value;
  return key;
}

// "soft/0" style name of a group for the report: the parameters but the varying one.
std::string group_name(const StudyRow& row, const std::string& column) {
  std::string name;
  for (const auto& [k, value] : row.parameters)
    if (k != column) name += (name.empty() ? "" : "/") + value;
  return name.empty() ? "all" : name;
}

}  // namespace

std::string field_column(const std::string& field) { return field.substr(0, field.find('=')); }

std::string field_path(const std::string& field) {
  const auto eq = field.find('=');
  return eq == std::string::npos ? field : field.substr(eq + 1);
}

double row_number(const StudyRow& row, const std::string& quantity) {
  // "A-B" / "A+B": split at the last operator that is not part of a number's exponent.
  for (std::size_t i = quantity.size(); i-- > 1;) {
    const char c = quantity[i];
    if ((c == '-' || c == '+') && quantity[i - 1] != 'e' && quantity[i - 1] != 'E') {
      const double a = single_number(row, trim(quantity.substr(0, i)));
      const double b = single_number(row, trim(quantity.substr(i + 1)));
      return c == '-' ? a - b : a + b;
    }
  }
  return single_number(row, quantity);
}

std::string row_text(const StudyRow& row, const std::string& column) {
  if (auto p = row.parameters.find(column); p != row.parameters.end()) return p->second;
  const double v = row_number(row, column);
  return std::isnan(v) ? "" : number_text(v);
}

bool row_matches(const StudyRow& row, const std::string& where) {
  for (const auto& condition : split(where, ';')) {
    if (condition.empty()) continue;
    static const char* ops[] = {"!=", ">=", "<=", "=", ">", "<"};  // two-character ones first
    std::size_t at = std::string::npos;
    std::string op;
    for (const char* o : ops) {
      const auto p = condition.find(o);
      if (p != std::string::npos && p > 0) {
        at = p, op = o;
        break;
      }
    }
    if (at == std::string::npos) throw Error("row filter '" + condition + "': expected COLUMN OP VALUE (= != > >= < <=)");
    const std::string column = trim(condition.substr(0, at)), value = trim(condition.substr(at + op.size()));
    if (op == "=" || op == "!=") {
      if ((row_text(row, column) == value) != (op == "=")) return false;
      continue;
    }
    double limit;
    if (!parse_number(value, limit)) throw Error("row filter '" + condition + "': '" + value + "' is not a number");
    const double v = row_number(row, column);
    const bool ok = op == ">" ? v > limit : op == ">=" ? v >= limit : op == "<" ? v < limit : v <= limit;
    if (!ok) return false;  // NaN fails every comparison
  }
  return true;
}

std::vector<Ordering> read_orderings(const std::string& csv_path) {
  const CsvTable t = read_csv(csv_path);
  std::vector<Ordering> out;
  for (const auto& r : t.rows) {
    Ordering o{t.field(r, "id"),     t.field(r, "claim"), t.field(r, "source"), t.field(r, "quantity"),
               t.field(r, "kind"),   t.field(r, "column"), t.field(r, "order"), t.field(r, "where"),
               csv_path + ":" + std::to_string(r.line)};
    for (const char* required : {"id", "claim", "source", "quantity", "kind"})
      if (t.field(r, required).empty()) throw Error(t.where(r, required) + ": empty");
    const bool grouped = o.kind == "order" || o.kind == "increasing" || o.kind == "decreasing";
    if (!grouped && o.kind != "negative" && o.kind != "positive")
      throw Error(t.where(r, "kind") + ": '" + o.kind + "' is not one of order, increasing, decreasing, negative, positive");
    if (grouped && o.column.empty()) throw Error(t.where(r, "column") + ": kind " + o.kind + " needs the column that varies");
    if (o.kind == "order" && split(o.order, '>').size() < 2)
      throw Error(t.where(r, "order") + ": expected values ranked with '>', e.g. smooth>block");
    out.push_back(std::move(o));
  }
  return out;
}

OrderingOutcome evaluate_ordering(const Ordering& o, const std::vector<StudyRow>& rows) {
  OrderingOutcome result;
  std::vector<const StudyRow*> kept;
  const bool numeric_column = o.kind == "increasing" || o.kind == "decreasing";
  for (const auto& r : rows)
    if (row_matches(r, o.where) && !std::isnan(row_number(r, o.quantity)) &&
        !(numeric_column && std::isnan(row_number(r, o.column))))  // a run off the numeric axis
      kept.push_back(&r);
  std::vector<std::string> details, failures;
  auto compare = [&](bool ok, const std::string& text) {
    ++result.compared;
    if (ok) ++result.held;
    (ok ? details : failures).push_back(text);
  };
  if (o.kind == "negative" || o.kind == "positive") {
    for (const auto* r : kept) {
      const double v = row_number(*r, o.quantity);
      compare(o.kind == "negative" ? v < 0 : v > 0, r->label + " " + number(v));
    }
  } else {
    std::map<std::string, std::vector<const StudyRow*>> groups;
    for (const auto* r : kept) groups[group_key(*r, o.column)].push_back(r);
    for (auto& [key, members] : groups) {
      const std::string name = group_name(*members.front(), o.column);
      if (o.kind == "order") {
        // Adjacent pairs of the ranking that are both present in the group.
        std::vector<const StudyRow*> ranked;
        for (const auto& value : split(o.order, '>'))
          for (const auto* m : members)
            if (row_text(*m, o.column) == value) ranked.push_back(m);
        for (std::size_t i = 0; i + 1 < ranked.size(); ++i) {
          const double a = row_number(*ranked[i], o.quantity), b = row_number(*ranked[i + 1], o.quantity);
          compare(a > b, name + ": " + row_text(*ranked[i], o.column) + " " + number(a) + (a > b ? " > " : " <= ") +
                             row_text(*ranked[i + 1], o.column) + " " + number(b));
        }
      } else {
        std::sort(members.begin(), members.end(), [&](const StudyRow* a, const StudyRow* b) {
          return row_number(*a, o.column) < row_number(*b, o.column);
        });
        for (std::size_t i = 0; i + 1 < members.size(); ++i) {
          const double a = row_number(*members[i], o.quantity), b = row_number(*members[i + 1], o.quantity);
          const bool ok = o.kind == "increasing" ? b > a : b < a;
          compare(ok, name + ": " + o.column + " " + row_text(*members[i], o.column) + " -> " +
                          row_text(*members[i + 1], o.column) + ": " + number(a) + " -> " + number(b));
        }
      }
    }
  }
  if (result.compared == 0) {
    result.hold = "not run";
    result.ours = "no runs to compare";
    return result;
  }
  result.hold = result.held == result.compared ? "hold" : "fail";
  result.ours = std::to_string(result.held) + " of " + std::to_string(result.compared) + " hold";
  // The failures first (what a reader looks for), then the rest.
  for (const auto* list : {&failures, &details})
    for (const auto& d : *list) result.ours += "; " + d;
  return result;
}

void apply_f5_radius(const scene::StudyF5Radius& f, std::vector<StudyRow>& rows) {
  auto radius_of = [](const StudyRow& r) {
    const double v = row_number(r, "tyre.rolling_radius_m");
    return std::isnan(v) ? row_number(r, "rolling_radius_m") : v;
  };
  for (auto& row : rows) {
    const StudyRow* reference = nullptr;
    for (const auto& other : rows) {
      if (other.pass != row.pass) continue;
      if (!f.case_label().empty()) {
        if (other.label == f.case_label()) reference = &other;
        continue;
      }
      if (row_text(other, f.column()) != f.value()) continue;
      bool same = true;
      for (const auto& [name, value] : row.parameters)
        if (name != f.column()) same = same && other.parameters.count(name) && other.parameters.at(name) == value;
      if (same) reference = &other;
    }
    const double rrm = row_number(row, "rolling_resistance_moment_Nm");
    const double f5 = row_number(row, "rolling_resistance_force_N");
    if (!reference || std::isnan(rrm) || std::isnan(f5)) continue;
    const double r = radius_of(*reference);
    if (!(r > 0.0)) continue;
    const double f5_new = rrm / r;
    row.computed["rolling_radius_for_F5_m"] = r;
    row.computed["rolling_resistance_force_N"] = f5_new;
    row.computed["drawbar_pull_N"] = row_number(row, "drawbar_pull_N") + f5 - f5_new;
    row.computed["traction_minus_rrf_N"] = row_number(row, "traction_force_N") - f5_new;
  }
}

}  // namespace cosim

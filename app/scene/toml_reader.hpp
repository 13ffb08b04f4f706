// Reading TOML input files (scene files, study files): typed getters that name the file, line,
// column and dotted field of a bad value, and reject unknown fields. Internal to app/.
#pragma once

#include <toml++/toml.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <optional>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/scene/input_error.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {

using sim::Vec3;

inline std::string sourceOf(const toml::node& n, const std::string& fallback) {
  const auto& path = n.source().path;
  return path && !path->empty() ? *path : fallback;
}

inline const char* typeName(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}

template <class Names>
std::string join(const Names& choices) {
  std::string s;
  for (const auto& c : choices) s.append(s.empty() ? "" : ", ").append(c);
  return s;
}

// One TOML table being read: typed getters that name file, line and dotted field on error, and
// a check that every key was used (unknown fields are errors, not silently ignored). Values of
// description settings are checked by their validator in sim/scene/settings.hpp.
class Reader {
 public:
  Reader(const toml::table& t, std::string prefix, std::string file)
      : table_(t), prefix_(std::move(prefix)), file_(std::move(file)) {}

  [[noreturn]] void fail(const toml::node* n, const std::string& key, const std::string& why) const {
    const toml::node& at = n ? *n : static_cast<const toml::node&>(table_);
    throw InputError(sourceOf(at, file_), static_cast<int>(at.source().begin.line),
                     static_cast<int>(at.source().begin.column), field(key), why);
  }
  std::string field(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  const std::string& file() const { return file_; }
  const toml::table& table() const { return table_; }

  const toml::node* find(const std::string& key) {
    used_.insert(key);
    return table_.get(key);
  }
  bool has(const std::string& key) const { return table_.contains(key); }
  /// The node of `key` when present (for errors found after reading), else null.
  const toml::node* nodeOf(const std::string& key) const { return table_.get(key); }

  /// Reads setting `s` from `key` when present (or fails when `required` and missing): typed
  /// as the setting's kind, checked by its validator, stored in `desc`. True when present.
  template <class Desc>
  bool setting(const sim::Setting<Desc>& s, Desc& desc, const std::string& key, bool required = false) {
    const toml::node* n = find(key);
    if (!n) {
      if (required) fail(nullptr, key, std::string("missing (") + kindName(s) + " is required)");
      return false;
    }
    if (s.kind == sim::SettingKind::kVector) {
      const Vec3 v = checkedVec3(*n, key);
      if (const std::optional<std::string> why = sim::checkGiven(s, v)) fail(n, key, *why);
      s.set_vector(desc, v * s.si_per_unit);
      return true;
    }
    if (s.kind == sim::SettingKind::kChoice) {
      const int index = n->is_string() ? sim::choiceIndex(s, n->as_string()->get()) : -1;
      if (index < 0) fail(n, key, "expected one of " + sim::choiceList(s));
      s.set(desc, index);
      return true;
    }
    if (s.kind == sim::SettingKind::kInteger && !n->is_integer()) {
      fail(n, key, std::string("expected an integer, got ") + typeName(*n));
    }
    const double v = checkedNumber(*n, key, -HUGE_VAL, HUGE_VAL);
    if (const std::optional<std::string> why = sim::checkGiven(s, v)) fail(n, key, *why);
    sim::setGiven(s, desc, v);
    return true;
  }
  /// Fails on the first field the validator of a whole description found not legal.
  void failOn(const std::optional<sim::FieldError>& e) const {
    if (e) fail(nodeOf(e->field), e->field, e->reason);
  }

  double number(const std::string& key, double fallback, double lo = -HUGE_VAL, double hi = HUGE_VAL) {
    const toml::node* n = find(key);
    return n ? checkedNumber(*n, key, lo, hi) : fallback;
  }
  double requiredNumber(const std::string& key, double lo = -HUGE_VAL, double hi = HUGE_VAL) {
    const toml::node* n = find(key);
    if (!n) fail(nullptr, key, "missing (a number is required)");
    return checkedNumber(*n, key, lo, hi);
  }
  int integer(const std::string& key, int fallback, int lo, int hi) {
    const toml::node* n = find(key);
    if (!n) return fallback;
    if (!n->is_integer()) fail(n, key, std::string("expected an integer, got ") + typeName(*n));
    const std::int64_t v = n->as_integer()->get();
    if (v < lo || v > hi) fail(n, key, "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(v);
  }
  bool boolean(const std::string& key, bool fallback) {
    const toml::node* n = find(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(n, key, std::string("expected true or false, got ") + typeName(*n));
    return n->as_boolean()->get();
  }
  std::string string(const std::string& key, const std::string& fallback) {
    const toml::node* n = find(key);
    if (!n) return fallback;
    if (!n->is_string()) fail(n, key, std::string("expected a string, got ") + typeName(*n));
    return n->as_string()->get();
  }
  // One of `choices`; returns its index.
  template <class Names>
  int choice(const std::string& key, const Names& choices, int fallback) {
    const toml::node* n = find(key);
    if (!n) {
      if (fallback < 0) fail(nullptr, key, "missing (one of " + join(choices) + ")");
      return fallback;
    }
    if (!n->is_string()) fail(n, key, std::string("expected a string, got ") + typeName(*n));
    const std::string v = n->as_string()->get();
    for (std::size_t i = 0; i < std::size(choices); ++i) {
      if (v == choices[i]) return static_cast<int>(i);
    }
    fail(n, key, "unknown value '" + v + "' (one of " + join(choices) + ")");
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback) {
    const toml::node* n = find(key);
    return n ? checkedVec3(*n, key) : fallback;
  }
  Vec3 checkedVec3(const toml::node& n, const std::string& key) {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3) fail(&n, key, "expected an array of 3 numbers [x, y, z]");
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = checkedNumber(*a->get(i), key, -HUGE_VAL, HUGE_VAL);
    return v;
  }
  /// `orientation` (a quaternion [x, y, z, w] of finite numbers, normalised) or `rotation`
  /// (degrees [x, y, z]: about x, then y, then z, each about the axes the ones before turned);
  /// `fallback` when neither is given. Fails when both are, or on a zero quaternion.
  sim::Quat orientation(const sim::Quat& fallback) {
    constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
    if (has("orientation") && has("rotation")) fail(find("rotation"), "rotation", "give either orientation or rotation, not both");
    if (has("rotation")) {
      const Vec3 deg = vec3("rotation", Vec3::Zero());
      return Eigen::AngleAxisd(deg.x() * kDegToRad, Vec3::UnitX()) * Eigen::AngleAxisd(deg.y() * kDegToRad, Vec3::UnitY()) *
             Eigen::AngleAxisd(deg.z() * kDegToRad, Vec3::UnitZ());
    }
    const toml::node* n = find("orientation");
    if (!n) return fallback;
    const toml::array* a = n->as_array();
    const auto finite = [](const toml::node& e) { return e.is_number() && std::isfinite(e.value<double>().value_or(NAN)); };
    if (!a || a->size() != 4 || !std::all_of(a->begin(), a->end(), finite)) {
      fail(n, "orientation", "expected a quaternion [x, y, z, w] of finite numbers");
    }
    const sim::Quat q(a->get(3)->value<double>().value(), a->get(0)->value<double>().value(),
                      a->get(1)->value<double>().value(), a->get(2)->value<double>().value());
    if (q.norm() < 1e-9) fail(n, "orientation", "quaternion has zero length");
    return q.normalized();
  }
  /// A box `key = { min = [x, y, z], max = [x, y, z] }` (m), every coordinate of max above
  /// min's; nullopt when `key` is absent.
  std::optional<std::pair<Vec3, Vec3>> box(const std::string& key) {
    const toml::node* z = find(key);
    if (!z) return std::nullopt;
    const toml::table* t = z->as_table();
    if (!t) fail(z, key, std::string("expected a table { min = [x, y, z], max = [x, y, z] }, got ") + typeName(*z));
    Reader zr(*t, field(key), file());
    if (!zr.has("min") || !zr.has("max")) zr.fail(nullptr, zr.has("min") ? "max" : "min", "missing: the corners min and max (m)");
    const Vec3 lo = zr.vec3("min", Vec3::Zero()), hi = zr.vec3("max", Vec3::Zero());
    if (!(lo.array() < hi.array()).all()) zr.fail(zr.nodeOf("max"), "max", "every coordinate must exceed min's");
    zr.finish();
    return std::pair(lo, hi);
  }
  std::vector<double> numbers(const std::string& key) {
    std::vector<double> out;
    const toml::node* n = find(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a) fail(n, key, std::string("expected an array of numbers, got ") + typeName(*n));
    for (const toml::node& e : *a) out.push_back(checkedNumber(e, key, 0.0, HUGE_VAL));
    return out;
  }
  std::vector<std::pair<std::string, const toml::node*>> strings(const std::string& key) {
    std::vector<std::pair<std::string, const toml::node*>> out;
    const toml::node* n = find(key);
    if (!n) return out;
    const toml::array* a = n->as_array();
    if (!a) fail(n, key, std::string("expected an array of strings, got ") + typeName(*n));
    for (const toml::node& e : *a) {
      if (!e.is_string()) fail(&e, key, std::string("expected a string, got ") + typeName(e));
      out.emplace_back(e.as_string()->get(), &e);
    }
    return out;
  }
  // The tables of the array of tables `key` ([[key]]), each with its dotted name ("key.0");
  // fails naming `what` when `key` is not such an array, or (when `non_empty`) is empty.
  std::vector<std::pair<std::string, const toml::table*>> arrayTables(const std::string& key, const std::string& what,
                                                                      bool non_empty = false) {
    std::vector<std::pair<std::string, const toml::table*>> out;
    const toml::node* n = find(key);
    if (!n) {
      if (non_empty) fail(nullptr, key, "missing: expected a non-empty array of tables ([[" + key + "]])" + what);
      return out;
    }
    const toml::array* a = n->as_array();
    if (!a || (non_empty && a->empty())) {
      fail(n, key, std::string("expected ") + (non_empty ? "a non-empty" : "an") + " array of tables ([[" + key + "]])" +
                       what + ", got " + typeName(*n));
    }
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string name = key + "." + std::to_string(i);
      const toml::node& e = *a->get(i);
      if (!e.is_table()) fail(&e, name, std::string("expected a table, got ") + typeName(e));
      out.emplace_back(name, e.as_table());
    }
    return out;
  }
  // Sub-tables of `key`, in the order they appear in the file (overrides last).
  std::vector<std::pair<std::string, const toml::table*>> namedTables(const std::string& key) {
    std::vector<std::pair<std::string, const toml::table*>> out;
    const toml::node* n = find(key);
    if (!n) return out;
    const toml::table* t = n->as_table();
    if (!t) fail(n, key, std::string("expected a table, got ") + typeName(*n));
    for (const auto& [k, v] : *t) {
      if (!v.is_table()) fail(&v, key + "." + std::string(k.str()), std::string("expected a table, got ") + typeName(v));
      out.emplace_back(std::string(k.str()), v.as_table());
    }
    auto line = [](const toml::table* t2) {
      const auto& p = t2->source().path;
      // Nodes from --set have their own source: they sort after the file's.
      return std::pair(p && p->rfind("--set", 0) == 0 ? 1 : 0, t2->source().begin.line);
    };
    std::stable_sort(out.begin(), out.end(),
                     [&](const auto& a, const auto& b) { return line(a.second) < line(b.second); });
    return out;
  }
  // Every key of the table must have been read.
  void finish() const {
    for (const auto& [k, v] : table_) {
      if (!used_.contains(std::string(k.str()))) fail(&v, std::string(k.str()), "unknown field");
    }
  }

 private:
  template <class Desc>
  static const char* kindName(const sim::Setting<Desc>& s) {
    return s.kind == sim::SettingKind::kVector    ? "an array [x, y, z]"
           : s.kind == sim::SettingKind::kInteger ? "an integer"
           : s.kind == sim::SettingKind::kChoice  ? "a name"
                                                  : "a number";
  }
  double checkedNumber(const toml::node& n, const std::string& key, double lo, double hi) const {
    if (!n.is_number()) fail(&n, key, std::string("expected a number, got ") + typeName(n));
    const double v = n.value<double>().value_or(0.0);
    if (!std::isfinite(v)) fail(&n, key, "must be finite");
    if (v < lo || v > hi) {
      fail(&n, key, "must be in [" + sim::numberText(lo) + ", " + sim::numberText(hi) + "], got " + sim::numberText(v));
    }
    return v;
  }
  const toml::table& table_;
  std::string prefix_;
  std::string file_;
  std::set<std::string> used_;
};

}  // namespace gf::app

// --set FIELD=VALUE: a change to the parsed scene file before it is read, so every value passes
// the same checks as the file's own.
#include "app/scene/sections.hpp"

#include <charconv>
#include <cstdio>

namespace gf::app {
namespace {

// The element of array `a` that `part` (digits) names, or throws naming the field walked so far.
std::size_t arrayIndex(const toml::array& a, const std::string& part, const std::string& where,
                       const std::string& walked) {
  std::size_t i = 0;
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), i);
  if (ec != std::errc() || end != part.data() + part.size()) {
    throw InputError(where, 0, 0, walked,
                     "is an array: expected an element index, got '" + part + "'");
  }
  if (i >= a.size()) {
    throw InputError(where, 0, 0, walked,
                     "no element " + part + " (the array has " + std::to_string(a.size()) + ")");
  }
  return i;
}

// "--set a.b.c=VALUE": VALUE is read as TOML, or as a string when it is not valid TOML. A part
// of the path may be an element index of an array (`loads.0.torque`).
// `--set fingers.NAME.FIELD=...` or `bodies.NAME.FIELD=...` for a NAME the scene lacks is a typo
// unless it starts a new finger with its device or a new body with its shape: then it says so,
// naming the fingers or bodies there are.
void requireKnownOrNew(const toml::table& group, const std::vector<std::string>& parts, const std::string& where) {
  struct Kind {
    const char* group;
    const char* what;
    const char* defining;
  };
  static constexpr Kind kKinds[] = {{"fingers", "finger", "device"}, {"bodies", "body", "shape"}};
  for (const Kind& k : kKinds) {
    if (parts[0] != k.group || (parts.size() > 2 && parts[2] == k.defining)) continue;
    std::string names;
    for (const auto& [name, node] : group) names.append(names.empty() ? "" : ", ").append(name.str());
    throw InputError(where, 0, 0, parts[0] + "." + parts[1],
                     std::string("no such ") + k.what + " (the scene has: " + (names.empty() ? "none" : names) +
                         "); a new " + k.what + " starts with its " + k.defining + ", e.g. --set " + parts[0] + "." +
                         parts[1] + "." + k.defining + (parts[0] == "fingers" ? ".csv=FILE" : "=\"box\""));
  }
}

// `text` with its control characters written out (\n, \r, \xNN), for a message on one line.
std::string visible(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    }
  }
  return out;
}

// One --set is one field and one value on one line: a control character other than a tab (TOML's
// whitespace) would cut the text (a newline starts another TOML line: "8\nfingers.index.r_max =
// 0.5" set a second field unseen) or hide in a string. Refused, naming --set and the field.
void requireNoControlCharacters(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto u = static_cast<unsigned char>(text[i]);
    if ((u >= 0x20 && u != 0x7f) || u == '\t') continue;
    const std::size_t eq = text.find('=');
    const std::string field = visible(eq == std::string::npos ? text : text.substr(0, eq));
    char code[8];
    std::snprintf(code, sizeof code, "0x%02x", u);
    throw InputError("--set " + visible(text), 0, 0, field,
                     std::string("holds a control character (") + code + (u == '\n' ? ", a newline" : "") +
                         ") at byte " + std::to_string(i) +
                         ": one --set sets one field to one value on one line; give each field its own --set");
  }
}

}  // namespace

void applyOverride(toml::table& root, const std::string& text) {
  requireNoControlCharacters(text);
  const std::string where = "--set " + text;
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError(where, 0, 0, text, "expected FIELD=VALUE");
  const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
  std::vector<std::string> parts;
  for (std::size_t a = 0; a <= key.size();) {
    const std::size_t b = std::min(key.find('.', a), key.size());
    parts.push_back(key.substr(a, b - a));
    if (parts.back().empty()) throw InputError(where, 0, 0, key, "empty name in the field path");
    a = b + 1;
  }
  toml::node* at = &root;  // a table or an array
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    toml::node* n = nullptr;
    if (toml::array* a = at->as_array()) {
      n = a->get(arrayIndex(*a, parts[i], where, walked));
    } else {
      n = at->as_table()->get(parts[i]);
      if (!n && i == 1) requireKnownOrNew(*at->as_table(), parts, where);
      if (!n) n = at->as_table()->insert(parts[i], toml::table{}).first->second.as_table();
    }
    if (!n->is_table() && !n->is_array()) throw InputError(where, 0, 0, walked, "is not a table");
    at = n;
  }
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value, where);
  } catch (const toml::parse_error&) {
    std::string quoted;
    for (char c : value) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    try {
      parsed = toml::parse("v = \"" + quoted + "\"", where);
    } catch (const toml::parse_error& e) {
      throw InputError(where, 0, 0, key, std::string(e.description()));
    }
  }
  if (toml::array* a = at->as_array()) {
    const std::size_t i = arrayIndex(*a, parts.back(), where, key);
    a->replace(a->cbegin() + static_cast<std::ptrdiff_t>(i), std::move(*parsed.get("v")));
  } else {
    at->as_table()->insert_or_assign(parts.back(), std::move(*parsed.get("v")));
  }
}

}  // namespace gf::app

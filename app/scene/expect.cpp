// [expect]: what a run must show, read into app::ExpectDesc.
#include "app/scene/sections.hpp"

#include <algorithm>
#include <optional>

#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

// max_roll_ratio and its roll_window: a sphere's only (the ratio needs its radius), the window
// [from, to] with 0 <= from < to, and only with the limit it bounds.
void readRollRatio(Reader& br, const sim::BodyDesc& body, BodyExpect& b) {
  if (br.has("max_roll_ratio")) b.max_roll_ratio = br.number("max_roll_ratio", 0.0, 0.0, 1e6);
  if (b.max_roll_ratio && body.shape != sim::ShapeKind::kSphere) {
    br.fail(br.nodeOf("max_roll_ratio"), "max_roll_ratio",
            "'" + body.name + "' is not a sphere: a roll ratio needs its radius");
  }
  const toml::node* w = br.find("roll_window");
  if (!w) return;
  const std::vector<double> v = br.numbers("roll_window");
  if (v.size() != 2 || !(v[0] >= 0.0) || !(v[1] > v[0])) {
    br.fail(w, "roll_window", "expected [from, to] in seconds, 0 <= from < to");
  }
  if (!b.max_roll_ratio) br.fail(w, "roll_window", "without max_roll_ratio it checks nothing");
  b.roll_from = v[0];
  b.roll_to = v[1];
}

}  // namespace

// [expect]: invariants of the run (app/scene/expect_desc.hpp).
void readExpect(Reader& parent, SessionDesc& s) {
  const toml::node* n = parent.find("expect");
  if (!n) return;
  if (!n->is_table()) parent.fail(n, "expect", "expected a table");
  Reader r(*n->as_table(), "expect", parent.file());
  ExpectDesc& e = s.expect;
  const auto optional = [](Reader& at, const std::string& key, double lo, double hi) -> std::optional<double> {
    if (!at.has(key)) return std::nullopt;
    return at.number(key, 0.0, lo, hi);
  };
  e.finite = r.boolean("finite", true);
  e.max_speed = optional(r, "max_speed", 0.0, 1e6);
  e.max_angular_speed = optional(r, "max_angular_speed", 0.0, 1e6);
  e.energy_growth = optional(r, "energy_growth", 0.0, 1e9);
  e.max_penetration = optional(r, "max_penetration", 0.0, 1e6);
  e.no_tunnelling = r.boolean("no_tunnelling", false);
  e.min_port_energy = r.number("min_port_energy", e.min_port_energy, -1e6, 0.0);
  for (const auto& [name, t] : r.namedTables("bodies")) {
    const auto body = std::find_if(s.scene.bodies.begin(), s.scene.bodies.end(),
                                   [&wanted = name](const sim::BodyDesc& b) { return b.name == wanted; });
    if (body == s.scene.bodies.end() || body->mass <= 0.0) {
      r.fail(t, "bodies." + name, "no dynamic body called '" + name + "'");
    }
    Reader br(*t, "expect.bodies." + name, parent.file());
    BodyExpect& b = e.bodies[name];
    b.max_speed = optional(br, "max_speed", 0.0, 1e6);
    b.max_angular_speed = optional(br, "max_angular_speed", 0.0, 1e6);
    b.stays_above = optional(br, "stays_above", -1e6, 1e6);
    b.ends_above = optional(br, "ends_above", -1e6, 1e6);
    b.max_rotation_deg = optional(br, "max_rotation_deg", 0.0, 180.0);
    b.max_drift = optional(br, "max_drift", 0.0, 1e6);
    b.max_tilt_deg = optional(br, "max_tilt_deg", 0.0, 180.0);
    b.after = br.number("after", 0.0, 0.0, 1e6);
    b.rests_after = optional(br, "rests_after", 0.0, 1e6);
    b.rest_speed = br.number("rest_speed", b.rest_speed, 0.0, 1e6);
    b.rest_tilt_rate = br.number("rest_tilt_rate", b.rest_tilt_rate, 0.0, 1e6);
    readRollRatio(br, *body, b);
    br.finish();
  }
  for (const auto& [name, t] : r.namedTables("fingers")) {
    const bool known = std::any_of(s.scene.fingers.begin(), s.scene.fingers.end(),
                                   [&wanted = name](const sim::FingerDesc& f) { return f.name == wanted; });
    if (!known) r.fail(t, "fingers." + name, "no finger called '" + name + "'");
    Reader fr(*t, "expect.fingers." + name, parent.file());
    FingerExpect& f = e.fingers[name];
    if (fr.has("min_sgo")) f.min_sgo = fr.integer("min_sgo", 0, 0, sim::kMaxSgo * sim::kMaxRings);
    if (const toml::node* w = fr.find("window")) {
      const std::vector<double> v = fr.numbers("window");
      if (v.size() != 2 || !(v[1] > v[0])) fr.fail(w, "window", "expected [from, to] in seconds, from < to");
      f.from = v[0];
      f.to = v[1];
    }
    f.max_force = optional(fr, "max_force", 0.0, 1e9);
    f.max_force_change = optional(fr, "max_force_change", 0.0, 1e9);
    if (f.max_force_change && !fr.has("window")) {
      fr.fail(fr.nodeOf("max_force_change"), "max_force_change",
              "needs window = [from, to]: the change is counted from the force at `from`");
    }
    f.max_penetration = optional(fr, "max_penetration", 0.0, 1e6);
    fr.finish();
  }
  r.finish();
}

}  // namespace gf::app

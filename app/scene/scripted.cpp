// What acts during a run besides the devices: [[loads]] and scripted [[changes]] of finger settings.
#include "app/scene/sections.hpp"

#include <algorithm>

#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

// The index of the element of `items` (bodies or fingers) whose name field `key` gives, or fails
// naming the field: missing, not a string, or no such name (with the names there are).
template <class Desc>
int namedIndex(Reader& r, const std::string& key, const std::string& what, const std::vector<Desc>& items) {
  const toml::node* n = r.find(key);
  if (!n) r.fail(nullptr, key, "missing (the name of " + what + ")");
  if (!n->is_string()) r.fail(n, key, "expected the name of " + what + " (a string), got " + typeName(*n));
  const std::string name = n->as_string()->get();
  const auto named = std::find_if(items.begin(), items.end(), [&](const Desc& d) { return d.name == name; });
  if (named == items.end()) {
    std::vector<std::string> names;
    for (const Desc& d : items) names.push_back(d.name);
    r.fail(n, key, "no " + key + " called '" + name + "' (one of " + join(names) + ")");
  }
  return static_cast<int>(named - items.begin());
}

// One `[[loads]]` entry: the body it acts on (by name), then force, torque, start, ramp and stop.
sim::LoadDesc readLoad(Reader& r, const std::vector<sim::BodyDesc>& bodies) {
  sim::LoadDesc load;
  load.body = namedIndex(r, "body", "a dynamic body", bodies);
  load.body_name = bodies[static_cast<std::size_t>(load.body)].name;
  if (!r.has("force") && !r.has("torque")) {
    r.fail(nullptr, "force",
           "missing: give force = [x, y, z] (N), torque = [x, y, z] (N m) or both");
  }
  for (const sim::Setting<sim::LoadDesc>& s : sim::loadSettings()) {
    r.setting(s, load, std::string(s.name));
  }
  r.failOn(sim::validateLoad(load, bodies));
  r.finish();
  return load;
}

}  // namespace

// `[[loads]]`: known external loads, named `loads.INDEX` in errors and --set.
void readLoads(Reader& parent, sim::SceneDesc& scene) {
  for (const auto& [key, t] : parent.arrayTables("loads", "")) {
    Reader r(*t, parent.field(key), parent.file());
    scene.loads.push_back(readLoad(r, scene.bodies));
  }
}

// `[[changes]]`: scripted changes of a finger's live god-finger settings at a time, in time
// order, named `changes.INDEX` in errors and --set. Each entry holds the finger's whole settings
// from then on: the fields it names over the finger's settings before it.
void readChanges(Reader& parent, sim::SceneDesc& scene) {
  std::vector<sim::PatchSettings> current;
  for (const sim::FingerDesc& f : scene.fingers) current.push_back(f.patch);
  double previous_time = 0.0;
  for (const auto& [key, t] : parent.arrayTables("changes", "")) {
    Reader r(*t, parent.field(key), parent.file());
    sim::PatchChange change;
    change.finger = namedIndex(r, "finger", "a finger", scene.fingers);
    change.time = r.requiredNumber("t", 0.0, 1e6);
    sim::FingerDesc next = scene.fingers[static_cast<std::size_t>(change.finger)];
    next.patch = current[static_cast<std::size_t>(change.finger)];
    bool any = false;
    const std::string live = sim::liveFingerSettingNames();
    for (const sim::Setting<sim::FingerDesc>& s : sim::fingerSettings()) {
      const std::string field(s.name);
      if (!s.live && r.has(field)) r.fail(r.find(field), field, "cannot change during a run; a change may give " + live);
      if (s.live) any = r.setting(s, next, field) || any;
    }
    r.finish();  // a misspelt setting is named as unknown, not as a change without settings
    if (!any) r.fail(r.find("finger"), "finger", "the change names no setting: give one or more of " + live);
    change.patch = next.patch;
    r.failOn(sim::validateChange(change, scene.fingers, previous_time));
    current[static_cast<std::size_t>(change.finger)] = change.patch;
    previous_time = change.time;
    scene.changes.push_back(change);
  }
}

}  // namespace gf::app

// godfinger.World: a live session (app/session/live.hpp) stepped and steered from Python. Every
// command but `step` goes through the live protocol's own parser, so it is checked and refused
// exactly as `godfinger live` does; `step` calls the session's step directly (one haptic step
// per call costs what the C++ loop's does, plus the call).
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "app/python/convert.hpp"
#include "app/python/module.hpp"
#include "app/runs/contacts.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/session/live.hpp"

namespace gf::app::python {
namespace {

using namespace pybind11::literals;

// The most steps one call takes, as `step N` of the live protocol.
constexpr long kMaxSteps = 10000000;

class World {
 public:
  World(const std::string& scene, const py::dict& set) : live_(options(scene, set)) {}

  void step(long n) {
    if (n < 1 || n > kMaxSteps) command("step " + std::to_string(n));  // refused with live's words
    for (long i = 0; i < n; ++i) live_.step();
  }
  py::object state() { return parseJson(command("state")); }
  std::string move(const std::string& finger, const std::vector<double>& xyz, double seconds) {
    if (xyz.size() != 3) throw InputError("move", 0, 0, "xyz", "expected 3 coordinates (m), got " + std::to_string(xyz.size()));
    return command("move " + finger + " " + shortestNumber(xyz[0]) + " " + shortestNumber(xyz[1]) + " " +
                   shortestNumber(xyz[2]) + " " + shortestNumber(seconds));
  }
  void set(const std::string& field, const py::object& value) {
    py::dict one;
    one[py::str(field)] = value;
    command("set " + overridesFromDict(one).front());
  }
  py::dict snapshot() { return snapshotDict(live_.snapshot(), live_.session().scene); }
  py::object contacts() { return parseJson(contactsJson(live_.snapshot(), live_.session().scene).dump()); }
  double time() const { return live_.time(); }
  std::vector<std::string> names(bool fingers) const {
    std::vector<std::string> out;
    const sim::SceneDesc& s = live_.session().scene;
    if (fingers) {
      for (const sim::FingerDesc& f : s.fingers) out.push_back(f.name);
    } else {
      for (const sim::BodyDesc& b : s.bodies) out.push_back(b.name);
    }
    return out;
  }
  const std::string& name() const { return live_.session().scene.name; }

 private:
  static LiveOptions options(const std::string& scene, const py::dict& set) {
    LiveOptions o;
    o.scene_path = resolveScenePath(scene);
    o.overrides = overridesFromDict(set);
    return o;
  }

  // One line of the live protocol; its answer without the leading "ok ".
  std::string command(const std::string& line) {
    std::string answer;
    live_.execute(line, answer);
    return answer.rfind("ok ", 0) == 0 ? answer.substr(3) : answer;
  }

  LiveSession live_;
};

}  // namespace

void bindWorld(py::module_& m) {
  py::class_<World>(m, "World", "A scene's world, stepped and steered as `godfinger live` does")
      .def(py::init<const std::string&, const py::dict&>(), "scene"_a, py::kw_only(), "set"_a = py::dict(),
           "Loads a scene (a file, or the name of a bundled scene) with set={field: value} as --set")
      .def("step", &World::step, "n"_a = 1, "N haptic steps (1 / haptic_rate_hz each)")
      .def("state", &World::state, "The live `state` answer as a dict")
      .def("move", &World::move, "finger"_a, "xyz"_a, "seconds"_a = 0.0,
           "The finger's device to xyz (m), straight, over `seconds`; returns the answer")
      .def("set", &World::set, "field"_a, "value"_a, "A live finger setting: set('fingers.NAME.FIELD', value)")
      .def("snapshot", &World::snapshot, "The world now, with each contact's SGOs and loads as numpy arrays")
      .def("contacts", &World::contacts, "The contacts JSON of `live`'s snapshot command, as Python objects")
      .def_property_readonly("t", &World::time, "Simulated time (s)")
      .def_property_readonly("fingers", [](const World& w) { return w.names(true); })
      .def_property_readonly("bodies", [](const World& w) { return w.names(false); })
      .def("__repr__", [](const World& w) { return "<godfinger.World " + w.name() + " at t=" + shortestNumber(w.time()) + " s>"; });
}

}  // namespace gf::app::python

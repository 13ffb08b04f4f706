// godfinger.World's C++ side (world.hpp). Every command but `step` goes through the live
// protocol's own parser, so it is checked and refused exactly as `godfinger live` does; `step`
// calls the session's step directly (one haptic step per call costs what the C++ loop's does,
// plus the call).
//
// Save and restore keep the history, not the world: a sim::World's state is Bullet's (bodies,
// the broadphase's pair cache and its order, contact manifolds with their warm-start impulses,
// the solver's seed) and the god-finger's own (warm-started walks, proxies, filters, port
// observers), and no part of it can be copied out and back in whole. A World built again from
// the same loaded scene and given the same steps and commands is the same world bit for bit
// (the determinism tests'), so restore builds one and replays the history into it.
#include "app/python/world.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <stdexcept>

#include "app/live/live_command.hpp"
#include "app/python/convert.hpp"
#include "app/runs/contacts.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"

namespace gf::app::python {
namespace {

using namespace pybind11::literals;

// The most steps one call takes, as `step N` of the live protocol.
constexpr long kMaxSteps = 10000000;

std::shared_ptr<const WorldOrigin> loadOrigin(const py::object& scene, const py::dict& set) {
  auto origin = std::make_shared<WorldOrigin>();
  origin->options.scene_path = resolveScenePath(pathText(scene, "World: scene"));
  origin->options.overrides = overridesFromDict(set);
  origin->start = loadSceneFile(origin->options.scene_path, origin->options.overrides);
  return origin;
}

std::unique_ptr<LiveSession> startSession(const WorldOrigin& origin) {
  return std::make_unique<LiveSession>(origin.options, origin.start);
}

// `n` steps of `live`, checking Python's signals between every kStepsPerSignalCheck; returns
// the steps taken and whether a signal's handler raised (its exception is then Python's error).
struct Stepped {
  long steps = 0;
  bool interrupted = false;
};
Stepped stepChecked(LiveSession& live, long n) {
  Stepped done;
  while (done.steps < n) {
    const long chunk = std::min(n - done.steps, World::kStepsPerSignalCheck);
    for (long i = 0; i < chunk; ++i) live.step();
    done.steps += chunk;
    if (done.steps < n && PyErr_CheckSignals() != 0) {
      done.interrupted = true;
      break;
    }
  }
  return done;
}

// One command is one line of the protocol: a control character (a newline above all) in a
// finger's name, a field or a value is refused before the parser sees it.
void refuseControlCharacters(const std::string& line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if (c < 0x20 || c == 0x7f) {
      throw std::invalid_argument(line.substr(0, line.find(' ')) + ": control character " + std::to_string(c) +
                                  " at byte " + std::to_string(i) + " of the command (one command is one line)");
    }
  }
}

}  // namespace

World::World(const py::object& scene, const py::dict& set)
    : origin_(loadOrigin(scene, set)), live_(startSession(*origin_)) {}

void World::close() {
  if (live_) live();  // refused from another thread
  live_.reset();
  history_.clear();
}

LiveSession& World::live() {
  if (!live_) throw std::runtime_error("godfinger.World: closed (close() or the end of its `with` block)");
  if (std::this_thread::get_id() != owner_) {
    throw std::runtime_error("godfinger.World: used from another thread than the one that made it (make one World per thread)");
  }
  return *live_;
}

std::string World::command(const std::string& line) {
  LiveSession& session = live();
  refuseControlCharacters(line);
  std::string answer;
  session.execute(line, answer);
  return answer.rfind("ok ", 0) == 0 ? answer.substr(3) : answer;
}

void World::addSteps(long n) {
  if (n == 0) return;
  if (!history_.empty() && history_.back().line.empty()) history_.back().steps += n;
  else history_.push_back({"", n});
}

void World::step(long n) {
  LiveSession& session = live();
  if (n < 1 || n > kMaxSteps) command("step " + std::to_string(n));  // refused with live's words
  const Stepped done = stepChecked(session, n);
  addSteps(done.steps);
  if (done.interrupted) throw py::error_already_set();
}

void World::reset() {
  live();
  live_ = startSession(*origin_);
  history_.clear();
}

SavedState World::save() {
  const LiveSession& session = live();
  return {origin_, history_, session.time(), session.world().counters().steps};
}

void World::restore(const SavedState& state) {
  live();
  if (state.origin != origin_) {
    throw std::invalid_argument("restore: the state was saved by another World (a State restores into the World that saved it)");
  }
  // Built aside and swapped in whole: an interrupted replay leaves this World as it was.
  std::unique_ptr<LiveSession> next = startSession(*origin_);
  for (const HistoryEntry& e : state.history) {
    if (e.line.empty()) {
      if (stepChecked(*next, e.steps).interrupted) throw py::error_already_set();
      continue;
    }
    std::string answer;
    next->execute(e.line, answer);
  }
  live_ = std::move(next);
  history_ = state.history;
}

py::object World::state() {
  LiveSession& session = live();
  return jsonObject(stateJson(session.snapshot(), session.session().scene));
}

std::string World::move(const std::string& finger, const std::vector<double>& xyz, double seconds) {
  live();
  // A name with a space (or none) would be read as other words of the line.
  if (finger.empty() || finger.find(' ') != std::string::npos) throw std::invalid_argument("no finger called '" + finger + "'");
  if (xyz.size() != 3) throw InputError("move", 0, 0, "xyz", "expected 3 coordinates (m), got " + std::to_string(xyz.size()));
  const std::string line = "move " + finger + " " + shortestNumber(xyz[0]) + " " + shortestNumber(xyz[1]) + " " +
                           shortestNumber(xyz[2]) + " " + shortestNumber(seconds);
  std::string answer = command(line);
  history_.push_back({line, 0});
  return answer;
}

void World::set(const std::string& field, const py::object& value) {
  live();
  py::dict one;
  one[py::str(field)] = value;
  const std::string line = "set " + overridesFromDict(one).front();
  command(line);
  history_.push_back({line, 0});
}

py::dict World::snapshot() {
  LiveSession& session = live();
  return snapshotDict(session.snapshot(), session.session().scene);
}

py::object World::contacts() {
  LiveSession& session = live();
  return jsonObject(contactsJson(session.snapshot(), session.session().scene));
}

py::dict World::arrays() {
  const sim::World& w = live().world();
  const auto bodies = static_cast<py::ssize_t>(w.desc().bodies.size());
  const auto fingers = static_cast<py::ssize_t>(w.desc().fingers.size());
  py::array_t<double> position({bodies, py::ssize_t{3}}), orientation({bodies, py::ssize_t{4}});
  py::array_t<double> velocity({bodies, py::ssize_t{3}}), angular({bodies, py::ssize_t{3}});
  double *p = position.mutable_data(), *q = orientation.mutable_data(), *v = velocity.mutable_data(),
         *a = angular.mutable_data();
  // Per body: its description frame's pose (quaternion x y z w) and velocities, world frame.
  for (int b = 0; b < bodies; ++b) {
    const sim::Pose pose = w.bodyPose(b);
    const sim::Vec3 lin = w.bodyLinearVelocity(b), ang = w.bodyAngularVelocity(b);
    for (int i = 0; i < 3; ++i, ++p, ++v, ++a) *p = pose.position[i], *v = lin[i], *a = ang[i];
    for (const double c : {pose.orientation.x(), pose.orientation.y(), pose.orientation.z(), pose.orientation.w()}) *q++ = c;
  }
  // Per finger: the god-object (proxy), the device, the coupling's force and the device's.
  py::array_t<double> proxy({fingers, py::ssize_t{3}}), device({fingers, py::ssize_t{3}});
  py::array_t<double> force({fingers, py::ssize_t{3}}), feedback({fingers, py::ssize_t{3}});
  py::array_t<int> sgos(fingers);
  double *x = proxy.mutable_data(), *d = device.mutable_data(), *f = force.mutable_data(), *r = feedback.mutable_data();
  for (int k = 0; k < fingers; ++k) {
    const sim::Vec3 xk = w.proxyPosition(k), dk = w.devicePosition(k), fk = w.couplingForce(k), rk = w.feedbackForce(k);
    for (int i = 0; i < 3; ++i) *x++ = xk[i], *d++ = dk[i], *f++ = fk[i], *r++ = rk[i];
    sgos.mutable_data()[k] = w.sgoCount(k);
  }
  return py::dict("t"_a = w.time(), "step"_a = w.counters().steps, "body_position"_a = position,
                  "body_orientation"_a = orientation, "body_velocity"_a = velocity,
                  "body_angular_velocity"_a = angular, "finger_proxy"_a = proxy, "finger_device"_a = device,
                  "finger_force"_a = force, "finger_feedback"_a = feedback, "finger_n_sgo"_a = sgos);
}

double World::time() { return live().time(); }

std::vector<std::string> World::names(bool fingers) {
  const sim::SceneDesc& s = live().session().scene;
  std::vector<std::string> out;
  if (fingers) {
    for (const sim::FingerDesc& f : s.fingers) out.push_back(f.name);
  } else {
    for (const sim::BodyDesc& b : s.bodies) out.push_back(b.name);
  }
  return out;
}

std::string World::repr() const {
  const std::string name = origin_->start.scene.name;
  if (!live_) return "<godfinger.World " + name + " (closed)>";
  return "<godfinger.World " + name + " at t=" + shortestNumber(live_->time()) + " s>";
}

}  // namespace gf::app::python

#include "app/runs/run_folder.hpp"
#include "app/session/live.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <csignal>
#include <optional>
#include <cmath>
#include <filesystem>
#include <istream>
#include <ostream>
#include <sstream>
#include <vector>

#include "app/runs/contacts.hpp"
#include "app/runs/files.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/interrupt.hpp"
#include "sim/settings.hpp"
#include "sim/world.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

class Live {
 public:
  Live(const LiveOptions& o, std::ostream& out)
      : options_(o), out_(out), session_(loadSceneFile(o.scene_path, o.overrides)), world_(session_.scene) {
    // Live steps when told to; a UDP device's packets come in wall-clock time.
    if (!session_.udp_devices.empty()) {
      const UdpDeviceDesc& d = session_.udp_devices.front();
      throw InputError(d.file, d.line, d.column,
                       "fingers." + session_.scene.fingers[static_cast<std::size_t>(d.finger)].name + ".device.udp",
                       "`live` steps on command and cannot follow a UDP device: use `godfinger run --realtime`");
    }
    devices_ = sim::deviceTracks(session_.scene);
    samples_.resize(devices_.size());
  }

  // Executes one line; returns false on quit. Every word is read and checked before anything
  // runs: a bad line changes nothing and gets one error reply.
  bool execute(const std::string& line) {
    std::istringstream split(line);
    std::vector<std::string> w;
    for (std::string word; split >> word;) w.push_back(word);
    if (w.empty() || w[0][0] == '#') return true;
    const std::string& command = w[0];
    const auto arguments = [&](std::size_t lo, std::size_t hi, const char* usage) {
      if (w.size() - 1 < lo || w.size() - 1 > hi) throw std::invalid_argument(command + ": expected " + usage);
    };
    if (command == "quit" || command == "exit") {
      arguments(0, 0, "no argument");
      out_ << "ok bye\n";
      return false;
    }
    if (command == "help") {
      arguments(0, 0, "no argument");
      out_ << "ok commands: move FINGER X Y Z [SECONDS] | set fingers.NAME.FIELD=VALUE | step [N] | "
              "state | snapshot [NAME] | quit\n";
    } else if (command == "step") {
      arguments(0, 1, "step [N]");
      const long n = w.size() > 1 ? wholeNumber(w[1], 1, 10000000, "step: N") : 1;
      for (long i = 0; i < n && !(options_.stop_on_interrupt && interruptSignal() != 0); ++i) step();
      answerState();
    } else if (command == "state") {
      arguments(0, 0, "no argument");
      answerState();
    } else if (command == "move") {
      arguments(4, 5, "FINGER X Y Z [SECONDS]");
      move(w);
    } else if (command == "set") {
      arguments(1, 1, "fingers.NAME.FIELD=VALUE");
      set(w[1]);
    } else if (command == "snapshot") {
      arguments(0, 1, "snapshot [NAME]");
      const std::string name = w.size() > 1 ? w[1] : "live_" + std::to_string(world_.counters().steps);
      if (name.find('/') != std::string::npos) throw std::invalid_argument("snapshot: NAME must not contain '/'");
      snapshot(name);
    } else {
      throw std::invalid_argument("unknown command '" + command + "' (try help)");
    }
    return true;
  }

  double time() const { return world_.time(); }

  // `text` as a whole number in lo..hi, or throws naming `what`.
  static long wholeNumber(const std::string& text, long lo, long hi, const std::string& what) {
    long v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi) {
      throw std::invalid_argument(what + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                                  ", got '" + text + "'");
    }
    return v;
  }
  // `text` as a finite number, or throws naming `what`.
  static double finiteNumber(const std::string& text, const std::string& what) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
      throw std::invalid_argument(what + " must be a finite number, got '" + text + "'");
    }
    return v;
  }

 private:
  void step() {
    const double t = world_.time();
    for (std::size_t i = 0; i < devices_.size(); ++i) samples_[i] = devices_[i].sample(t);
    world_.step(1.0 / session_.scene.world.haptic_rate_hz, samples_);
  }

  int fingerIndex(const std::string& name) const {
    for (std::size_t i = 0; i < session_.scene.fingers.size(); ++i) {
      if (session_.scene.fingers[i].name == name) return static_cast<int>(i);
    }
    throw std::invalid_argument("no finger called '" + name + "'");
  }

  void move(const std::vector<std::string>& w) {
    const std::string& finger = w[1];
    const double x = finiteNumber(w[2], "move: X"), y = finiteNumber(w[3], "move: Y"), z = finiteNumber(w[4], "move: Z");
    const double seconds = w.size() > 5 ? finiteNumber(w[5], "move: SECONDS") : 0.0;
    const sim::Vec3 target(x, y, z);
    if (!target.allFinite() || !std::isfinite(seconds) || seconds < 0.0) {
      throw std::invalid_argument("move: position and SECONDS must be finite, SECONDS >= 0");
    }
    const int f = fingerIndex(finger);
    const double t = world_.time();
    sim::DeviceTrack track;
    track.interpolation = sim::Interpolation::kLinear;
    track.keyframes.push_back({t, devices_[f].sample(t).position});
    if (seconds > 0.0) track.keyframes.push_back({t + seconds, target});
    else track.keyframes.back().position = target;
    if (const std::optional<sim::FieldError> e = sim::validateTrack(track)) {
      throw std::invalid_argument("move: " + e->reason);
    }
    devices_[f] = track;
    out_ << "ok " << finger << " to " << x << ' ' << y << ' ' << z << " by t=" << t + seconds << '\n';
  }

  // fingers.NAME.FIELD=VALUE: a live finger setting, checked by its validator, applied from
  // the next step.
  void set(const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    const std::string key = assignment.substr(0, eq);
    const std::size_t dot = key.rfind('.');
    const bool finger_field = key.rfind("fingers.", 0) == 0 && dot != std::string::npos && dot > 8;
    const sim::Setting<sim::FingerDesc>* s =
        finger_field ? sim::findSetting(sim::fingerSettings(), std::string_view(key).substr(dot + 1)) : nullptr;
    if (eq == std::string::npos || !s || !s->live) {
      throw std::invalid_argument("set: expected fingers.NAME.FIELD=VALUE with FIELD one of " + sim::liveFingerSettingNames());
    }
    const int f = fingerIndex(key.substr(8, dot - 8));
    const std::string text = assignment.substr(eq + 1);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw std::invalid_argument(key + ": expected a number, got '" + text + "'");
    if (const std::optional<std::string> why = sim::checkGiven(*s, value)) throw std::invalid_argument(key + ": " + *why);
    sim::FingerDesc next = session_.scene.fingers[f];
    sim::setGiven(*s, next, value);
    world_.setPatchSettings(f, next.patch);
    session_.scene.fingers[f].patch = next.patch;
    out_ << "ok " << assignment << '\n';
  }

  void snapshot(const std::string& name) {
    sim::Snapshot snap;
    world_.snapshot(snap);
    const fs::path dir = fs::path(options_.out_dir) / kContactsFolder;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot create folder: " + ec.message());
    const std::string path = (dir / (name + ".json")).string();
    writeFileAtomically(path, contactsJson(snap, session_.scene).dump(1) + "\n");
    out_ << "ok " << path << '\n';
  }

  void answerState() {
    nlohmann::json fingers = nlohmann::json::array();
    for (std::size_t i = 0; i < session_.scene.fingers.size(); ++i) {
      const int f = static_cast<int>(i);
      const sim::Vec3 p = world_.proxyPosition(f), force = world_.couplingForce(f);
      fingers.push_back({{"name", session_.scene.fingers[i].name},
                         {"proxy", {p.x(), p.y(), p.z()}},
                         {"force_n", {force.x(), force.y(), force.z()}},
                         {"n_sgo", world_.sgoCount(f)}});
    }
    // Every dynamic body: pose (position m, orientation quaternion x y z w), velocities.
    nlohmann::json bodies = nlohmann::json::array();
    for (std::size_t i = 0; i < session_.scene.bodies.size(); ++i) {
      if (session_.scene.bodies[i].mass <= 0.0) continue;
      const int b = static_cast<int>(i);
      const sim::Pose pose = world_.bodyPose(b);
      const sim::Vec3 v = world_.bodyLinearVelocity(b), w = world_.bodyAngularVelocity(b);
      const sim::Quat& q = pose.orientation;
      bodies.push_back({{"name", session_.scene.bodies[i].name},
                        {"position", {pose.position.x(), pose.position.y(), pose.position.z()}},
                        {"orientation", {q.x(), q.y(), q.z(), q.w()}},
                        {"velocity", {v.x(), v.y(), v.z()}},
                        {"angular_velocity", {w.x(), w.y(), w.z()}}});
    }
    out_ << "ok " << nlohmann::json{{"t", world_.time()}, {"fingers", fingers}, {"bodies", bodies}}.dump() << '\n';
  }

  const LiveOptions& options_;
  std::ostream& out_;
  SessionDesc session_;
  sim::World world_;
  std::vector<sim::DeviceTrack> devices_;
  std::vector<sim::DeviceSample> samples_;
};

}  // namespace

int runLive(const LiveOptions& options, std::istream& in, std::ostream& out) {
  Live live(options, out);
  std::optional<InterruptScope> interrupt;
  if (options.stop_on_interrupt) interrupt.emplace();
  out << "ok ready (help lists the commands)" << std::endl;
  int failures = 0, number = 0;
  std::string line;
  const auto interrupted = [&] { return interrupt && interruptSignal() != 0; };
  while (!interrupted() && std::getline(in, line)) {
    ++number;
    bool go_on = true;
    try {
      go_on = live.execute(line);
    } catch (const std::exception& e) {
      ++failures;
      out << "error: " << options.input_name << ':' << number << ": " << e.what() << '\n';
    }
    out.flush();
    if (!go_on) break;
  }
  if (interrupted()) {
    out << "error: interrupted by " << (interruptSignal() == SIGTERM ? "SIGTERM" : "SIGINT") << " at t = "
        << live.time() << " s; the session ends" << std::endl;
    return interruptedStatus();
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace gf::app

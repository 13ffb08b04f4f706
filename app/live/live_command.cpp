#include "app/live/live_command.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "app/runs/contacts.hpp"
#include "app/runs/files.hpp"
#include "app/runs/run_folder.hpp"

namespace gf::app {
namespace {

// `text` as a whole number in lo..hi, or throws naming `what`.
long wholeNumber(const std::string& text, long lo, long hi, const std::string& what) {
  long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi) {
    throw std::invalid_argument(what + " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi) +
                                ", got '" + text + "'");
  }
  return v;
}

// `text` as a finite number, or throws naming `what`.
double finiteNumber(const std::string& text, const std::string& what) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) {
    throw std::invalid_argument(what + " must be a finite number, got '" + text + "'");
  }
  return v;
}

int fingerIndex(const sim::SceneDesc& scene, const std::string& name) {
  for (std::size_t i = 0; i < scene.fingers.size(); ++i) {
    if (scene.fingers[i].name == name) return static_cast<int>(i);
  }
  throw std::invalid_argument("no finger called '" + name + "'");
}

void parseMove(const std::vector<std::string>& w, const sim::SceneDesc& scene, LiveCommand& c) {
  c.finger = fingerIndex(scene, w[1]);
  c.target = sim::Vec3(finiteNumber(w[2], "move: X"), finiteNumber(w[3], "move: Y"), finiteNumber(w[4], "move: Z"));
  c.seconds = w.size() > 5 ? finiteNumber(w[5], "move: SECONDS") : 0.0;
  if (c.seconds < 0.0 || c.seconds > 1e6) throw std::invalid_argument("move: SECONDS must be in 0..1e6");
  if (c.target.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    throw std::invalid_argument("move: each coordinate must be within ±" + std::to_string(sim::kMaxSceneCoordinate) +
                                " m");
  }
}

// fingers.NAME.FIELD=VALUE: a live finger setting, checked by its validator.
void parseSet(const std::string& assignment, const sim::SceneDesc& scene, LiveCommand& c) {
  const std::size_t eq = assignment.find('=');
  const std::string key = assignment.substr(0, eq);
  const std::size_t dot = key.rfind('.');
  const bool finger_field = key.rfind("fingers.", 0) == 0 && dot != std::string::npos && dot > 8;
  c.setting = finger_field ? sim::findSetting(sim::fingerSettings(), std::string_view(key).substr(dot + 1)) : nullptr;
  if (eq == std::string::npos || !c.setting || !c.setting->live) {
    throw std::invalid_argument("set: expected fingers.NAME.FIELD=VALUE with FIELD one of " + sim::liveFingerSettingNames());
  }
  c.finger = fingerIndex(scene, key.substr(8, dot - 8));
  const std::string text = assignment.substr(eq + 1);
  char* end = nullptr;
  c.value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw std::invalid_argument(key + ": expected a number, got '" + text + "'");
  if (const std::optional<std::string> why = sim::checkGiven(*c.setting, c.value)) {
    throw std::invalid_argument(key + ": " + *why);
  }
  c.text = assignment;
}

}  // namespace

const char* const kLiveHelp =
    "commands: move FINGER X Y Z [SECONDS] | set fingers.NAME.FIELD=VALUE | step [N] | state | snapshot [NAME] | "
    "record start|stop | quit";

LiveCommand parseLiveCommand(const std::string& line, const sim::SceneDesc& scene) {
  std::istringstream split(line);
  std::vector<std::string> w;
  for (std::string word; split >> word;) w.push_back(word);
  LiveCommand c;
  if (w.empty() || w[0][0] == '#') return c;
  const std::string& command = w[0];
  const auto arguments = [&](std::size_t lo, std::size_t hi, const char* usage) {
    if (w.size() - 1 < lo || w.size() - 1 > hi) throw std::invalid_argument(command + ": expected " + usage);
  };
  using Kind = LiveCommand::Kind;
  if (command == "quit" || command == "exit" || command == "help" || command == "state") {
    arguments(0, 0, "no argument");
    c.kind = command == "help" ? Kind::kHelp : command == "state" ? Kind::kState : Kind::kQuit;
  } else if (command == "step") {
    arguments(0, 1, "step [N]");
    c.kind = Kind::kStep;
    c.steps = w.size() > 1 ? wholeNumber(w[1], 1, 10000000, "step: N") : 1;
  } else if (command == "move") {
    arguments(4, 5, "FINGER X Y Z [SECONDS]");
    c.kind = Kind::kMove;
    parseMove(w, scene, c);
  } else if (command == "set") {
    arguments(1, 1, "fingers.NAME.FIELD=VALUE");
    c.kind = Kind::kSet;
    parseSet(w[1], scene, c);
  } else if (command == "snapshot") {
    arguments(0, 1, "snapshot [NAME]");
    c.kind = Kind::kSnapshot;
    c.text = w.size() > 1 ? w[1] : "";
    if (c.text.find('/') != std::string::npos || c.text == "." || c.text == "..") {
      throw std::invalid_argument("snapshot: NAME must not contain '/'");
    }
  } else if (command == "record") {
    arguments(1, 1, "record start|stop");
    if (w[1] != "start" && w[1] != "stop") throw std::invalid_argument("record: expected start or stop, got '" + w[1] + "'");
    c.kind = Kind::kRecord;
    c.on = w[1] == "start";
  } else {
    throw std::invalid_argument("unknown command '" + command + "' (try help)");
  }
  return c;
}

std::string moveAnswer(const LiveCommand& c, const sim::SceneDesc& scene, double t_end) {
  std::ostringstream out;
  out << "ok " << scene.fingers[static_cast<std::size_t>(c.finger)].name << " to " << c.target.x() << ' '
      << c.target.y() << ' ' << c.target.z() << " by t=" << t_end;
  return out.str();
}

std::string writeSnapshot(const LiveCommand& c, const sim::Snapshot& snapshot, const sim::SceneDesc& scene,
                          const std::string& out_dir) {
  const std::string name = c.text.empty() ? "live_" + std::to_string(snapshot.step) : c.text;
  const std::filesystem::path dir = std::filesystem::path(out_dir) / kContactsFolder;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create folder: " + ec.message());
  const std::string path = (dir / (name + ".json")).string();
  writeFileAtomically(path, contactsJson(snapshot, scene).dump(1) + "\n");
  return "ok " + path;
}

sim::PatchSettings applySet(const LiveCommand& command, const sim::PatchSettings& current) {
  sim::FingerDesc f;
  f.patch = current;
  sim::setGiven(*command.setting, f, command.value);
  return f.patch;
}

nlohmann::json stateJson(const sim::Snapshot& snap, const sim::SceneDesc& scene) {
  const auto vec = [](const sim::Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  nlohmann::json fingers = nlohmann::json::array();
  for (std::size_t i = 0; i < snap.fingers.size() && i < scene.fingers.size(); ++i) {
    const sim::FingerSnapshot& f = snap.fingers[i];
    nlohmann::json contacts = nlohmann::json::array();
    for (const sim::ContactSnapshot& c : f.contacts) {
      nlohmann::json& contact = contacts.emplace_back(nlohmann::json{{"body", scene.bodies[static_cast<std::size_t>(c.body)].name},
                                                                     {"point", vec(c.point_world)},
                                                                     {"radius_m", c.radius},
                                                                     {"sgos", c.sgos_world.size()}});
      addLoadsJson(c, contact);
    }
    sim::FingerDesc desc = scene.fingers[i];
    desc.patch = f.patch;
    fingers.push_back({{"name", scene.fingers[i].name},
                       {"proxy", vec(f.proxy)},
                       {"device", vec(f.device)},
                       {"force_n", vec(f.coupling_force)},
                       {"feedback_n", vec(f.feedback_force)},
                       {"n_sgo", f.sgo_count},
                       {"model", sim::modelName(f.patch)},
                       {"settings", fingerSettingsJson(desc, true)},
                       {"contacts", contacts}});
  }
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.bodies.size() && i < snap.bodies.size(); ++i) {
    if (scene.bodies[i].mass <= 0.0) continue;
    const sim::Pose& pose = snap.bodies[i];
    const sim::Quat& q = pose.orientation;
    const bool moving = i < snap.body_velocities.size();
    bodies.push_back({{"name", scene.bodies[i].name},
                      {"position", vec(pose.position)},
                      {"orientation", {q.x(), q.y(), q.z(), q.w()}},
                      {"velocity", vec(moving ? snap.body_velocities[i].first : sim::Vec3::Zero())},
                      {"angular_velocity", vec(moving ? snap.body_velocities[i].second : sim::Vec3::Zero())}});
  }
  return {{"t", snap.time}, {"step", snap.step}, {"fingers", fingers}, {"bodies", bodies}};
}

}  // namespace gf::app

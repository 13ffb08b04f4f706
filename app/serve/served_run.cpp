#include "app/serve/served_run.hpp"

#include "app/live/live_command.hpp"

namespace gf::app {

ServedRun::ServedRun(const SessionDesc& session, const ServeOptions& options, const view::Camera& camera,
                     const std::string& out_dir, bool background)
    : session_(session), out_dir_(out_dir), view_(session, camera, "realtime", out_dir, background) {
  const sim::SceneDesc& scene = session.scene;
  for (std::size_t i = 0; i < scene.fingers.size(); ++i) {
    bool web = false, udp = false;
    for (const WebDeviceDesc& d : session.web_devices) web = web || d.finger == static_cast<int>(i);
    for (const UdpDeviceDesc& d : session.udp_devices) udp = udp || d.finger == static_cast<int>(i);
    devices_.push_back(std::make_unique<SteeredDevice>(scene.fingers[i].device, web));
    settings_.push_back(scene.fingers[i].patch);
    udp_.push_back(udp);
  }
  posted_.reserve(64);
  taking_.reserve(64);
  if (!options.participant.is_null()) view_.setParticipant(options.participant);
  participant_command_ = options.participant_command;
  participant_ = !options.participant.is_null();
  server_ = std::make_unique<WebServer>(
      options, view_, [this](const std::string& line) { return answer(line); });
}

ServedRun::~ServedRun() {
  try {
    finish();
  } catch (const std::exception&) {
    // reported by finish() to an owner that called it
  }
}

std::span<sim::DeviceSource* const> ServedRun::sources(std::span<sim::DeviceSource* const> udp) {
  sources_.clear();
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    sim::DeviceSource* u = i < udp.size() ? udp[i] : nullptr;
    sources_.push_back(u ? u : devices_[i].get());
  }
  return sources_;
}

bool ServedRun::afterStep(sim::World& world) {
  long moves = 0;  // moves taken and moves arrived: a frame should show both at once
  for (const auto& d : devices_) moves += d->moves() + d->arrivals();
  const bool moved = moves != moves_seen_;
  moves_seen_ = moves;
  if (!has_posted_.load(std::memory_order_acquire)) return moved;
  {
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return moved;  // the next step takes them
    taking_.swap(posted_);
    has_posted_.store(false, std::memory_order_relaxed);
  }
  for (const sim::SettingsCommand& c : taking_) {
    try {
      world.setPatchSettings(c.finger, c.patch);  // checked when posted: the World agrees
    } catch (const std::exception&) {
      settings_refused_.fetch_add(1, std::memory_order_relaxed);
    }
  }
  settings_applied_.fetch_add(static_cast<long>(taking_.size()), std::memory_order_relaxed);
  taking_.clear();
  return true;
}

void ServedRun::markMoves(sim::Snapshot& snapshot) const {
  const MoveMarks marks = moveMarks(devices_);
  snapshot.moves_taken = marks.taken;
  snapshot.moves_arrived = marks.arrived;
}

// One `live` command, answered as `godfinger live` answers it on standard input.
std::string ServedRun::answer(const std::string& line) {
  using K = LiveCommand::Kind;
  try {
    if (participant_command_) {
      if (std::optional<std::string> a = participant_command_(line)) return *a;
    }
    const LiveCommand c = parseLiveCommand(line, session_.scene);
    if (participant_ && (c.kind == K::kSet || c.kind == K::kRecord || c.kind == K::kSnapshot)) {
      const char* what = c.kind == K::kSet ? "set" : c.kind == K::kRecord ? "record" : "snapshot";
      return std::string("error: ") + what + ": not during an experiment's trial (its page moves the fingers only)";
    }
    sim::Snapshot snap;
    const bool drawn = view_.latest(snap);
    switch (c.kind) {
      case K::kNone: return "ok";
      case K::kHelp: return std::string("ok ") + kLiveHelp;
      case K::kQuit: return "error: quit: a realtime run ends at its duration, or with Ctrl-C where it was started";
      case K::kStep: return "error: step: a realtime run follows the wall clock (step is for `godfinger live`)";
      case K::kRecord: return view_.record(c.on);
      case K::kState:
        if (!drawn) return "error: state: no frame drawn yet";
        if (participant_) return "ok " + LiveView::participantState(stateJson(snap, session_.scene));
        return "ok " + stateJson(snap, session_.scene).dump();
      case K::kSnapshot:
        if (!drawn) return "error: snapshot: no frame drawn yet";
        return writeSnapshot(c, snap, session_.scene, out_dir_);
      case K::kMove:
        if (udp_[static_cast<std::size_t>(c.finger)]) {
          return "error: move: fingers." + session_.scene.fingers[static_cast<std::size_t>(c.finger)].name +
                 " follows its UDP device";
        }
        {
          // One thread answers the commands (WebServer's commander): numbers follow the posts.
          const long number = moves_numbered_.fetch_add(1, std::memory_order_relaxed) + 1;
          devices_[static_cast<std::size_t>(c.finger)]->moveTo(c.target, c.seconds, number);
          return moveAnswer(c, session_.scene, snap.time + c.seconds) + " move " + std::to_string(number);
        }
      case K::kSet: {
        std::lock_guard lock(mutex_);
        sim::PatchSettings& p = settings_[static_cast<std::size_t>(c.finger)];
        const sim::PatchSettings next = applySet(c, p);
        if (const std::optional<sim::FieldError> e = sim::validatePatch(next)) {
          return "error: " + c.text + ": " + e->reason;  // as the World would refuse it
        }
        p = next;
        posted_.push_back({c.finger, p});
        has_posted_.store(true, std::memory_order_release);
        return "ok " + c.text;
      }
    }
  } catch (const std::exception& e) {
    return std::string("error: ") + e.what();
  }
  return "error: unknown command";
}

nlohmann::json ServedRun::finish() {
  server_->stop();
  view_.finish();
  nlohmann::json out = server_->statsJson();
  out["view"] = view_.statsJson();
  out["settings_applied"] = settings_applied_.load() - settings_refused_.load();
  out["settings_refused"] = settings_refused_.load();
  long moves = 0;
  for (const auto& d : devices_) moves += d->moves();
  out["moves_taken"] = moves;
  return out;
}

}  // namespace gf::app

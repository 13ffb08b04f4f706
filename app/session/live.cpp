#include "app/session/live.hpp"

#include <nlohmann/json.hpp>

#include <condition_variable>
#include <csignal>
#include <deque>
#include <future>
#include <memory>
#include <istream>
#include <mutex>
#include <optional>
#include <ostream>
#include <thread>
#include <utility>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "app/serve/live_view.hpp"
#include "app/process/interrupt.hpp"
#include "app/live/live_command.hpp"
#include "app/session/session.hpp"
#include "sim/world/world.hpp"

namespace gf::app {
namespace {

using K = LiveCommand::Kind;

}  // namespace

LiveSession::LiveSession(const LiveOptions& o) : LiveSession(o, loadSceneFile(o.scene_path, o.overrides)) {}

LiveSession::LiveSession(const LiveOptions& o, SessionDesc session)
    : options_(o), session_(std::move(session)), world_(session_.scene) {
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

namespace {
constexpr std::chrono::milliseconds kDrawnWithin{2000};
}  // namespace

void LiveSession::show(render::RenderThread* renderer, LiveView* view) {
  renderer_ = renderer;
  view_ = view;
  publish();
}

bool LiveSession::execute(const std::string& line, std::string& answer, bool posted) {
  const LiveCommand c = parseLiveCommand(line, session_.scene);
  if (posted && c.kind == K::kQuit) {
    throw std::invalid_argument("quit: only on the session's standard input (or Ctrl-C)");
  }
  switch (c.kind) {
    case K::kNone: return true;
    case K::kQuit: answer = "ok bye"; return false;
    case K::kHelp: answer = std::string("ok ") + kLiveHelp; return true;
    case K::kStep:
      for (long i = 0; i < c.steps && !(options_.stop_on_interrupt && interruptSignal() != 0); ++i) step();
      answer = state();
      break;
    case K::kState: answer = state(); return true;
    case K::kMove: answer = move(c); break;
    case K::kSet: {
      sim::FingerDesc& f = session_.scene.fingers[static_cast<std::size_t>(c.finger)];
      const sim::PatchSettings next = applySet(c, f.patch);
      world_.setPatchSettings(c.finger, next);
      f.patch = next;
      answer = "ok " + c.text;
      break;
    }
    case K::kSnapshot:
      world_.snapshot(snap_);
      answer = writeSnapshot(c, snap_, session_.scene, options_.out_dir);
      return true;
    case K::kRecord:
      if (!view_) throw std::invalid_argument("record: only with --serve (the frames are the browser view's)");
      answer = view_->record(c.on);
      return true;
  }
  publish();
  return true;
}

void LiveSession::step() {
  const double t = world_.time();
  for (std::size_t i = 0; i < devices_.size(); ++i) samples_[i] = devices_[i].sample(t);
  world_.step(1.0 / session_.scene.world.haptic_rate_hz, samples_);
}

const sim::Snapshot& LiveSession::snapshot() {
  world_.snapshot(snap_);
  return snap_;
}

std::string LiveSession::move(const LiveCommand& c) {
  const double t = world_.time();
  sim::DeviceTrack track;
  track.interpolation = sim::Interpolation::kLinear;
  track.keyframes.push_back({t, devices_[static_cast<std::size_t>(c.finger)].sample(t).position});
  if (c.seconds > 0.0) track.keyframes.push_back({t + c.seconds, c.target});
  else track.keyframes.back().position = c.target;
  if (const std::optional<sim::FieldError> e = sim::validateTrack(track)) {
    throw std::invalid_argument("move: " + e->reason);
  }
  devices_[static_cast<std::size_t>(c.finger)] = track;
  return moveAnswer(c, session_.scene, t + c.seconds);
}

std::string LiveSession::state() { return "ok " + stateJson(snapshot(), session_.scene).dump(); }

// The world to the renderer; with a browser view, the answer waits (at most kDrawnWithin) until
// it is drawn, so the page, /frame.jpg and the stream show the state the answer gives.
void LiveSession::publish() {
  if (!renderer_) return;
  long step = 0;
  renderer_->publishLatest([&](sim::Snapshot& slot) {
    world_.snapshot(slot);
    step = slot.step;
  });
  if (view_) view_->waitDrawn(step, kDrawnWithin);
}

namespace {

// Runs one line for `input`:`number`; writes the answer or the error. False on quit.
bool answerLine(LiveSession& live, const std::string& line, const std::string& where, std::string& answer, int& failures,
                bool posted = false) {
  bool go_on = true;
  try {
    go_on = live.execute(line, answer, posted);
  } catch (const std::exception& e) {
    ++failures;
    answer = "error: " + where + e.what();
  }
  return go_on;
}

int interruptedEnd(const LiveSession& live, std::ostream& out) {
  out << "error: interrupted by " << (interruptSignal() == SIGTERM ? "SIGTERM" : "SIGINT") << " at t = " << live.time()
      << " s; the session ends" << std::endl;
  return interruptedStatus();
}

}  // namespace

// Lines from standard input and from the server, taken in turn by the session's thread.
class LiveQueue {
 public:
  struct Item {
    std::string line;
    int number = 0;                        // standard input's line number; 0: from the server
    std::promise<std::string>* reply = nullptr;  // the server's request
    bool end = false;                      // standard input ended
  };
  void push(Item item) {
    std::lock_guard lock(mutex_);
    if (closed_) {  // the session has ended: answered at once, never queued
      if (item.reply) item.reply->set_value("error: the session has ended");
      return;
    }
    items_.push_back(std::move(item));
    changed_.notify_all();
  }
  std::optional<Item> pop(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_for(lock, wait, [&] { return !items_.empty(); })) return std::nullopt;
    Item item = std::move(items_.front());
    items_.pop_front();
    return item;
  }
  // The session has ended: every request still queued, and every one pushed from now on, is
  // answered so (before the server stops: its threads wait for their answers).
  void close() {
    std::lock_guard lock(mutex_);
    closed_ = true;
    for (Item& i : items_) {
      if (i.reply) i.reply->set_value("error: the session has ended");
    }
    items_.clear();
  }

 private:
  bool closed_ = false;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Item> items_;
};

namespace {

// A posted command, answered once the session's thread has run it.
std::string postAndWait(LiveQueue& queue, const std::string& line) {
  std::promise<std::string> reply;
  std::future<std::string> answer = reply.get_future();
  queue.push({line, 0, &reply, false});
  return answer.get();
}

int runServed(LiveSession& live, const LiveOptions& options, std::istream& in, std::ostream& out) {
  const SessionDesc& session = live.session();
  SessionOptions so;
  so.out_dir = options.out_dir;
  so.realtime = true;
  so.camera = options.camera;
  LiveView view(session, sessionCamera(session, options.camera), "live", options.out_dir, false);
  render::FrameOutputSettings fo = frameSettings(session, so);
  fo.background_priority = false;
  fo.tap = &view;
  render::RenderThread renderer(session.scene, fo);
  live.show(&renderer, &view);
  // Shared with the reader thread, which may outlive the session while standard input stays open.
  const auto queue_ptr = std::make_shared<LiveQueue>();
  LiveQueue& queue = *queue_ptr;
  WebServer server(*options.serve, view, [&](const std::string& line) { return postAndWait(queue, line); });
  out << "ok ready, serving " << server.shownUrl() << " (help lists the commands)" << std::endl;
  std::thread reader([queue_ptr, &in] {
    int number = 0;
    for (std::string line; std::getline(in, line);) queue_ptr->push({line, ++number, nullptr, false});
    queue_ptr->push({"", 0, nullptr, true});
  });
  int failures = 0;
  bool go_on = true, input_ended = false;
  while (go_on && !(options.stop_on_interrupt && interruptSignal() != 0)) {
    std::optional<LiveQueue::Item> item = queue.pop(std::chrono::milliseconds(100));
    if (!item) continue;
    if (item->end) {
      input_ended = true;
      out << "ok input ended; serving until Ctrl-C" << std::endl;
      continue;
    }
    std::string answer;
    int posted_failures = 0;  // a page's bad request is answered to it; the exit status is standard input's
    go_on = answerLine(live, item->line, item->reply ? "" : options.input_name + ':' + std::to_string(item->number) + ": ",
                       answer, item->reply ? posted_failures : failures, item->reply != nullptr);
    if (item->reply) item->reply->set_value(answer);
    else if (!answer.empty()) out << answer << std::endl;
  }
  queue.close();
  server.stop();
  view.finish();
  renderer.finish();
  // Standard input may stay open (the session ended by `quit` or Ctrl-C): the reader is left to
  // the process's end, holding its share of the queue.
  if (input_ended) reader.join();
  else reader.detach();
  if (options.stop_on_interrupt && interruptSignal() != 0) return interruptedEnd(live, out);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int runLive(const LiveOptions& options, std::istream& in, std::ostream& out) {
  LiveSession live(options);
  std::optional<InterruptScope> interrupt;
  if (options.stop_on_interrupt) interrupt.emplace();
  if (options.serve) return runServed(live, options, in, out);
  out << "ok ready (help lists the commands)" << std::endl;
  int failures = 0, number = 0;
  std::string line;
  const auto interrupted = [&] { return interrupt && interruptSignal() != 0; };
  while (!interrupted() && std::getline(in, line)) {
    std::string answer;
    const bool go_on = answerLine(live, line, options.input_name + ':' + std::to_string(++number) + ": ", answer, failures);
    if (!answer.empty()) out << answer << '\n';
    out.flush();
    if (!go_on) break;
  }
  if (interrupted()) return interruptedEnd(live, out);
  return failures == 0 ? 0 : 1;
}

}  // namespace gf::app

#include "app/session/session.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <pthread.h>
#include <unistd.h>

#include "app/runs/contacts.hpp"
#include "app/runs/files.hpp"
#include "app/runs/forces.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/summary.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/input_error.hpp"
#include "app/serve/served_run.hpp"
#include "app/session/frame_driver.hpp"
#include "app/process/interrupt.hpp"
#include "app/device/udp_device.hpp"
#include "sim/scene/settings.hpp"
#include "sim/world/world.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// Bodies overlapping by more than this at the start (m) are reported.
constexpr double kStartOverlap = 1e-3;
constexpr double kFirstFrameSeconds = 30.0;  // the most a realtime run waits for its first frame
// What a run's outputs take, about, for the room they need (measured on the bundled scenes):
// bytes per trace.csv or forces.csv number with its comma (14.8 to 17), per pixel of a PNG frame
// (0.36 for a 1280 x 720 scene), per contact snapshot with its close-ups (JSON up to 37 kB, a
// close-up up to 73 kB per finger), for forces.png (36 kB) and for summary.json (5 kB).
constexpr double kBytesPerNumber = 16.0;
constexpr double kPngBytesPerPixel = 0.3;
constexpr double kContactSnapshotBytes = 150e3;
constexpr double kForceChartBytes = 64e3;
constexpr double kSummaryBytes = 64e3;

// Progress on stderr: on a terminal one line rewritten in place once per simulated second;
// otherwise (a log file, a pipe) a plain line at every tenth of the run, so logs stay readable.
class Progress {
 public:
  Progress(std::string name, double duration, long steps, bool on)
      : name_(std::move(name)), duration_(duration), steps_(std::max(1L, steps)), on_(on),
        terminal_(isatty(STDERR_FILENO) == 1),
        every_(terminal_ ? std::max(1L, steps_ / std::max(1L, std::lround(duration_))) : std::max(1L, steps_ / 10)),
        start_(std::chrono::steady_clock::now()) {}
  void step(double t, long done) {
    if (!on_ || done % every_ != 0) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "%s[godfinger] %s: t = %.1f / %.1f s, %ld / %ld steps, ETA %.1f s%s", terminal_ ? "\r" : "",
                 name_.c_str(), t, duration_, done, steps_, wall / static_cast<double>(done) * static_cast<double>(steps_ - done),
                 terminal_ ? " " : "\n");
    printed_ = true;
  }
  void finish() {
    if (on_ && terminal_ && printed_) std::fprintf(stderr, "\n");
  }

 private:
  std::string name_;
  double duration_;
  long steps_;
  bool on_, terminal_, printed_ = false;
  long every_;  // steps between lines: a simulated second on a terminal, a tenth of the run otherwise
  std::chrono::steady_clock::time_point start_;
};

// The y force on the first force body with every finger a god-object, for the Fig. 8 chart.
render::ChartSeries godObjectForces(const SessionDesc& session) {
  sim::SceneDesc scene = session.scene;
  for (sim::FingerDesc& f : scene.fingers) f.patch.n_sgo = 0;
  sim::World world(scene);
  const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(scene);
  const double dt = 1.0 / scene.world.haptic_rate_hz;
  ForceWriter forces(world, {session.record.force_bodies.front()}, 0, "");
  sim::runHapticLoop(world, devices, {scene.world.haptic_rate_hz, scene.duration},
                     [&](const sim::World& w) { forces.record(w, dt); });
  // Okabe–Ito's orange, dashed, square markers: apart from the god-finger's blue in
  // lightness, dash and marker as well as hue.
  render::ChartSeries out = forces.series("god-object (n_SGO = 0)", render::linearFromSrgb(render::kOkabeIto[4]));
  out.dash = render::LineDash::kDashed;
  out.marker = render::MarkerShape::kSquare;
  out.marker_spacing_px = 90.0f;
  out.marker_phase = 0.5f;
  return out;
}

void writeForceChart(const SessionDesc& session, const ForceWriter& forces, render::RenderThread& renderer,
                     const fs::path& path) {
  render::ChartSpec chart;
  chart.title = !session.record.force_chart_title.empty()
                    ? session.record.force_chart_title
                    : session.scene.name + ": y force on " + session.record.force_bodies.front() + " (N, gravity removed)";
  chart.x_label = "time, s";
  chart.y_label = "y force, N";
  chart.series.push_back(godObjectForces(session));
  int n = 0;
  for (const sim::FingerDesc& f : session.scene.fingers) n = std::max(n, f.patch.n_sgo);
  render::ChartSeries finger =
      forces.series("god-finger (n_SGO = " + std::to_string(n) + ")", render::linearFromSrgb(render::kOkabeIto[0]));
  finger.marker_spacing_px = 90.0f;  // circles, solid
  chart.series.push_back(std::move(finger));
  renderer.submitChart(chart, path.string());
}

nlohmann::json changesJson(const std::vector<AppliedChange>& changes, const sim::SceneDesc& scene) {
  nlohmann::json out = nlohmann::json::array();
  for (const AppliedChange& c : changes) {
    sim::FingerDesc finger = scene.fingers[static_cast<std::size_t>(c.command.finger)];
    finger.patch = c.command.patch;
    nlohmann::json j = fingerSettingsJson(finger, true);
    j["t"] = c.time;
    j["finger"] = finger.name;
    out.push_back(std::move(j));
  }
  return out;
}

// The bytes a run of `session` with `options` writes into its folder, about: trace.csv,
// forces.csv, frames, contact snapshots and summary.json. (The video's size depends too much on
// what is seen to be estimated: its folder is proven writable, and a video that does not fit is
// reported and never put in place.)
std::uintmax_t estimatedOutputBytes(const SessionDesc& session, const SessionOptions& options) {
  const sim::SceneDesc& scene = session.scene;
  const double rows = static_cast<double>(sim::stepCount(scene.duration, scene.world.haptic_rate_hz) + 1);
  const auto snapshots = std::count_if(session.record.contact_times.begin(), session.record.contact_times.end(),
                                       [&](double t) { return t <= scene.duration; });
  double bytes = kSummaryBytes + kContactSnapshotBytes * static_cast<double>(snapshots);
  if (session.record.force_chart) bytes += kForceChartBytes;
  if (session.record.trace) {
    const double every = traceStride(scene.world.haptic_rate_hz, session.record.trace_rate);
    bytes += rows / every * static_cast<double>(traceColumns(scene).size()) * kBytesPerNumber;
  }
  bytes += rows * static_cast<double>(1 + 3 * session.record.force_bodies.size()) * kBytesPerNumber;
  if (options.frames) {
    const double frames = std::floor(scene.duration * render::FrameOutputSettings{}.fps) + 1.0;
    bytes += frames * session.view.width * session.view.height * kPngBytesPerPixel;
  }
  return static_cast<std::uintmax_t>(bytes);
}

// Requests a run cannot carry out but that do not make it useless, known before the world is built.
std::vector<std::string> requestWarnings(const SessionDesc& session, const SessionOptions& options) {
  const sim::SceneDesc& scene = session.scene;
  std::vector<std::string> warnings;
  for (double t : session.record.contact_times) {
    if (t > scene.duration + 0.5 / scene.world.haptic_rate_hz) {
      char text[160];
      std::snprintf(text, sizeof text, "record.contacts: %g s is past the run's duration (%g s): no snapshot then", t,
                    scene.duration);
      warnings.emplace_back(text);
    }
  }
  for (const WebDeviceDesc& d : session.web_devices) {
    if (options.serve) continue;
    warnings.push_back("fingers." + scene.fingers[static_cast<std::size_t>(d.finger)].name +
                       ".device.web: no --serve, so no page moves this finger: it stays at its start");
  }
  if (!options.camera.empty() && !options.frames && options.video_path.empty() && !options.serve) {
    warnings.push_back("--camera " + options.camera + ": no --frames or --video, so nothing is drawn with it");
  }
  return warnings;
}

// Bodies that start inside each other, and proxies that start inside a body, as warnings.
void addOverlapWarnings(const sim::World& world, std::vector<std::string>& warnings) {
  const std::vector<sim::BodyDesc>& bodies = world.desc().bodies;
  for (const sim::World::Overlap& o : world.bodyOverlaps(kStartOverlap)) {
    char text[256];
    std::snprintf(text, sizeof text, "bodies.%s and bodies.%s start %.1f mm inside each other: the solver will push them apart",
                  bodies[static_cast<std::size_t>(o.body_a)].name.c_str(),
                  bodies[static_cast<std::size_t>(o.body_b)].name.c_str(), 1e3 * o.depth);
    warnings.emplace_back(text);
  }
  for (const sim::World::ProxyOverlap& o : world.proxyOverlaps(kStartOverlap)) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "fingers.%s's proxy starts %.1f mm inside bodies.%s: the contact will throw the body out; "
                  "start the device outside it",
                  world.desc().fingers[static_cast<std::size_t>(o.finger)].name.c_str(), 1e3 * o.depth,
                  bodies[static_cast<std::size_t>(o.body)].name.c_str());
    warnings.emplace_back(text);
  }
}

// A live device's packets arrive in wall-clock time: it needs the realtime clock; so does a page.
void requireRealtimeForLiveDevices(const SessionDesc& session, const SessionOptions& options) {
  if (options.serve && !options.realtime) {
    throw commandLineError("--serve",
                     "the browser view follows a run in real time: add --realtime (or use `godfinger live --serve`)");
  }
  if (session.udp_devices.empty() || options.realtime) return;
  const UdpDeviceDesc& d = session.udp_devices.front();
  throw InputError(d.file, d.line, d.column,
                   "fingers." + session.scene.fingers[static_cast<std::size_t>(d.finger)].name + ".device.udp",
                   "a UDP device drives the session in real time: run it with --realtime");
}

// One run of a session, stage by stage (runSession). Haptic thread: the thread that calls it.
class SessionRun {
 public:
  SessionRun(const SessionDesc& session, const SessionOptions& options)
      : session_(session), scene_(session.scene), options_(options), dir_(options.out_dir),
        dt_(1.0 / scene_.world.haptic_rate_hz), steps_(sim::stepCount(scene_.duration, scene_.world.haptic_rate_hz)) {}

  void bindDevices();
  void prepareOutputs();
  void startThreads();
  sim::LoopStats loop();
  void finishOutputs(const sim::LoopStats& stats);

 private:
  void afterStep(const sim::World& w);
  void takeContactSnapshots(const sim::World& w);
  void failedOutput(const std::exception& e);
  template <class Write>
  void finish(Write&& write);
  void finishFiles(const sim::LoopStats& stats);
  nlohmann::json summary(const sim::LoopStats& stats);
  void addRenderSummary(nlohmann::json& summary);

  const SessionDesc& session_;
  const sim::SceneDesc& scene_;
  const SessionOptions& options_;
  const fs::path dir_;
  const double dt_;
  const long steps_;
  sim::CpuSplit cpus_;  // realtime, pinned: the loop's CPU and the others'
  std::optional<UdpDeviceBridge> udp_;
  std::unique_ptr<ServedRun> served_;  // --serve: the browser view
  std::optional<InterruptScope> interrupt_;
  std::optional<SignalsBlocked> quiet_threads_;
  std::optional<RunFolder> folder_;
  std::vector<std::string> warnings_;
  std::optional<sim::World> world_;
  std::vector<double> pending_;  // contact snapshot times still to take, the next at the back
  std::vector<std::pair<double, sim::Snapshot>> contact_snaps_;  // serialised after the run
  bool closeups_ = false;
  std::unique_ptr<render::RenderThread> renderer_;
  std::optional<TraceWriter> trace_;
  std::optional<ForceWriter> forces_;
  sim::LiveTimings live_;
  std::unique_ptr<FrameDriver> frames_;
  std::optional<ExpectChecker> expect_;
  std::vector<ExpectFailure> failed_;
  std::atomic<bool> halt_{false};
  std::string failure_;  // the first output failure, which stopped the loop
  bool interrupted_ = false;
  bool summary_written_ = false;
  long done_ = 0;
};

// Live devices: their sockets are bound before anything else (a port in use fails the run here,
// with nothing written).
void SessionRun::bindDevices() {
  requireRealtimeForLiveDevices(session_, options_);
  if (options_.serve) {
    served_ = std::make_unique<ServedRun>(session_, *options_.serve, sessionCamera(session_, options_.camera),
                                          options_.out_dir, options_.yield_render);
    const WebServer& server = served_->server();
    std::fprintf(stderr, "%s: serving %s%s\n", scene_.name.c_str(), server.shownUrl().c_str(),
                 server.loopback() ? "" : "  (beyond loopback: every request needs this token)");
  }
  if (session_.udp_devices.empty()) return;
  udp_.emplace(session_);
  for (const UdpDeviceDesc& d : session_.udp_devices) {
    const std::string& name = scene_.fingers[static_cast<std::size_t>(d.finger)].name;
    std::fprintf(stderr, "%s: fingers.%s.device: listening on %s, channel %d\n", scene_.name.c_str(), name.c_str(),
                 udp_->address(d.finger).c_str(), d.channel);
  }
  for (const std::string& w : udp_->bindWarnings()) {
    std::fprintf(stderr, "%s: warning: %s\n", scene_.name.c_str(), w.c_str());
  }
}

// The folder is this run's before anything in it is touched; room and writability are proven
// before an earlier run's outputs go; then the world is built and the files opened.
void SessionRun::prepareOutputs() {
  // Ctrl-C and SIGTERM are recorded from here on (the outputs are finished when one comes); the
  // threads started until the loop (writers, the render thread, its encoders) do not take them.
  if (options_.stop_on_interrupt) interrupt_.emplace();
  quiet_threads_.emplace();
  folder_.emplace(dir_);
  // The room the outputs need, less what an earlier run's outputs there give back when cleared.
  const std::uintmax_t needed = estimatedOutputBytes(session_, options_), freed = runOutputBytes(dir_);
  requireRoom(dir_, needed > freed ? needed - freed : 0, "the run's outputs");
  requireWritableFolder(dir_, "the run's outputs");
  requireWritableFolder(dir_ / kContactsFolder, "contact snapshots");
  if (options_.frames) requireWritableFolder(dir_ / kFramesFolder, "frames");
  if (!options_.video_path.empty()) requireVideoPath(options_.video_path);
  warnings_ = requestWarnings(session_, options_);
  world_.emplace(scene_);
  // Settings changed live (the overlay, the browser) reach a realtime World on its haptic thread.
  if (options_.realtime) world_->sizeForLiveSettings();
  addOverlapWarnings(*world_, warnings_);
  for (const std::string& w : warnings_) std::fprintf(stderr, "%s: warning: %s\n", scene_.name.c_str(), w.c_str());
  pending_ = session_.record.contact_times;
  std::sort(pending_.begin(), pending_.end(), std::greater<>());
}

// The render thread (frames, close-ups, charts), then the files: what an earlier run left of
// this run's outputs goes only now, when everything that can fail before the first step has.
void SessionRun::startThreads() {
  // Pinned: the threads started here (and the processes they start) inherit the other CPUs.
  if (options_.realtime && options_.pin_cpus) cpus_ = sim::splitCpus();
  std::optional<sim::CpuPin> elsewhere;
  if (cpus_.haptic >= 0) elsewhere.emplace(cpus_.others);
  const bool stream = options_.frames || !options_.video_path.empty() || served_;
  closeups_ = options_.close_ups && !pending_.empty();
  if (stream || closeups_ || session_.record.force_chart) {
    render::FrameOutputSettings fo = frameSettings(session_, options_);
    if (!stream) fo.overlay = fo.patch_insets = false;
    if (served_) fo.tap = served_->tap();
    renderer_ = std::make_unique<render::RenderThread>(scene_, fo);
  }
  clearRunOutputs(dir_);
  if (session_.record.trace) {
    const TraceOptions o{traceStride(scene_.world.haptic_rate_hz, session_.record.trace_rate), true,
                         options_.trace_fail_after_bytes, options_.realtime ? kRealtimeRingRows : kOfflineRingRows};
    trace_.emplace(*world_, (dir_ / kTraceFile).string(), o);
  }
  forces_.emplace(*world_, session_.record.force_bodies, steps_, (dir_ / kForcesFile).string());
  if (stream) frames_ = std::make_unique<FrameDriver>(*renderer_, 60.0, options_.realtime, session_.view.actions, &live_);
  if (frames_ && served_) frames_->setMarks([served = served_.get()](sim::Snapshot& s) { served->markMoves(s); });
  if (frames_) frames_->start(*world_);
  // The loop's clock starts once the first frame is drawn: drawing it compiles llvmpipe's
  // shaders, and its frames would wait for that from the run's first second.
  if (frames_ && options_.realtime) renderer_->waitFirstFrame(kFirstFrameSeconds);
  expect_.emplace(session_.expect, *world_);
  quiet_threads_.reset();  // this thread takes the signals again
}

// The loop stops before its next step on a signal or when an output fails (a full disk, a dead
// ffmpeg): the run then writes what it reached and reports the failure.
sim::LoopStats SessionRun::loop() {
  sim::LoopSettings loop{scene_.world.haptic_rate_hz, scene_.duration,
                         options_.realtime ? sim::ClockMode::kRealtime : sim::ClockMode::kOffline};
  loop.live = &live_;
  loop.fifo = options_.fifo;
  loop.spin_us = options_.spin_us;
  loop.short_slice = options_.short_slice;
  loop.cpu = cpus_.haptic;
  loop.stop = &halt_;
  if (udp_) loop.sources = udp_->sources();
  if (served_) {
    loop.sources = served_->sources(loop.sources);
    if (udp_) served_->setDeviceState([this] { return udp_->liveJson(); });
  }
  Progress progress(scene_.name, scene_.duration, steps_, options_.progress);
  const sim::LoopStats stats = sim::runHapticLoop(*world_, sim::deviceTracks(scene_), loop, [&](const sim::World& w) {
    afterStep(w);
    progress.step(w.time(), ++done_);
  });
  if (udp_) udp_->endRun(world_->time());  // answered while the outputs are written, their force fading
  progress.finish();
  interrupted_ = stats.stopped && failure_.empty();
  if (interrupted_) {
    std::fprintf(stderr, "%s: interrupted at t = %.3f s; writing the outputs of the time reached\n",
                 scene_.name.c_str(), world_->time());
  } else if (!failure_.empty()) {
    std::fprintf(stderr, "%s: stopped at t = %.3f s: %s; writing the outputs of the time reached\n",
                 scene_.name.c_str(), world_->time(), failure_.c_str());
  }
  return stats;
}

void SessionRun::failedOutput(const std::exception& e) {
  if (failure_.empty()) failure_ = e.what();
  halt_.store(true, std::memory_order_relaxed);
}

// Each output on its own: one failing does not skip the others' row of this step.
void SessionRun::afterStep(const sim::World& w) {
  if ((interrupt_ || options_.stop_on_held_interrupt) && interruptSignal() != 0) halt_.store(true, std::memory_order_relaxed);
  expect_->afterStep(w);
  const bool input = served_ && served_->afterStep(*world_);
  try {
    if (trace_) trace_->record(w);
    if (!forces_->empty()) forces_->record(w, dt_);
  } catch (const std::exception& e) {
    failedOutput(e);
  }
  takeContactSnapshots(w);
  try {
    if (frames_) frames_->afterStep(*world_, dt_, input);
  } catch (const std::exception& e) {
    failedOutput(e);
  }
}

void SessionRun::takeContactSnapshots(const sim::World& w) {
  while (!pending_.empty() && pending_.back() <= w.time() + 0.5 * dt_) {
    w.snapshot(contact_snaps_.emplace_back(pending_.back(), sim::Snapshot{}).second);
    try {
      if (closeups_) {
        renderer_->submitCloseUps(contact_snaps_.back().second,
                                  (dir_ / kContactsFolder / contactStem(pending_.back())).string());
      }
    } catch (const std::exception& e) {
      failedOutput(e);
    }
    pending_.pop_back();
  }
}

// Runs one output's finishing step; a failure is reported and kept, and the others go on.
template <class Write>
void SessionRun::finish(Write&& write) {
  try {
    write();
  } catch (const std::exception& e) {
    if (failure_ == e.what()) return;  // the failure that stopped the run, reported already
    // The same failure told in full when its file was closed (trace.csv: the rows it kept).
    if (!failure_.empty() && std::string_view(e.what()).starts_with(failure_)) failure_ = e.what();
    if (failure_.empty()) failure_ = e.what();
    std::fprintf(stderr, "%s: %s\n", scene_.name.c_str(), e.what());
  }
}

// Each output is finished on its own: one that fails does not cost the others. summary.json is
// last, so it can say what failed.
void SessionRun::finishOutputs(const sim::LoopStats& stats) {
  nlohmann::json served;
  if (served_) finish([&] { served = served_->finish(); });
  finishFiles(stats);
  nlohmann::json out = summary(stats);
  if (served_) out["serve"] = served;
  addRenderSummary(out);
  if (udp_) {  // what each device sent (its force faded out), and loud warnings when one sent nothing usable
    // A Ctrl-C that comes during the wait (a run that ended otherwise) ends it; after one that
    // stopped the run, a second ends the process.
    udp_->awaitFade(true, [stopped = interruptSignal() != 0] { return !stopped && interruptSignal() != 0; });
    out["udp_devices"] = udp_->json();
    for (const std::string& line : udp_->report()) std::fprintf(stderr, "%s: %s\n", scene_.name.c_str(), line.c_str());
    const std::vector<std::string> bound = udp_->bindWarnings(), silent = udp_->runWarnings();
    for (const std::string& w : silent) std::fprintf(stderr, "%s: warning: %s\n", scene_.name.c_str(), w.c_str());
    warnings_.insert(warnings_.end(), bound.begin(), bound.end());
    warnings_.insert(warnings_.end(), silent.begin(), silent.end());
  }
  if (!failure_.empty()) out["error"] = failure_;
  out["warnings"] = warnings_;
  finish([&] {
    writeFileAtomically((dir_ / kSummaryFile).string(), out.dump(2) + "\n");
    summary_written_ = true;
  });
  interrupt_.reset();
  if (failure_.empty()) return;
  char reached[160];
  std::snprintf(reached, sizeof reached, summary_written_ ? " (the outputs hold t = %.3f s)"
                                                          : " (summary.json could not be written either: t = %.3f s)",
                world_->time());
  throw std::runtime_error(failure_ + reached);
}

void SessionRun::finishFiles(const sim::LoopStats& stats) {
  // The frames are done: their GL memory is given back first, so the files written below (the
  // contact snapshots' JSON, the force chart's god-object rerun) take it rather than adding to
  // the run's peak.
  if (renderer_) finish([&] { renderer_->releaseFrames(); });
  if (trace_) {
    finish([&] { trace_->close(); });
    if (!trace_->sizeWarning().empty()) warnings_.push_back(trace_->sizeWarning());
  }
  finish([&] { forces_->close(); });
  for (const std::pair<double, sim::Snapshot>& snap : contact_snaps_) {  // (no structured binding: clang 14 lambdas)
    finish([&] {
      writeFileAtomically((dir_ / kContactsFolder / (contactStem(snap.first) + ".json")).string(),
                          contactsJson(snap.second, scene_).dump(1) + "\n");
    });
  }
  // The chart reruns the whole session with god-objects: not after a Ctrl-C or a failure.
  if (session_.record.force_chart && !stats.stopped) {
    finish([&] { writeForceChart(session_, *forces_, *renderer_, dir_ / kForceChartFile); });
  }
}

nlohmann::json SessionRun::summary(const sim::LoopStats& stats) {
  nlohmann::json out = summaryJson(session_, *world_, stats, options_.realtime);
  out["interrupted"] = interrupted_;
  out["time_reached_s"] = world_->time();
  if (interrupted_) out["signal"] = interruptSignal() == SIGTERM ? "SIGTERM" : "SIGINT";
  if (options_.cut_short) out["cut_short"] = true;
  failed_ = expect_->finish(*world_, !options_.cut_short);
  for (const ExpectFailure& f : failed_) std::fprintf(stderr, "%s: %s\n", scene_.name.c_str(), f.text().c_str());
  addExpectations(out, expect_->json(), failed_.size());
  out.update(provenanceJson(session_, options_.command_line));
  if (world_->counters().nan_recoveries > 0) {  // loud, whatever the scene expects
    std::fprintf(stderr, "%s: warning: %ld steps were not finite and were rolled back\n", scene_.name.c_str(),
                 world_->counters().nan_recoveries);
  }
  if (options_.expect_failures) *options_.expect_failures = failed_;
  if (options_.realtime) {
    out["realtime"] = realtimeJson(stats, options_.fifo);
    out["realtime"]["other_cpus"] = cpus_.others;
  }
  return out;
}

void SessionRun::addRenderSummary(nlohmann::json& out) {
  if (!renderer_) return;
  const long published = frames_ ? frames_->frames() : 0;
  finish([&] {
    render::RenderStats r;
    try {
      r = renderer_->finish();
    } catch (...) {
      out["render"] = {{"frames_published", published}};
      throw;
    }
    out["render"] = renderJson(std::move(r), published);
  });
  if (frames_) out["overlay_changes"] = changesJson(frames_->changes(), scene_);
}

}  // namespace

view::Camera sessionCamera(const SessionDesc& session, const std::string& name) {
  if (name.empty() && !session.cameras.empty()) return session.cameras.front();
  for (const view::Camera& c : session.cameras) {
    if (c.name == name) return c;
  }
  if (!name.empty()) {
    std::string known;
    for (const view::Camera& c : session.cameras) known.append(known.empty() ? "" : ", ").append(c.name);
    throw InputError(session.source, 0, 0, "cameras." + name,
                     "no such camera (the scene has: " + (known.empty() ? "none" : known) + ")");
  }
  view::Camera c;  // no camera in the scene: look at the origin from the front and above
  c.name = "default";
  return c;
}

render::FrameOutputSettings frameSettings(const SessionDesc& session, const SessionOptions& options) {
  const ViewSettings& v = session.view;
  render::FrameOutputSettings f;
  f.width = v.width;
  f.height = v.height;
  f.antialiasing = v.antialiasing;
  f.msaa_samples = v.msaa_samples;
  f.camera = sessionCamera(session, options.camera);
  if (options.frames) f.frames_dir = (fs::path(options.out_dir) / kFramesFolder).string();
  f.video_path = options.video_path;
  f.scene.shadows = v.shadows;
  f.scene.patch_highlight = v.patch_highlight;
  f.scene.load_arrows = v.load_arrows;
  f.top_left_taken = v.reserve_top_left;
  f.scene.body_pattern = v.body_pattern;
  f.scene.proxy = v.proxy;
  if (!session.targets.empty()) f.scene.targets = std::make_shared<const std::vector<view::Target>>(session.targets);
  f.patch_insets = v.patch_insets;
  f.overlay = v.overlay;
  f.overlay_settings.actions = v.actions;
  f.realtime = options.realtime;
  f.background_priority = options.realtime && options.yield_render;
  return f;
}

sim::LoopStats runSession(const SessionDesc& session, const SessionOptions& options) {
  SessionRun run(session, options);
  run.bindDevices();
  run.prepareOutputs();
  run.startThreads();
  const sim::LoopStats stats = run.loop();
  run.finishOutputs(stats);
  return stats;
}

}  // namespace gf::app

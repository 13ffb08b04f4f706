#include "app/session/session.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include <pthread.h>
#include <unistd.h>

#include "app/session/frame_driver.hpp"
#include "app/session/interrupt.hpp"
#include "godfinger_commit.hpp"
#include "app/runs/contacts.hpp"
#include "app/scene/scene_file.hpp"
#include "app/runs/trace.hpp"
#include "app/session/udp_device.hpp"
#include "app/session/expectations.hpp"
#include "sim/about.hpp"
#include "sim/mesh_import.hpp"
#include "sim/settings.hpp"
#include "sim/world.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

nlohmann::json fingerJson(const sim::FingerDesc& f) {
  nlohmann::json j = fingerSettingsJson(f, false);
  j["name"] = f.name;
  return j;
}

nlohmann::json effectsJson(const sim::EffectSet& e) {
  nlohmann::json out = nlohmann::json::object();
  for (const sim::EffectSwitch& s : sim::effectSwitches()) out[std::string(s.name)] = e.*s.on;
  return out;
}

// 64-bit FNV-1a of a file's bytes as 16 hex digits; empty when it cannot be read.
std::string fileHash(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return {};
  std::uint64_t h = 0xcbf29ce484222325ull;
  unsigned char buffer[65536];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ buffer[i]) * 0x100000001b3ull;
  }
  std::fclose(f);
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

std::string hostName() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string();
}

nlohmann::json summaryJson(const SessionDesc& session, const sim::World& world,
                           const sim::LoopStats& stats, bool realtime) {
  const sim::SceneDesc& scene = session.scene;
  nlohmann::json fingers = nlohmann::json::array();
  for (const sim::FingerDesc& f : scene.fingers) fingers.push_back(fingerJson(f));
  const sim::WorldCounters& c = world.counters();
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (scene.bodies[b].mass <= 0.0) continue;
    const sim::Vec3 inertia = world.bodyInertia(static_cast<int>(b));
    bodies.push_back({{"name", scene.bodies[b].name}, {"mass_kg", scene.bodies[b].mass},
                      {"inertia_kg_m2", {inertia.x(), inertia.y(), inertia.z()}}});
  }
  // Mesh bodies: the file's parts joined into the body (each node's mesh, its transform applied)
  // and what welding left.
  nlohmann::json meshes = nlohmann::json::array();
  for (const sim::BodyDesc& b : scene.bodies) {
    if (b.mesh_path.empty()) continue;
    nlohmann::json m = {{"body", b.name}, {"file", b.mesh_path}, {"scale", b.mesh_scale}};
    try {
      m["parts"] = sim::describeMeshFile(b.mesh_path).parts.size();
    } catch (const sim::MeshLoadError& e) {
      m["parts"] = nullptr;  // read when the scene loaded; gone or changed since
    }
    if (b.mesh) {
      m["vertices"] = b.mesh->vertexCount();
      m["faces"] = b.mesh->faceCount();
    }
    meshes.push_back(m);
  }
  return {{"scene", scene.name},
          {"source", session.source},
          {"overrides", session.overrides},
          {"clock", realtime ? "realtime" : "offline"},
          {"settings", sceneSettingsJson(scene)},
          {"effects", effectsJson(scene.effects)},
          {"fingers", fingers},
          {"bodies", bodies},
          {"meshes", meshes},
          {"step_time_us", {{"median", stats.step_median_us}, {"p99", stats.step_p99_us},
                            {"max", stats.step_max_us}}},
          {"interrupted", stats.stopped},
          {"counters", {{"steps", stats.steps}, {"deadline_misses", stats.late_steps},
                        {"max_lateness_us", stats.max_lateness_us},
                        {"fifo_priority", stats.fifo_priority},
                        {"nan_recoveries", c.nan_recoveries},
                        {"invalid_patches", c.invalid_patches}, {"sgos_injected", c.sgos_injected},
                        {"crossing_limit_stops", c.crossing_limit_stops},
                        {"tunnelling_stops", c.tunnelling_stops}}},
          {"patch_time_us", {{"calls", c.patch_calls},
                             {"mean", c.patch_calls > 0 ? 1e6 * c.patch_seconds / c.patch_calls : 0.0}}},
          {"wall_time_s", stats.wall_seconds},
          // When and where the steps ran, so a study can tell runs that shared a machine.
          {"finished_unix_s", std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count()},
          {"host", hostName()}};
}

// forces.csv: the force on each listed body other than gravity (N), from its change of velocity
// over the step: m (dv/dt - g). This is the paper's Fig. 8 curve for the pinched cylinder. The
// file is streamed while the run goes when `path` is given; the first body's y force is kept
// for the chart.
class ForceWriter {
 public:
  ForceWriter(const sim::World& world, const std::vector<std::string>& names, long rows, const std::string& path) {
    const sim::SceneDesc& d = world.desc();
    for (const std::string& n : names) {
      for (std::size_t b = 0; b < d.bodies.size(); ++b) {
        if (d.bodies[b].name != n) continue;
        bodies_.push_back(static_cast<int>(b));
        previous_.push_back(world.bodyLinearVelocity(static_cast<int>(b)));
      }
    }
    if (!path.empty() && !bodies_.empty()) {
      file_ = std::make_unique<StreamedFile>(path);
      std::string& text = file_->block();
      text.push_back('t');
      for (int b : bodies_) {
        for (const char* c : {".fx", ".fy", ".fz"}) text.append(1, ',').append(d.bodies[static_cast<std::size_t>(b)].name).append(c);
      }
      text += '\n';
      file_->rowDone();
    }
    gravity_ = d.effects.gravity ? d.world.gravity : sim::Vec3::Zero();
    times_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
    fy_.reserve(static_cast<std::size_t>(std::max(0L, rows)));
  }
  bool empty() const { return bodies_.empty(); }
  void record(const sim::World& world, double dt) {
    times_.push_back(world.time());
    std::string* text = file_ ? &file_->block() : nullptr;
    if (text) appendNumber(*text, world.time());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const sim::Vec3 v = world.bodyLinearVelocity(bodies_[i]);
      const sim::Vec3 f = world.desc().bodies[bodies_[i]].mass * ((v - previous_[i]) / dt - gravity_);
      previous_[i] = v;
      if (i == 0) fy_.push_back(f.y());
      if (!text) continue;
      for (double x : {f.x(), f.y(), f.z()}) {
        *text += ',';
        appendNumber(*text, x);
      }
    }
    if (!text) return;
    *text += '\n';
    file_->rowDone();
  }
  /// Writes the last rows and puts forces.csv in place.
  void close() {
    if (file_) file_->close();
  }
  /// The y force on the first body against time, as a chart curve.
  render::ChartSeries series(const std::string& label, const Eigen::Vector3f& colour) const {
    return {label, colour, times_, fy_};
  }

 private:
  std::unique_ptr<StreamedFile> file_;
  std::vector<int> bodies_;
  std::vector<sim::Vec3> previous_;
  std::vector<double> times_, fy_;
  sim::Vec3 gravity_ = sim::Vec3::Zero();
};

std::string contactFileName(double t) {
  char name[48];
  std::snprintf(name, sizeof name, "t%.3f", t);
  return name;
}

}  // namespace

std::string versionString() { return sim::libraryVersion(); }
std::string commitString() { return GF_GIT_COMMIT; }

sim::Camera sessionCamera(const SessionDesc& session, const std::string& name) {
  if (name.empty() && !session.cameras.empty()) return session.cameras.front();
  for (const sim::Camera& c : session.cameras) {
    if (c.name == name) return c;
  }
  if (!name.empty()) {
    std::string known;
    for (const sim::Camera& c : session.cameras) known.append(known.empty() ? "" : ", ").append(c.name);
    throw InputError(session.source, 0, 0, "cameras." + name,
                     "no such camera (the scene has: " + (known.empty() ? "none" : known) + ")");
  }
  sim::Camera c;  // no camera in the scene: look at the origin from the front and above
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
  if (options.frames) f.frames_dir = (fs::path(options.out_dir) / "frames").string();
  f.video_path = options.video_path;
  f.scene.shadows = v.shadows;
  f.scene.patch_highlight = v.patch_highlight;
  f.patch_insets = v.patch_insets;
  f.overlay = v.overlay;
  f.overlay_settings.actions = v.actions;
  f.realtime = options.realtime;
  f.background_priority = options.realtime && options.yield_render;
  return f;
}

namespace {

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
  return forces.series("god-object (n_SGO = 0)", {0.85f, 0.2f, 0.15f});
}

void writeForceChart(const SessionDesc& session, const ForceWriter& forces, render::RenderThread& renderer,
                     const fs::path& path) {
  render::ChartSpec chart;
  chart.title = !session.record.force_chart_title.empty()
                    ? session.record.force_chart_title
                    : session.scene.name + ": y force on " + session.record.force_bodies.front() + " (N, gravity removed)";
  chart.x_label = "time (s)";
  chart.y_label = "F_y (N)";
  chart.series.push_back(godObjectForces(session));
  int n = 0;
  for (const sim::FingerDesc& f : session.scene.fingers) n = std::max(n, f.patch.n_sgo);
  chart.series.push_back(forces.series("god-finger (n_SGO = " + std::to_string(n) + ")", {0.1f, 0.3f, 0.9f}));
  renderer.submitChart(chart, path.string());
}

// frames: drawn by the render thread; published: handed over by the haptic thread (realtime
// draws only the newest of those, so it can draw fewer).
nlohmann::json renderJson(render::RenderStats r, long published) {
  const auto fps = [](const render::SinkStats& s) { return s.busy_seconds > 0 ? s.frames / s.busy_seconds : 0.0; };
  const long frames = static_cast<long>(r.frame_ms.size());
  return {{"frames", frames},
          {"published", published},
          {"render_ms", {{"median", sim::percentile(r.frame_ms, 0.5)}, {"p99", sim::percentile(r.frame_ms, 0.99)}}},
          {"png", {{"frames", r.png.frames}, {"encode_fps", fps(r.png)}}},
          {"video", {{"frames", r.video.frames}, {"bytes", r.video.bytes}}},
          {"priority", r.background_priority ? "SCHED_IDLE" : "normal"},
          {"gl", r.gl}};
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

}  // namespace



namespace {

// True for the names of what a run writes into a folder of its own output kinds: the frame
// sequence (000000.png ...), contact snapshots and close-ups (t0.500.json, t0.500-left.png),
// and the temporary names they are written under.
std::string withoutTemporarySuffix(std::string name) {
  for (const char* suffix : {".part", ".tmp"}) {
    if (name.ends_with(suffix)) name.resize(name.size() - std::strlen(suffix));
  }
  return name;
}

bool isFrameName(const std::string& name) {
  const std::string stem = withoutTemporarySuffix(name);
  return stem.size() == 10 && stem.ends_with(".png") &&
         std::all_of(stem.begin(), stem.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
}

bool isContactName(const std::string& name) {
  const std::string stem = withoutTemporarySuffix(name);
  return stem.size() > 2 && stem[0] == 't' && stem[1] >= '0' && stem[1] <= '9' &&
         (stem.ends_with(".json") || stem.ends_with(".png"));
}

// Removes the files of `folder` whose names are `ours`, nothing else. Throws std::runtime_error
// naming a file it cannot remove.
void sweep(const fs::path& folder, bool (*ours)(const std::string&)) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return;
  std::vector<fs::path> doomed;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    if (e.is_regular_file(ec) && ours(e.path().filename().string())) doomed.push_back(e.path());
  }
  for (const fs::path& p : doomed) {
    if (!fs::remove(p, ec) && ec) throw std::runtime_error(p.string() + ": cannot remove an earlier run's file: " + ec.message());
  }
}

// A run owns its output folder: what an earlier run left of this run's kinds of output goes
// before anything is written, so the folder shows one run. Nothing else is touched.
void clearEarlierOutputs(const fs::path& dir) {
  std::error_code ec;
  for (const char* name : {"trace.csv", "forces.csv", "forces.png", "summary.json"}) {
    for (const char* suffix : {"", ".tmp", ".part"}) fs::remove(dir / (std::string(name) + suffix), ec);
  }
  sweep(dir / "frames", isFrameName);
  sweep(dir / "contacts", isContactName);
}

// While alive, SIGINT and SIGTERM are blocked on this thread, so the threads it starts meanwhile
// never take them (they stay with the haptic loop's thread, which waits for them).
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t both;
    sigemptyset(&both);
    sigaddset(&both, SIGINT);
    sigaddset(&both, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &both, &old_);
  }
  ~SignalsBlocked() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_{};
};

// Bodies overlapping by more than this at the start (m) are reported.
constexpr double kStartOverlap = 1e-3;

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

}  // namespace

void requireWritableFolder(const fs::path& folder, const std::string& what) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec || !fs::is_directory(folder)) {
    throw std::runtime_error(folder.string() + ": cannot create the folder for " + what +
                             (ec ? ": " + ec.message() : ": a file is in the way"));
  }
  const fs::path probe = folder / (".godfinger-probe-" + std::to_string(getpid()));
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f) throw std::runtime_error(folder.string() + ": cannot write " + what + " there: " + std::strerror(errno));
  std::fclose(f);
  fs::remove(probe, ec);
}

void prepareOutputs(const SessionOptions& options) {
  const fs::path dir(options.out_dir);
  requireWritableFolder(dir, "the run's outputs");
  requireWritableFolder(dir / "contacts", "contact snapshots");
  if (options.frames) requireWritableFolder(dir / "frames", "frames");
  if (!options.video_path.empty()) requireVideoPath(options.video_path);
}

void clearFrames(const fs::path& folder) { sweep(folder, isFrameName); }

void requireVideoPath(const std::string& path) {
  const fs::path video(path);
  std::error_code ec;
  if (fs::is_directory(video, ec)) throw std::runtime_error(path + " is a folder; give a file such as out.mp4");
  std::string ext = video.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".mp4" && ext != ".mkv" && ext != ".mov") {
    throw std::runtime_error(path + ": the video's name must end in .mp4, .mkv or .mov");
  }
  requireWritableFolder(video.parent_path().empty() ? fs::path(".") : video.parent_path(), "the video");
}

sim::LoopStats runSession(const SessionDesc& session, const SessionOptions& options) {
  const sim::SceneDesc& scene = session.scene;
  const fs::path dir(options.out_dir);
  // A live device's packets arrive in wall-clock time: it needs the realtime clock.
  if (!session.udp_devices.empty() && !options.realtime) {
    const UdpDeviceDesc& d = session.udp_devices.front();
    throw InputError(d.file, d.line, d.column,
                     "fingers." + scene.fingers[static_cast<std::size_t>(d.finger)].name + ".device.udp",
                     "a UDP device drives the session in real time: run it with --realtime");
  }
  // Live devices: their sockets are bound before anything else (a port in use fails the run
  // here, with nothing written).
  std::optional<UdpDeviceBridge> udp;
  if (!session.udp_devices.empty()) {
    udp.emplace(session);
    for (const UdpDeviceDesc& d : session.udp_devices) {
      const std::string& name = scene.fingers[static_cast<std::size_t>(d.finger)].name;
      std::fprintf(stderr, "%s: fingers.%s.device: listening on %s, channel %d\n", scene.name.c_str(), name.c_str(),
                   udp->address(d.finger).c_str(), d.channel);
    }
  }
  // Ctrl-C and SIGTERM are recorded from here on (the outputs are finished when one comes); the
  // threads started below (writers, the render thread, its encoders) do not take them.
  std::optional<InterruptScope> interrupt;
  if (options.stop_on_interrupt) interrupt.emplace();
  std::optional<SignalsBlocked> quiet_threads(std::in_place);
  prepareOutputs(options);
  // Requests this run cannot carry out but that do not make it useless: said on stderr now and
  // listed in summary.json.
  std::vector<std::string> warnings;
  for (double t : session.record.contact_times) {
    if (t > scene.duration + 0.5 / scene.world.haptic_rate_hz) {
      char text[160];
      std::snprintf(text, sizeof text, "record.contacts: %g s is past the run's duration (%g s): no snapshot then", t,
                    scene.duration);
      warnings.emplace_back(text);
    }
  }
  if (!options.camera.empty() && !options.frames && options.video_path.empty()) {
    warnings.push_back("--camera " + options.camera + ": no --frames or --video, so nothing is drawn with it");
  }
  sim::World world(scene);
  for (const sim::World::Overlap& o : world.bodyOverlaps(kStartOverlap)) {
    char text[256];
    std::snprintf(text, sizeof text, "bodies.%s and bodies.%s start %.1f mm inside each other: the solver will push them apart",
                  scene.bodies[static_cast<std::size_t>(o.body_a)].name.c_str(),
                  scene.bodies[static_cast<std::size_t>(o.body_b)].name.c_str(), 1e3 * o.depth);
    warnings.emplace_back(text);
  }
  for (const std::string& w : warnings) std::fprintf(stderr, "%s: warning: %s\n", scene.name.c_str(), w.c_str());
  const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(scene);
  const double rate = scene.world.haptic_rate_hz, dt = 1.0 / rate;
  const long steps = sim::stepCount(scene.duration, rate);
  std::vector<double> pending = session.record.contact_times;
  std::sort(pending.begin(), pending.end(), std::greater<>());  // next time at the back
  std::vector<std::pair<double, sim::Snapshot>> contact_snaps;  // serialised after the run
  // The render thread: frames, close-ups and charts.
  const bool stream = options.frames || !options.video_path.empty();
  const bool closeups = options.close_ups && !pending.empty();
  std::unique_ptr<render::RenderThread> renderer;
  if (stream || closeups || session.record.force_chart) {
    render::FrameOutputSettings fo = frameSettings(session, options);
    if (!stream) fo.overlay = fo.patch_insets = false;
    renderer = std::make_unique<render::RenderThread>(scene, fo);
  }
  // Everything that can fail before the first step has: what an earlier run left of this run's
  // outputs goes now, then the files are opened.
  clearEarlierOutputs(dir);
  std::optional<TraceWriter> trace;
  if (session.record.trace) trace.emplace(world, (dir / "trace.csv").string());
  ForceWriter forces(world, session.record.force_bodies, steps, (dir / "forces.csv").string());
  sim::LiveTimings live;
  std::unique_ptr<FrameDriver> frames;
  if (stream) frames = std::make_unique<FrameDriver>(*renderer, 60.0, options.realtime, session.view.actions, &live);
  long done = 0;
  sim::LoopSettings loop{rate, scene.duration,
                         options.realtime ? sim::ClockMode::kRealtime : sim::ClockMode::kOffline};
  loop.live = &live;
  loop.fifo = options.fifo;
  loop.spin_us = options.spin_us;
  if (udp) loop.sources = udp->sources();
  if (frames) frames->start(world);
  ExpectChecker expect(session.expect, world);
  quiet_threads.reset();  // this thread takes the signals again
  // The loop stops before its next step on a signal or when an output fails (a full disk, a
  // dead ffmpeg): the run then writes what it reached and reports the failure.
  std::atomic<bool> halt{false};
  loop.stop = &halt;
  std::string failure;
  const auto failed_output = [&](const std::exception& e) {
    if (failure.empty()) failure = e.what();
    halt.store(true, std::memory_order_relaxed);
  };
  Progress progress(scene.name, scene.duration, steps, options.progress);
  const sim::LoopStats stats = sim::runHapticLoop(world, devices, loop, [&](const sim::World& w) {
    if (interrupt && interruptSignal() != 0) halt.store(true, std::memory_order_relaxed);
    expect.afterStep(w);
    try {  // each output on its own: one failing does not skip the others' row of this step
      if (trace) trace->record(w);
      if (!forces.empty()) forces.record(w, dt);
    } catch (const std::exception& e) {
      failed_output(e);
    }
    while (!pending.empty() && pending.back() <= w.time() + 0.5 * dt) {
      w.snapshot(contact_snaps.emplace_back(pending.back(), sim::Snapshot{}).second);
      try {
        if (closeups) renderer->submitCloseUps(contact_snaps.back().second,
                                               (dir / "contacts" / contactFileName(pending.back())).string());
      } catch (const std::exception& e) {
        failed_output(e);
      }
      pending.pop_back();
    }
    try {
      if (frames) frames->afterStep(world, dt);
    } catch (const std::exception& e) {
      failed_output(e);
    }
    progress.step(w.time(), ++done);
  });
  progress.finish();
  const bool interrupted = stats.stopped && failure.empty();
  if (interrupted) {
    std::fprintf(stderr, "%s: interrupted at t = %.3f s; writing the outputs of the time reached\n",
                 scene.name.c_str(), world.time());
  } else if (!failure.empty()) {
    std::fprintf(stderr, "%s: stopped at t = %.3f s: %s; writing the outputs of the time reached\n",
                 scene.name.c_str(), world.time(), failure.c_str());
  }
  // Each output is finished on its own: one that fails does not cost the others.
  const auto finish = [&](auto&& write) {
    try {
      write();
    } catch (const std::exception& e) {
      if (failure == e.what()) return;  // the failure that stopped the run, reported above
      if (failure.empty()) failure = e.what();
      std::fprintf(stderr, "%s: %s\n", scene.name.c_str(), e.what());
    }
  };
  if (trace) finish([&] { trace->close(); });
  finish([&] { forces.close(); });
  for (const std::pair<double, sim::Snapshot>& snap : contact_snaps) {  // (no structured binding: clang 14 lambdas)
    finish([&] {
      writeFileAtomically((dir / "contacts" / (contactFileName(snap.first) + ".json")).string(),
                          contactsJson(snap.second, scene).dump(1) + "\n");
    });
  }
  // The chart reruns the whole session with god-objects: not after a Ctrl-C or a failure.
  if (session.record.force_chart && !stats.stopped) {
    finish([&] { writeForceChart(session, forces, *renderer, dir / "forces.png"); });
  }
  nlohmann::json summary = summaryJson(session, world, stats, options.realtime);
  summary["interrupted"] = interrupted;
  summary["time_reached_s"] = world.time();
  if (interrupted) summary["signal"] = interruptSignal() == SIGTERM ? "SIGTERM" : "SIGINT";
  const std::vector<ExpectFailure> failed = expect.finish(world);
  for (const ExpectFailure& f : failed) std::fprintf(stderr, "%s: %s\n", scene.name.c_str(), f.text().c_str());
  const nlohmann::json checks = expect.json();
  summary["expectations"] = {{"checks", checks}, {"failed", failed.size()}};
  // What made this result: the build, the command, the scene file's bytes, and the scene's
  // headline measures (its checks' measured values) at the top for a quick look.
  summary["godfinger"] = {{"version", versionString()}, {"commit", commitString()}};
  summary["command_line"] = options.command_line;
  summary["scene_file_fnv1a64"] = fileHash(session.source);
  nlohmann::json measures = nlohmann::json::object();
  for (const nlohmann::json& c : checks) {
    if (c["checked"].get<bool>()) measures[c["name"].get<std::string>()] = c["worst"];
  }
  summary["measures"] = measures;
  if (world.counters().nan_recoveries > 0) {  // loud, whatever the scene expects
    std::fprintf(stderr, "%s: warning: %ld steps were not finite and were rolled back\n", scene.name.c_str(),
                 world.counters().nan_recoveries);
  }
  if (options.expect_failures) *options.expect_failures = failed;
  if (options.realtime) {
    // How the deadlines were kept: the haptic thread's policy, the wake-up, the share late.
    summary["realtime"] = {{"haptic_priority", stats.fifo_priority ? "SCHED_FIFO" : "normal"},
                           {"fifo_requested", options.fifo},
                           {"spin_us", stats.spin_us},
                           {"late_steps", stats.late_steps},
                           {"late_percent", stats.steps > 0 ? 100.0 * stats.late_steps / stats.steps : 0.0},
                           {"max_lateness_us", stats.max_lateness_us},
                           {"late_per_second", stats.late_per_second}};
  }
  if (renderer) {
    finish([&] {
      render::RenderStats r;
      try {
        r = renderer->finish();
      } catch (...) {
        summary["render"] = {{"frames_published", frames ? frames->frames() : 0}};
        throw;
      }
      summary["render"] = renderJson(std::move(r), frames ? frames->frames() : 0);
    });
    if (frames) summary["overlay_changes"] = changesJson(frames->changes(), scene);
  }
  if (udp) summary["udp_devices"] = udp->json();
  if (!failure.empty()) summary["error"] = failure;
  summary["warnings"] = warnings;
  finish([&] { writeFileAtomically((dir / "summary.json").string(), summary.dump(2) + "\n"); });
  interrupt.reset();
  if (!failure.empty()) throw std::runtime_error(failure + " (the outputs hold t = " + std::to_string(world.time()) + " s)");
  return stats;
}

}  // namespace gf::app

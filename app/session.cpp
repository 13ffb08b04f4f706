#include "app/session.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <unistd.h>

#include "app/frame_driver.hpp"
#include "app/patch_json.hpp"
#include "app/scene_file.hpp"
#include "app/trace_writer.hpp"
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
  return {{"scene", scene.name},
          {"source", session.source},
          {"overrides", session.overrides},
          {"clock", realtime ? "realtime" : "offline"},
          {"settings", sceneSettingsJson(scene)},
          {"effects", effectsJson(scene.effects)},
          {"fingers", fingers},
          {"bodies", bodies},
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

render::Camera sessionCamera(const SessionDesc& session, const std::string& name) {
  if (name.empty() && !session.cameras.empty()) return session.cameras.front();
  for (const CameraDesc& c : session.cameras) {
    if (c.name == name) return c;
  }
  if (!name.empty()) {
    std::string known;
    for (const CameraDesc& c : session.cameras) known.append(known.empty() ? "" : ", ").append(c.name);
    throw InputError(session.source, 0, 0, "cameras." + name,
                     "no such camera (the scene has: " + (known.empty() ? "none" : known) + ")");
  }
  render::Camera c;  // no camera in the scene: look at the origin from the front and above
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
  chart.title = session.scene.name + ": y force on " + session.record.force_bodies.front() +
                " (N, gravity removed) - paper Fig. 8";
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

// Ctrl-C (SIGINT) or SIGTERM during a run: the haptic loop stops before its next step and the
// run writes its outputs for the time it reached, marked interrupted. The handler is installed
// for the loop only and resets itself, so a second Ctrl-C ends the process at once.
std::atomic<bool> g_interrupt{false};

extern "C" void onInterrupt(int) { g_interrupt.store(true, std::memory_order_relaxed); }

class InterruptScope {
 public:
  InterruptScope() {
    g_interrupt.store(false);
    struct sigaction a {};
    a.sa_handler = onInterrupt;
    a.sa_flags = SA_RESETHAND;
    sigemptyset(&a.sa_mask);
    sigaction(SIGINT, &a, &old_int_);
    sigaction(SIGTERM, &a, &old_term_);
  }
  ~InterruptScope() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {};
};

sim::LoopStats runSession(const SessionDesc& session, const SessionOptions& options) {
  const sim::SceneDesc& scene = session.scene;
  const fs::path dir(options.out_dir);
  std::error_code ec;
  fs::create_directories(dir / "contacts", ec);
  if (ec) throw std::runtime_error(options.out_dir + ": cannot create folder: " + ec.message());
  sim::World world(scene);
  const std::vector<sim::DeviceTrack> devices = sim::deviceTracks(scene);
  const double rate = scene.world.haptic_rate_hz, dt = 1.0 / rate;
  const long steps = sim::stepCount(scene.duration, rate);
  std::optional<TraceWriter> trace;
  if (session.record.trace) trace.emplace(world, (dir / "trace.csv").string());
  ForceWriter forces(world, session.record.force_bodies, steps, (dir / "forces.csv").string());
  std::vector<double> pending = session.record.contact_times;
  std::sort(pending.begin(), pending.end(), std::greater<>());  // next time at the back
  std::vector<std::pair<double, sim::Snapshot>> contact_snaps;  // serialised after the run
  // The render thread: frames, close-ups and charts.
  const bool stream = options.frames || !options.video_path.empty();
  const bool closeups = options.close_ups && !pending.empty();
  std::unique_ptr<render::RenderThread> renderer;
  if (stream || closeups || session.record.force_chart) {
    render::FrameOutputSettings fo = frameSettings(session, options);
    if (!stream) fo.overlay = false;
    renderer = std::make_unique<render::RenderThread>(scene, fo);
  }
  sim::LiveTimings live;
  std::unique_ptr<FrameDriver> frames;
  if (stream) frames = std::make_unique<FrameDriver>(*renderer, 60.0, options.realtime, session.view.actions, &live);
  const long report_every = std::max(1L, static_cast<long>(rate));  // once per simulated second
  const auto start = std::chrono::steady_clock::now();
  long done = 0;
  sim::LoopSettings loop{rate, scene.duration,
                         options.realtime ? sim::ClockMode::kRealtime : sim::ClockMode::kOffline};
  loop.live = &live;
  loop.fifo = options.fifo;
  loop.spin_us = options.spin_us;
  if (frames) frames->start(world);
  ExpectChecker expect(session.expect, world);
  std::optional<InterruptScope> interrupt;
  if (options.stop_on_interrupt) {
    interrupt.emplace();
    loop.stop = &g_interrupt;
  }
  const sim::LoopStats stats = sim::runHapticLoop(world, devices, loop, [&](const sim::World& w) {
    expect.afterStep(w);
    if (trace) trace->record(w);
    if (!forces.empty()) forces.record(w, dt);
    if (frames) frames->afterStep(world, dt);
    while (!pending.empty() && pending.back() <= w.time() + 0.5 * dt) {
      w.snapshot(contact_snaps.emplace_back(pending.back(), sim::Snapshot{}).second);
      if (closeups) renderer->submitCloseUps(contact_snaps.back().second,
                                             (dir / "contacts" / contactFileName(pending.back())).string());
      pending.pop_back();
    }
    if (options.progress && ++done % report_every == 0) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "\r[godfinger] %s: t = %.1f / %.1f s, %ld / %ld steps, ETA %.1f s ",
                   scene.name.c_str(), w.time(), scene.duration, done, steps,
                   wall / done * (steps - done));
    }
  });
  interrupt.reset();
  if (options.progress) std::fprintf(stderr, "\n");
  if (stats.stopped) {
    std::fprintf(stderr, "%s: interrupted at t = %.3f s; writing the outputs of the time reached\n",
                 scene.name.c_str(), world.time());
  }
  if (trace) trace->close();
  forces.close();
  for (const auto& [t, snap] : contact_snaps) {
    writeFileAtomically((dir / "contacts" / (contactFileName(t) + ".json")).string(),
                        contactsJson(snap, scene).dump(1) + "\n");
  }
  // The chart reruns the whole session with god-objects: not after a Ctrl-C.
  if (session.record.force_chart && !stats.stopped) writeForceChart(session, forces, *renderer, dir / "forces.png");
  nlohmann::json summary = summaryJson(session, world, stats, options.realtime);
  const std::vector<ExpectFailure> failed = expect.finish(world);
  for (const ExpectFailure& f : failed) std::fprintf(stderr, "%s: %s\n", scene.name.c_str(), f.text().c_str());
  summary["expectations"] = {{"checks", expect.json()}, {"failed", failed.size()}};
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
    summary["render"] = renderJson(renderer->finish(), frames ? frames->frames() : 0);
    if (frames) summary["overlay_changes"] = changesJson(frames->changes(), scene);
  }
  writeFileAtomically((dir / "summary.json").string(), summary.dump(2) + "\n");
  return stats;
}

}  // namespace gf::app

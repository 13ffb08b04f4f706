#include "app/runs/summary.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>

#include <unistd.h>

#include "app/runs/contacts.hpp"
#include "app/runs/files.hpp"
#include "godfinger_commit.hpp"
#include "sim/about.hpp"
#include "sim/mesh/mesh_import.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

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

}  // namespace

nlohmann::json summaryJson(const SessionDesc& session, const sim::World& world, const sim::LoopStats& stats,
                           bool realtime) {
  const sim::SceneDesc& scene = session.scene;
  nlohmann::json fingers = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.fingers.size(); ++i) {
    nlohmann::json j = fingerJson(scene.fingers[i]);
    // The device port's passivity observer at the end and its lowest; the device's jumps apart.
    const sim::PortObserver& port = world.portObserver(static_cast<int>(i));
    j["port"] = {{"energy_j", port.energy}, {"min_energy_j", port.min_energy}, {"jumps", port.jumps},
                 {"jump_energy_j", port.jump_energy}};
    fingers.push_back(j);
  }
  const sim::WorldCounters& c = world.counters();
  nlohmann::json overlaps = nlohmann::json::array();  // docs/overlap.md
  for (int k = 0; k < world.overlapPairCount(); ++k) {
    const sim::OverlapStats o = world.overlap(k);
    overlaps.push_back({{"fingers", {scene.fingers[static_cast<std::size_t>(o.finger_a)].name,
                                     scene.fingers[static_cast<std::size_t>(o.finger_b)].name}},
                        {"peak_mm2", o.peak * 1e6},
                        {"integral_mm2_s", o.integral * 1e6}});
  }
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
          {"overlap", overlaps},
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
                        {"tunnelling_stops", c.tunnelling_stops},
                        {"pad_resets", c.pad_resets},
                        {"soft_resets", c.soft_resets}}},
          {"patch_time_us", {{"calls", c.patch_calls},
                             {"mean", c.patch_calls > 0 ? 1e6 * c.patch_seconds / c.patch_calls : 0.0}}},
          {"wall_time_s", stats.wall_seconds},
          // When and where the steps ran, so a study can tell runs that shared a machine.
          {"finished_unix_s", std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count()},
          {"host", hostName()}};
}

// frames: drawn by the render thread; published: handed over by the haptic thread (realtime
// with a viewer draws only the newest of those, so it can draw fewer; realtime to files draws
// them all, in order, but those published to a full queue, `dropped`).
nlohmann::json renderJson(render::RenderStats r, long published) {
  const auto fps = [](const render::SinkStats& s) { return s.busy_seconds > 0 ? s.frames / s.busy_seconds : 0.0; };
  const long frames = static_cast<long>(r.frame_ms.size());
  return {{"frames", frames},
          {"published", published},
          {"pictures_reused", r.pictures_reused},
          {"hurried", r.hurried},
          {"queue", {{"dropped", r.dropped}, {"most_waiting", r.queue_max}, {"drawn_after_end", r.drawn_after_end}}},
          {"render_ms", {{"median", sim::percentile(r.frame_ms, 0.5)}, {"p99", sim::percentile(r.frame_ms, 0.99)}}},
          {"png", {{"frames", r.png.frames}, {"encode_fps", fps(r.png)}, {"repeated", r.png.repeated},
                   {"banded", r.png.banded}, {"bands_compressed", r.png.bands_compressed}}},
          {"video", {{"frames", r.video.frames}, {"bytes", r.video.bytes}}},
          {"priority", r.background_priority ? "nice " + std::to_string(render::kBackgroundNice) : std::string("normal")},
          {"gl", r.gl}};
}

std::string versionString() { return sim::libraryVersion(); }
std::string commitString() { return GF_GIT_COMMIT; }

namespace {

// A histogram as {"upper_us": [edges..., null], "counts": [...]}: the last bin is open.
nlohmann::json histogramJson(const sim::LatencyHistogram& h) {
  nlohmann::json upper(sim::LatencyHistogram::kEdgesUs);
  upper.push_back(nullptr);
  return {{"upper_us", upper}, {"counts", h.counts}};
}

}  // namespace

nlohmann::json sleeperJson(const sim::SleeperStats& s) {
  return {{"wakeups", s.wakeups},
          {"late", s.late},
          {"late_percent", s.late_percent()},
          {"late_us", {{"p50", s.p50_us}, {"p99", s.p99_us}, {"p999", s.p999_us}, {"max", s.max_late_us}}},
          {"histogram", histogramJson(s.histogram)}};
}

nlohmann::json realtimeJson(const sim::LoopStats& stats, bool fifo_requested) {
  nlohmann::json late = nlohmann::json::array();
  for (const sim::LateStep& l : stats.first_late) {
    late.push_back({{"t", l.t}, {"late_us", l.late_us}, {"cause", l.cause},
                    {"before_step_us", l.before_step_us}, {"before_work_us", l.before_work_us},
                    {"faults", l.faults}, {"preemptions", l.preemptions}});
  }
  return {{"haptic_priority", stats.fifo_priority ? "SCHED_FIFO" : "normal"},
          {"fifo_requested", fifo_requested},
          {"spin_us", stats.spin_us},
          {"memory", stats.memory},
          {"late_steps", stats.late_steps},
          {"late_percent", stats.steps > 0 ? 100.0 * stats.late_steps / stats.steps : 0.0},
          {"max_lateness_us", stats.max_lateness_us},
          {"late_per_second", stats.late_per_second},
          {"short_slice", stats.short_slice},
          {"cpu", stats.cpu >= 0 ? nlohmann::json(stats.cpu) : nlohmann::json()},
          {"late_causes", {{"woke_late", stats.late_woke}, {"overran", stats.late_overran},
                           {"catching_up", stats.late_catching_up}}},
          {"lateness_us", {{"p50", stats.late_p50_us}, {"p99", stats.late_p99_us}, {"p999", stats.late_p999_us},
                           {"max", stats.max_lateness_us}}},
          {"histograms", {{"lateness", histogramJson(stats.late_histogram)},
                          {"step", histogramJson(stats.step_histogram)},
                          {"work", histogramJson(stats.work_histogram)}}},
          {"haptic_thread", {{"minor_faults", stats.minor_faults}, {"major_faults", stats.major_faults},
                             {"preemptions", stats.preemptions}}},
          {"first_late_steps", late}};
}

nlohmann::json provenanceJson(const SessionDesc& session, const std::vector<std::string>& command_line) {
  return {{"godfinger", {{"version", versionString()}, {"commit", commitString()}}},
          {"command_line", command_line},
          {"scene_file_fnv1a64", fileFnv1a64(session.source)}};
}

void addExpectations(nlohmann::json& summary, const nlohmann::json& checks, std::size_t failed) {
  summary["expectations"] = {{"checks", checks}, {"failed", failed}};
  nlohmann::json measures = nlohmann::json::object();
  for (const nlohmann::json& c : checks) {
    if (c["checked"].get<bool>()) measures[c["name"].get<std::string>()] = c["worst"];
  }
  summary["measures"] = measures;
}

}  // namespace gf::app

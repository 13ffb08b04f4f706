#include "app/session.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/trace_writer.hpp"
#include "sim/world.hpp"

namespace gf::app {
namespace {

nlohmann::json fingerJson(const sim::FingerDesc& f) {
  const sim::PatchSettings& p = f.patch;
  return {{"name", f.name},
          {"n_sgo", p.n_sgo},
          {"r_max_m", p.r_max},
          {"d0_m", p.d0},
          {"alpha", p.alpha},
          {"stretch_length_m", p.stretch_length},
          {"tau_a_rad", p.tau_a},
          {"friction", p.friction},
          {"coupling_stiffness_n_per_m", f.coupling.stiffness},
          {"coupling_damping_ns_per_m", f.coupling.damping},
          {"proxy_radius_m", f.proxy.radius},
          {"proxy_mass_kg", f.proxy.mass},
          {"contact_stiffness_n_per_m", f.proxy.contact_stiffness},
          {"contact_damping_ns_per_m", f.proxy.contact_damping}};
}

nlohmann::json summaryJson(const sim::SceneDesc& scene, const sim::World& world,
                           const sim::LoopStats& stats, bool realtime) {
  nlohmann::json fingers = nlohmann::json::array();
  for (const sim::FingerDesc& f : scene.fingers) fingers.push_back(fingerJson(f));
  const sim::EffectSet& e = scene.effects;
  const sim::WorldCounters& c = world.counters();
  return {{"scene", scene.name},
          {"clock", realtime ? "realtime" : "offline"},
          {"duration_s", scene.duration},
          {"haptic_rate_hz", scene.world.haptic_rate_hz},
          {"solver_iterations", scene.world.solver_iterations},
          {"effects", {{"gravity", e.gravity}, {"friction", e.friction}, {"god_finger", e.god_finger},
                       {"tangential_stretch", e.tangential_stretch},
                       {"angular_threshold", e.angular_threshold}, {"friction_cone", e.friction_cone},
                       {"force_feedback", e.force_feedback}}},
          {"fingers", fingers},
          {"step_time_us", {{"median", stats.step_median_us}, {"p99", stats.step_p99_us},
                            {"max", stats.step_max_us}}},
          {"counters", {{"steps", stats.steps}, {"deadline_misses", stats.late_steps},
                        {"max_lateness_us", stats.max_lateness_us},
                        {"nan_recoveries", c.nan_recoveries},
                        {"invalid_patches", c.invalid_patches}, {"sgos_injected", c.sgos_injected}}},
          {"wall_time_s", stats.wall_seconds}};
}

}  // namespace

sim::LoopStats runSession(const sim::SceneDesc& scene, const SessionOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) throw std::runtime_error(options.out_dir + ": cannot create folder: " + ec.message());
  sim::World world(scene);
  std::vector<sim::DeviceTrack> devices;
  for (const sim::FingerDesc& f : scene.fingers) devices.push_back(f.device);
  const double rate = scene.world.haptic_rate_hz;
  const long steps = sim::stepCount(scene.duration, rate);
  TraceWriter trace(world, steps);
  const long report_every = std::max(1L, static_cast<long>(rate));  // once per simulated second
  const auto start = std::chrono::steady_clock::now();
  long done = 0;
  sim::LoopSettings loop{rate, scene.duration,
                         options.realtime ? sim::ClockMode::kRealtime : sim::ClockMode::kOffline};
  const sim::LoopStats stats = sim::runHapticLoop(world, devices, loop, [&](const sim::World& w) {
    trace.record(w);
    if (options.progress && ++done % report_every == 0) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "\r[godfinger] %s: t = %.1f / %.1f s, %ld / %ld steps, ETA %.1f s ",
                   scene.name.c_str(), w.time(), scene.duration, done, steps,
                   wall / done * (steps - done));
    }
  });
  if (options.progress) std::fprintf(stderr, "\n");
  const std::filesystem::path dir(options.out_dir);
  trace.save((dir / "trace.csv").string());
  writeFileAtomically((dir / "summary.json").string(),
                      summaryJson(scene, world, stats, options.realtime).dump(2) + "\n");
  return stats;
}

}  // namespace gf::app

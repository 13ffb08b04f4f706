// Haptic deadlines beside the renderer: a realtime Fig. 8 session (5 s, PNG frames at 1280x720)
// as a user without root or CAP_SYS_NICE runs it (no SCHED_FIFO, whoever runs the benchmark)
// and, for comparison, with SCHED_FIFO when the user may have it. Args: fifo (0, 1), the
// haptic loop's spin before each deadline (us: 0 sleeps to it, 1000 never sleeps) and whether
// the renderer yields (nice 10, 1) or runs at normal priority (0). Counters: late steps
// (> 0.5 ms), the worst lateness, frames drawn per second, whether SCHED_FIFO was granted, and
// the same machine's floor measured just before: a bare 1 kHz sleeper's late share and worst
// wake-up (sim::runSleeper, what cyclictest measures), at the benchmark's own priority.
// Wall-clock only: run by hand, never by ctest.
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "sim/loop/realtime.hpp"

namespace {

using namespace gf;

void BM_RealtimeDeadlines(benchmark::State& state) {
  app::SessionDesc session = app::loadSceneFile(app::resolveScenePath("fig8-pinch-oscillation"));
  session.scene.duration = 5.0;
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "gf_bench_realtime";
  app::SessionOptions options;
  options.out_dir = out.string();
  options.realtime = true;
  options.progress = false;
  options.frames = true;
  options.fifo = state.range(0) == 1;
  options.spin_us = static_cast<double>(state.range(1));
  options.yield_render = state.range(2) == 1;
  double late = 0, worst = 0, fps = 0, fifo = 0, floor = 0, floor_worst = 0;
  for (auto _ : state) {
    // The machine's floor first: a bare 1 kHz sleeper at the same priority (cyclictest's measure).
    const sim::SleeperStats sleeper = sim::runSleeper(1000.0, session.scene.duration, sim::LoopSettings{}.late_threshold);
    floor = sleeper.late_percent();
    floor_worst = sleeper.max_late_us;
    std::filesystem::remove_all(out);
    const sim::LoopStats stats = app::runSession(session, options);
    std::ifstream in(out / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(in);
    late = 100.0 * static_cast<double>(stats.late_steps) / static_cast<double>(std::max(1L, stats.steps));
    worst = stats.max_lateness_us;
    fps = summary["render"]["frames"].get<double>() / stats.wall_seconds;
    fifo = stats.fifo_priority ? 1 : 0;
  }
  state.counters["late_percent"] = late;
  state.counters["sleeper_late_percent"] = floor;
  state.counters["sleeper_worst_late_us"] = floor_worst;
  state.counters["worst_late_us"] = worst;
  state.counters["frames_per_s"] = fps;
  state.counters["fifo_granted"] = fifo;
}
BENCHMARK(BM_RealtimeDeadlines)
    ->ArgsProduct({{0, 1}, {0, 1000}, {1}})
    ->Args({0, 0, 0})
    ->ArgNames({"fifo", "spin_us", "yield"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace

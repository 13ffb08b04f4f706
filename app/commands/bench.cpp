// `godfinger bench realtime [SCENE]`: how punctual the haptic loop is on this machine, beside the
// machine's own floor. Each round runs a bare periodic sleeper (what cyclictest measures: an
// ordinary thread that only sleeps to absolute 1 ms deadlines) and then the scene's realtime
// session with frames, at the same priority, optionally with busy threads keeping the cores
// loaded; the late shares of both are printed side by side and written as JSON.
#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "app/commands/commands.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/files.hpp"
#include "app/runs/run_reader.hpp"
#include "app/runs/summary.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"
#include "app/process/interrupt.hpp"
#include "app/session/session.hpp"
#include "sim/loop/realtime.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// `count` threads spinning at normal priority while alive: the ordinary load a desktop or a
// shared server puts beside the loop.
class BusyThreads {
 public:
  explicit BusyThreads(int count) {
    for (int i = 0; i < count; ++i) {
      threads_.emplace_back([this] {
        volatile unsigned long spin = 0;
        while (!stop_.load(std::memory_order_relaxed)) spin = spin + 1;
      });
    }
  }
  ~BusyThreads() {
    stop_.store(true);
    for (std::thread& t : threads_) t.join();
  }
  BusyThreads(const BusyThreads&) = delete;
  BusyThreads& operator=(const BusyThreads&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

class BenchCommand final : public Command {
 public:
  explicit BenchCommand(const std::vector<std::string>& argv) : command_line_(argv) {}

  CLI::App* add(CLI::App& app) override {
    CLI::App* bench = app.add_subcommand("bench", "Measure this machine: bench realtime");
    bench->require_subcommand(1);
    realtime_ = bench->add_subcommand(
        "realtime", "Late haptic steps of a realtime session beside a bare 1 kHz sleeper (cyclictest's floor) "
                    "on this machine, round after round");
    realtime_->add_option("scene", scene_, "Scene file or bundled scene name (default: fig8-pinch-oscillation)");
    realtime_->add_option("--duration", duration_, "Seconds of each measurement (sleeper and session)")
        ->check(CLI::Range(0.1, 3600.0));
    realtime_->add_option("--rounds", rounds_, "Sleeper/session pairs, alternating")->check(CLI::Range(1, 100));
    realtime_->add_option("--load", load_, "Busy threads at normal priority during both (0: none)")
        ->check(CLI::Range(0, 64));
    realtime_->add_flag("--no-frames", no_frames_, "Run the session without drawing frames");
    realtime_->add_flag("--no-fifo", no_fifo_, "Do not ask for SCHED_FIFO (measure as an ordinary user does)");
    realtime_->add_flag("--no-short-slice", no_short_slice_,
                        "Do not ask the scheduler for a short slice for the haptic loop (to see what it gives)");
    realtime_->add_flag("--pin", pin_, "Keep the haptic loop alone on the last CPU, the rest on the others");
    realtime_->add_option("--out", out_, "Folder for the sessions' run folders and bench.json (default: out/bench-realtime)");
    return bench;
  }

  int run() override {
    SessionDesc session = loadSceneFile(resolveScenePath(scene_));
    session.scene.duration = duration_;
    fs::create_directories(out_);
    const double threshold = sim::LoopSettings{}.late_threshold;
    nlohmann::json rounds = nlohmann::json::array();
    long sleeper_late = 0, sleeper_n = 0, loop_late = 0, loop_n = 0;
    std::printf("bench realtime: %s, %g s each, %d round(s), %d busy thread(s), frames %s, %s\n",
                session.scene.name.c_str(), duration_, rounds_, load_, no_frames_ ? "off" : "on",
                no_fifo_ ? "no SCHED_FIFO" : "SCHED_FIFO if granted");
    for (int r = 1; r <= rounds_; ++r) {
      const BusyThreads load(load_);
      const sim::SleeperStats sleeper = sim::runSleeper(session.scene.world.haptic_rate_hz, duration_, threshold);
      SessionOptions options;
      options.out_dir = (fs::path(out_) / ("round-" + std::to_string(r))).string();
      options.realtime = true;
      options.progress = false;
      options.frames = !no_frames_;
      options.fifo = !no_fifo_;
      options.short_slice = !no_short_slice_;
      options.pin_cpus = pin_;
      options.command_line = command_line_;
      options.stop_on_interrupt = true;  // Ctrl-C: this round's run folder is finished for the time reached
      const sim::LoopStats stats = runSession(session, options);
      const nlohmann::json summary = requireSummary(options.out_dir);
      // Frames drawn while the loop ran; a run writing frames draws the states still queued at
      // its end after it (render.queue.drawn_after_end), and drops those published to a full queue.
      const nlohmann::json render = summary.value("render", nlohmann::json::object());
      const double after_end = render.contains("queue") ? render["queue"]["drawn_after_end"].get<double>() : 0.0;
      const double dropped = render.contains("queue") ? render["queue"]["dropped"].get<double>() : 0.0;
      const double frames_per_s =
          render.contains("frames") ? (render["frames"].get<double>() - after_end) / std::max(1e-9, stats.wall_seconds) : 0.0;
      const nlohmann::json loop = summary["realtime"];
      std::printf("round %d: sleeper late %.3f %% (p99 %.0f us, max %.0f us) | loop late %.3f %% (p99 %.0f us, max %.0f us; "
                  "woke late %ld, overran %ld, catching up %ld), %.1f frames/s (then %.0f drawn after the end, %.0f dropped)\n",
                  r, sleeper.late_percent(), sleeper.p99_us, sleeper.max_late_us, loop["late_percent"].get<double>(),
                  stats.late_p99_us, stats.max_lateness_us, stats.late_woke, stats.late_overran, stats.late_catching_up,
                  frames_per_s, after_end, dropped);
      rounds.push_back({{"sleeper", sleeperJson(sleeper)}, {"loop", loop}, {"frames_per_s", frames_per_s},
                        {"frames_after_end", after_end}, {"frames_dropped", dropped},
                        {"run_folder", options.out_dir}});
      sleeper_late += sleeper.late;
      sleeper_n += sleeper.wakeups;
      loop_late += stats.late_steps;
      loop_n += stats.steps;
      if (stats.stopped || interruptSignal() != 0) break;  // Ctrl-C: bench.json of the rounds reached
    }
    const double floor = 100.0 * static_cast<double>(sleeper_late) / static_cast<double>(std::max(1L, sleeper_n));
    const double ours = 100.0 * static_cast<double>(loop_late) / static_cast<double>(std::max(1L, loop_n));
    std::printf("all rounds: sleeper (this machine's floor) %.3f %%, haptic loop %.3f %%: %+.3f points\n", floor, ours,
                ours - floor);
    const nlohmann::json out = {{"scene", session.scene.name}, {"duration_s", duration_}, {"load_threads", load_},
                                {"frames", !no_frames_}, {"late_threshold_us", 1e6 * threshold},
                                {"sleeper_late_percent", floor}, {"loop_late_percent", ours},
                                {"difference_points", ours - floor}, {"rounds", rounds},
                                {"provenance", provenanceJson(session, command_line_)}};
    writeFileAtomically((fs::path(out_) / "bench.json").string(), out.dump(2) + "\n");
    std::printf("wrote %s\n", (fs::path(out_) / "bench.json").c_str());
    return interruptSignal() != 0 ? interruptedStatus() : 0;
  }

 private:
  CLI::App* realtime_ = nullptr;
  std::string scene_ = "fig8-pinch-oscillation";
  std::string out_ = defaultOutFolder("bench-realtime");
  double duration_ = 10.0;
  int rounds_ = 2, load_ = 0;
  bool no_frames_ = false, no_fifo_ = false, no_short_slice_ = false, pin_ = false;
  std::vector<std::string> command_line_;
};

}  // namespace

std::unique_ptr<Command> makeBenchCommand(const std::vector<std::string>& argv) {
  return std::make_unique<BenchCommand>(argv);
}

}  // namespace gf::app

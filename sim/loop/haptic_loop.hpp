// The fixed-step haptic loop and its two clocks. The loop owns no Bullet state; it drives a
// World from the thread that calls run().
#pragma once

#include <atomic>
#include <functional>
#include <span>
#include <vector>

#include "sim/loop/realtime.hpp"
#include "sim/world/world.hpp"

namespace gf::sim {

/// How simulated time relates to wall-clock time.
enum class ClockMode {
  kOffline,   ///< as fast as possible; deterministic
  kRealtime,  ///< step k starts at start + k dt on steady_clock (absolute deadlines)
};

/// Step timings the loop keeps current while it runs, for the overlay. Written and read on the
/// haptic thread (the observer reads them).
struct LiveTimings {
  std::vector<float> recent_us = std::vector<float>(1000);  ///< ring: cost of the latest steps
  long steps = 0;                                           ///< steps recorded so far
  long late_steps = 0;                                      ///< realtime steps started late
  /// Median and p99 over the ring, and the late count. Copies the ring into a buffer kept from
  /// the first call (no allocation after it); one thread.
  HapticTimings summary() const;

 private:
  mutable std::vector<float> scratch_;
};

/// Settings of one run.
struct LoopSettings {
  double rate_hz = 1000.0;          ///< haptic rate (steps per simulated second)
  double duration = 1.0;            ///< simulated seconds to run
  ClockMode clock = ClockMode::kOffline;
  double late_threshold = 0.0005;   ///< s: a realtime step starting later than this is late
  LiveTimings* live = nullptr;      ///< updated after every step when set
  /// When set, the loop ends before the next step once it reads true (a Ctrl-C); any thread
  /// may set it.
  const std::atomic<bool>* stop = nullptr;
  /// Realtime: ask for SCHED_FIFO (granted to root or CAP_SYS_NICE); false runs as a user
  /// without either does, at normal priority.
  bool fifo = true;
  /// Realtime without SCHED_FIFO: sleep until this long before each deadline, then spin to it
  /// (us; 0: sleep to it; the period or more: never sleep). Ignored under SCHED_FIFO, where a
  /// thread that never sleeps is throttled by the kernel.
  double spin_us = 0.0;
  /// Realtime without SCHED_FIFO: ask for the scheduler's shortest slice (ShortSlice), so a
  /// waking step preempts ordinary threads sooner.
  bool short_slice = true;
  /// Realtime: the CPU the loop's thread runs on alone while it runs (CpuPin; -1: any).
  int cpu = -1;
  /// Live devices, in finger order (empty, or one entry per finger): a finger with a source is
  /// sampled from it instead of its track, and gets each step's feedback.
  std::span<DeviceSource* const> sources{};
};

/// A late realtime step, with what its previous iteration did (the evidence of why it was late).
struct LateStep {
  double t = 0.0;             ///< simulated time of the step (s)
  double late_us = 0.0;       ///< how late it started
  /// Why: "woke late" (its sleep ended late: the thread waited for a core), "overran" (the
  /// previous iteration started in time but ended after this step's deadline), "catching up"
  /// (the previous step was late itself and the loop had not caught up yet).
  const char* cause = "";
  double before_step_us = 0.0;  ///< cost of the previous World::step
  double before_work_us = 0.0;  ///< the rest of the previous iteration (feedback, outputs)
  long faults = 0;            ///< page faults of the haptic thread in the previous iteration and its sleep
  long preemptions = 0;       ///< involuntary context switches in the same span
};

/// Timing statistics of a run (wall-clock, so not deterministic).
struct LoopStats {
  long steps = 0;
  double step_median_us = 0.0;  ///< cost of World::step
  double step_p99_us = 0.0;
  double step_max_us = 0.0;
  long late_steps = 0;          ///< realtime: steps started more than late_threshold late
  double max_lateness_us = 0.0; ///< realtime: worst start lateness
  /// realtime: late steps in each second of simulated time (when in a run they happen)
  std::vector<int> late_per_second;
  double spin_us = 0.0;          ///< realtime: the spin before each deadline used (0 under SCHED_FIFO)
  double wall_seconds = 0.0;
  /// realtime: the loop ran under SCHED_FIFO (needs root or CAP_SYS_NICE); otherwise it
  /// shared the cores with the renderer and encoders at normal priority.
  bool fifo_priority = false;
  bool stopped = false;          ///< LoopSettings::stop ended the run before its duration
  // Realtime only, from here on.
  LatencyHistogram late_histogram;  ///< start lateness of every step (us)
  LatencyHistogram step_histogram;  ///< cost of World::step (us)
  LatencyHistogram work_histogram;  ///< the rest of each iteration: device feedback and the observer (us)
  double late_p50_us = 0.0, late_p99_us = 0.0, late_p999_us = 0.0;
  long late_woke = 0;      ///< late steps by cause (LateStep::cause)
  long late_overran = 0;
  long late_catching_up = 0;
  /// At normal priority: the short EEVDF slice was granted (ShortSlice).
  bool short_slice = false;
  int cpu = -1;  ///< the CPU the loop was pinned to (-1: not pinned)
  /// The haptic thread during the loop: page faults, and preemptions while it could run.
  long minor_faults = 0, major_faults = 0, preemptions = 0;
  std::string memory;               ///< MemoryLock::state()
  static constexpr std::size_t kLateStepsKept = 64;
  std::vector<LateStep> first_late;  ///< the first kLateStepsKept late steps
};

/// Called after every step with the world (haptic thread). Keep it cheap.
using StepObserver = std::function<void(const World&)>;

/// Runs `world` for settings.duration at a constant dt = 1/rate_hz. Devices are sampled at the
/// start time of each step, in finger order (from settings.sources where given, which then get
/// each step's feedback). Allocates only before the first step. A realtime
/// loop asks for SCHED_FIFO priority for the calling thread while it runs (so rendering and
/// encoding threads cannot delay a step; settings.fifo) and a 1 us timer slack (the default 50 us
/// delays every wake-up), and restores both afterwards; it locks the process's memory where
/// allowed (MemoryLock) and sleeps to each deadline with clock_nanosleep(TIMER_ABSTIME).
LoopStats runHapticLoop(World& world, const std::vector<DeviceTrack>& devices,
                        const LoopSettings& settings, const StepObserver& observer);

}  // namespace gf::sim

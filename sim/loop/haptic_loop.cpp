#include "sim/loop/haptic_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <optional>
#include <thread>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>

namespace gf::sim {
namespace {

using Clock = std::chrono::steady_clock;

// SCHED_FIFO for the calling thread while alive; the previous policy is restored after.
class FifoPriority {
 public:
  static constexpr int kPriority = 80;  // real-time priority asked for (1..99)
  FifoPriority() {
    pthread_getschedparam(pthread_self(), &policy_, &saved_);
    sched_param p{};
    p.sched_priority = std::min(kPriority, sched_get_priority_max(SCHED_FIFO));
    active_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
    // A user without root may still be allowed a lower real-time priority (RLIMIT_RTPRIO, as
    // limits.conf gives an "audio" or "realtime" group).
    rlimit limit{};
    if (!active_ && getrlimit(RLIMIT_RTPRIO, &limit) == 0 && limit.rlim_cur > 0) {
      p.sched_priority = static_cast<int>(std::min<rlim_t>(limit.rlim_cur, static_cast<rlim_t>(p.sched_priority)));
      active_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p) == 0;
    }
  }
  ~FifoPriority() {
    if (active_) pthread_setschedparam(pthread_self(), policy_, &saved_);
  }
  FifoPriority(const FifoPriority&) = delete;
  FifoPriority& operator=(const FifoPriority&) = delete;
  bool active() const { return active_; }

 private:
  int policy_ = SCHED_OTHER;
  sched_param saved_{};
  bool active_ = false;
};


}  // namespace

HapticTimings LiveTimings::summary() const {
  const std::size_t n = std::min(recent_us.size(), static_cast<std::size_t>(std::max(0L, steps)));
  scratch_.reserve(recent_us.size());
  scratch_.assign(recent_us.begin(), recent_us.begin() + static_cast<std::ptrdiff_t>(n));
  HapticTimings t;
  t.step_p99_us = percentile(scratch_, 0.99);
  t.step_median_us = percentile(scratch_, 0.5);
  t.late_steps = late_steps;
  return t;
}

namespace {

// The realtime half of the loop: the thread's priority, slice, CPU, timer slack and memory while
// it runs, the wait for each step's absolute deadline, and the account of how late each step
// started and why. Allocates only in its constructor.
class Deadlines {
 public:
  Deadlines(const LoopSettings& settings, long steps, double t0, LoopStats& stats)
      : settings_(settings), stats_(stats), t0_(t0), late_us_(static_cast<std::size_t>(steps)) {
    if (settings.cpu >= 0 && pin_.emplace(std::vector<int>{settings.cpu}).active()) stats.cpu = settings.cpu;
    if (settings.fifo) stats.fifo_priority = priority_.emplace().active();
    if (!stats.fifo_priority && settings.short_slice) stats.short_slice = slice_.emplace(kRealtimeSlice).granted();
    slack_.emplace(kRealtimeTimerSlackNs);
    stats.late_per_second.assign(static_cast<std::size_t>(std::ceil(settings.duration)) + 1, 0);
    stats.first_late.reserve(LoopStats::kLateStepsKept);
    memory_.emplace();  // after every buffer above exists, so they are locked too
    stats.memory = memory_->state();
    // A SCHED_FIFO thread needs no spin, and one that never sleeps is throttled by the kernel
    // (sched_rt_runtime_us: 50 ms of every second by default): spin only at normal priority.
    stats.spin_us = stats.fifo_priority ? 0.0 : std::max(0.0, settings.spin_us);
    spin_ = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::micro>(stats.spin_us));
    period_ = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / settings.rate_hz));
  }

  void start(Clock::time_point start) {
    start_ = iteration_end_ = start;
    usage_start_ = usage_before_ = ThreadUsage::now();
  }

  // Waits for step k's deadline and accounts for how late it starts. `step_us` holds the earlier
  // steps' costs.
  void wait(long k, const std::vector<float>& step_us) {
    // Absolute deadline: drift-free, a late step does not shift the following ones.
    const auto deadline = start_ + k * period_;
    sleepUntil(deadline - spin_);
    auto now = Clock::now();
    while (now < deadline) now = Clock::now();
    const auto us = static_cast<float>(std::chrono::duration<double, std::micro>(now - deadline).count());
    late_us_[static_cast<std::size_t>(k)] = us;  // float, like the percentiles taken from them
    stats_.late_histogram.add(us);
    stats_.max_lateness_us = std::max(stats_.max_lateness_us, static_cast<double>(us));
    const ThreadUsage usage = ThreadUsage::now();
    const bool late = us > 1e6 * settings_.late_threshold;
    if (late) countLate(k, us, deadline, usage, k > 0 ? step_us[static_cast<std::size_t>(k - 1)] : 0.0f);
    usage_before_ = usage;
    previous_late_ = late;
    if (settings_.live) settings_.live->late_steps = stats_.late_steps;
  }

  // After step k's outputs: what the step and the rest of the iteration cost.
  void iterationDone(float step_us, Clock::time_point stepped) {
    iteration_end_ = Clock::now();
    work_us_ = std::chrono::duration<float, std::micro>(iteration_end_ - stepped).count();
    stats_.step_histogram.add(step_us);
    stats_.work_histogram.add(work_us_);
  }

  void finish(long steps_run) {
    const ThreadUsage usage = ThreadUsage::now();
    stats_.minor_faults = usage.minor_faults - usage_start_.minor_faults;
    stats_.major_faults = usage.major_faults - usage_start_.major_faults;
    stats_.preemptions = usage.involuntary_switches - usage_start_.involuntary_switches;
    late_us_.resize(static_cast<std::size_t>(steps_run));
    stats_.late_p50_us = percentile(late_us_, 0.5);
    stats_.late_p99_us = percentile(late_us_, 0.99);
    stats_.late_p999_us = percentile(late_us_, 0.999);
  }

 private:
  void countLate(long k, float us, Clock::time_point deadline, const ThreadUsage& usage, float before_step_us) {
    ++stats_.late_steps;
    const char* cause = "woke late";
    if (k > 0 && iteration_end_ > deadline) cause = previous_late_ ? "catching up" : "overran";
    ++(cause[0] == 'w' ? stats_.late_woke : cause[0] == 'o' ? stats_.late_overran : stats_.late_catching_up);
    const auto second = static_cast<std::size_t>(static_cast<double>(k) / settings_.rate_hz);
    ++stats_.late_per_second[std::min(stats_.late_per_second.size() - 1, second)];
    if (stats_.first_late.size() == LoopStats::kLateStepsKept) return;
    stats_.first_late.push_back({t0_ + static_cast<double>(k) / settings_.rate_hz, us, cause, before_step_us, work_us_,
                                 usage.minor_faults + usage.major_faults - usage_before_.minor_faults - usage_before_.major_faults,
                                 usage.involuntary_switches - usage_before_.involuntary_switches});
  }

  const LoopSettings& settings_;
  LoopStats& stats_;
  const double t0_;
  std::vector<float> late_us_;
  std::optional<CpuPin> pin_;
  std::optional<FifoPriority> priority_;
  std::optional<ShortSlice> slice_;
  std::optional<TimerSlack> slack_;
  std::optional<MemoryLock> memory_;
  Clock::duration spin_{}, period_{};
  Clock::time_point start_, iteration_end_;  // iteration_end_: when the previous iteration's outputs were done
  ThreadUsage usage_start_, usage_before_;    // usage_before_: at the previous step's start
  float work_us_ = 0.0f;                      // the previous iteration's time after World::step
  bool previous_late_ = false;
};

}  // namespace

LoopStats runHapticLoop(World& world, const std::vector<DeviceTrack>& devices,
                        const LoopSettings& settings, const StepObserver& observer) {
  if (!(settings.rate_hz > 0.0) || !std::isfinite(settings.rate_hz) || !(settings.duration >= 0.0) ||
      !std::isfinite(settings.duration)) {
    throw std::invalid_argument("haptic rate must be > 0 and duration >= 0, both finite");
  }
  const double dt = 1.0 / settings.rate_hz;
  if (!settings.sources.empty() && settings.sources.size() != devices.size()) {
    throw std::invalid_argument("LoopSettings::sources needs one entry per finger (nullptr for a track)");
  }
  const long steps = stepCount(settings.duration, settings.rate_hz);
  std::vector<DeviceSample> samples(devices.size());
  std::vector<float> step_us(static_cast<std::size_t>(steps));
  LoopStats stats;
  const double t0 = world.time();
  std::optional<Deadlines> deadlines;
  if (settings.clock == ClockMode::kRealtime) deadlines.emplace(settings, steps, t0, stats);
  const auto start = Clock::now();
  if (deadlines) deadlines->start(start);
  long k = 0;
  for (; k < steps; ++k) {
    if (settings.stop && settings.stop->load(std::memory_order_relaxed)) break;
    if (deadlines) deadlines->wait(k, step_us);
    // Time of step k from its index, so no rounding accumulates over long runs.
    const double t = t0 + static_cast<double>(k) * dt;
    for (std::size_t i = 0; i < devices.size(); ++i) {
      DeviceSource* source = i < settings.sources.size() ? settings.sources[i] : nullptr;
      samples[i] = source ? source->sample(t) : devices[i].sample(t);
    }
    const auto before = Clock::now();
    world.step(dt, samples);
    const auto stepped = Clock::now();
    step_us[k] = std::chrono::duration<float, std::micro>(stepped - before).count();
    for (std::size_t i = 0; i < settings.sources.size(); ++i) {
      if (DeviceSource* source = settings.sources[i]) {
        const int f = static_cast<int>(i);
        world.setToldForce(f, source->feedback(world.time(), {world.feedbackForce(f), world.contactRadius(f),
                                                              world.sgoCount(f), world.touching(f)}));
      }
    }
    if (LiveTimings* live = settings.live) live->recent_us[live->steps++ % live->recent_us.size()] = step_us[k];
    if (observer) observer(world);
    if (deadlines) deadlines->iterationDone(step_us[k], stepped);
  }
  stats.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stats.steps = k;
  stats.stopped = k < steps;
  if (deadlines) deadlines->finish(k);
  step_us.resize(static_cast<std::size_t>(k));
  stats.step_max_us = step_us.empty() ? 0.0 : *std::max_element(step_us.begin(), step_us.end());
  stats.step_p99_us = percentile(step_us, 0.99);
  stats.step_median_us = percentile(step_us, 0.5);
  return stats;
}

}  // namespace gf::sim

#include "sim/haptic_loop.hpp"

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

double percentile(std::vector<float>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::min<double>(v.size() - 1, q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

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

long stepCount(double duration, double rate_hz) { return std::lround(duration * rate_hz); }

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
  const bool realtime = settings.clock == ClockMode::kRealtime;
  std::vector<float> late_us(realtime ? static_cast<std::size_t>(steps) : 0);
  std::optional<FifoPriority> priority;
  std::optional<TimerSlack> slack;
  std::optional<MemoryLock> memory;
  std::optional<ShortSlice> short_slice;
  std::optional<CpuPin> pin;
  if (realtime && settings.cpu >= 0 && pin.emplace(std::vector<int>{settings.cpu}).active()) stats.cpu = settings.cpu;
  if (realtime && settings.fifo) stats.fifo_priority = priority.emplace().active();
  if (realtime && !stats.fifo_priority && settings.short_slice) stats.short_slice = short_slice.emplace(kRealtimeSlice).granted();
  if (realtime) {
    slack.emplace(kRealtimeTimerSlackNs);
    stats.late_per_second.assign(static_cast<std::size_t>(std::ceil(settings.duration)) + 1, 0);
    stats.first_late.reserve(LoopStats::kLateStepsKept);
    memory.emplace();  // after every buffer above exists, so they are locked too
    stats.memory = memory->state();
  }
  // A SCHED_FIFO thread needs no spin, and one that never sleeps is throttled by the kernel
  // (sched_rt_runtime_us: 50 ms of every second by default): spin only at normal priority.
  const double spin_us = stats.fifo_priority || !realtime ? 0.0 : std::max(0.0, settings.spin_us);
  stats.spin_us = spin_us;
  const auto spin = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::micro>(spin_us));
  const auto start = Clock::now();
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  const ThreadUsage usage_start = realtime ? ThreadUsage::now() : ThreadUsage{};
  ThreadUsage usage_before = usage_start;  // at the previous step's start
  auto iteration_end = start;              // when the previous iteration's outputs were done
  float work_us = 0.0f;                    // the previous iteration's time after World::step
  bool previous_late = false;
  long k = 0;
  for (; k < steps; ++k) {
    if (settings.stop && settings.stop->load(std::memory_order_relaxed)) break;
    if (realtime) {
      // Absolute deadline: drift-free, a late step does not shift the following ones.
      const auto deadline = start + k * period;
      sleepUntil(deadline - spin);
      auto now = Clock::now();
      while (now < deadline) now = Clock::now();
      const double late = std::chrono::duration<double>(now - deadline).count();
      const float us = static_cast<float>(1e6 * late);  // kept as float, like the percentiles taken from them
      late_us[static_cast<std::size_t>(k)] = us;
      stats.late_histogram.add(us);
      stats.max_lateness_us = std::max(stats.max_lateness_us, static_cast<double>(us));
      const ThreadUsage usage = ThreadUsage::now();
      const bool is_late = us > 1e6 * settings.late_threshold;
      if (is_late) {
        ++stats.late_steps;
        const char* cause = "woke late";
        if (k > 0 && iteration_end > deadline) cause = previous_late ? "catching up" : "overran";
        ++(cause[0] == 'w' ? stats.late_woke : cause[0] == 'o' ? stats.late_overran : stats.late_catching_up);
        const auto second = static_cast<std::size_t>(static_cast<double>(k) / settings.rate_hz);
        ++stats.late_per_second[std::min(stats.late_per_second.size() - 1, second)];
        if (stats.first_late.size() < LoopStats::kLateStepsKept) {
          stats.first_late.push_back({t0 + static_cast<double>(k) * dt, 1e6 * late, cause,
                                      k > 0 ? step_us[static_cast<std::size_t>(k - 1)] : 0.0, work_us,
                                      usage.minor_faults + usage.major_faults - usage_before.minor_faults - usage_before.major_faults,
                                      usage.involuntary_switches - usage_before.involuntary_switches});
        }
      }
      usage_before = usage;
      previous_late = is_late;
      if (settings.live) settings.live->late_steps = stats.late_steps;
    }
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
        source->feedback(world.time(), {world.feedbackForce(f), world.contactRadius(f), world.sgoCount(f), world.touching(f)});
      }
    }
    if (LiveTimings* live = settings.live) live->recent_us[live->steps++ % live->recent_us.size()] = step_us[k];
    if (observer) observer(world);
    if (realtime) {
      iteration_end = Clock::now();
      work_us = std::chrono::duration<float, std::micro>(iteration_end - stepped).count();
      stats.step_histogram.add(step_us[k]);
      stats.work_histogram.add(work_us);
    }
  }
  stats.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  stats.steps = k;
  stats.stopped = k < steps;
  if (realtime) {
    const ThreadUsage usage = ThreadUsage::now();
    stats.minor_faults = usage.minor_faults - usage_start.minor_faults;
    stats.major_faults = usage.major_faults - usage_start.major_faults;
    stats.preemptions = usage.involuntary_switches - usage_start.involuntary_switches;
    late_us.resize(static_cast<std::size_t>(k));
    stats.late_p50_us = percentile(late_us, 0.5);
    stats.late_p99_us = percentile(late_us, 0.99);
    stats.late_p999_us = percentile(late_us, 0.999);
  }
  step_us.resize(static_cast<std::size_t>(k));
  stats.step_max_us = step_us.empty() ? 0.0 : *std::max_element(step_us.begin(), step_us.end());
  stats.step_p99_us = percentile(step_us, 0.99);
  stats.step_median_us = percentile(step_us, 0.5);
  return stats;
}

}  // namespace gf::sim

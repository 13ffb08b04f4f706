// What a realtime loop needs from the operating system, and what it measures about it: the
// absolute-deadline sleep, locked or prefaulted memory, per-thread fault and preemption counts,
// latency histograms, and a bare periodic sleeper (cyclictest's measurement, in process) that
// shows the machine's own floor beside the haptic loop's.
#pragma once

#include <array>
#include <chrono>
#include <string>
#include <vector>

namespace gf::sim {

/// The q-quantile (0..1, nearest rank) of `values`, which it reorders; 0 when empty.
double percentile(std::vector<float>& values, double q);

/// Number of steps a run of `duration` seconds at `rate_hz` takes (rounded to nearest).
long stepCount(double duration, double rate_hz);

/// Counts of microsecond values in fixed bins (cyclictest's histogram, coarser): bin i holds
/// values up to kEdgesUs[i], the last bin everything above kEdgesUs.back().
struct LatencyHistogram {
  static constexpr std::array<double, 13> kEdgesUs = {5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000};
  std::array<long, kEdgesUs.size() + 1> counts{};
  void add(double us);
  long total() const;
  /// Values above `us` (an edge of the bins).
  long above(double us) const;
};

/// Sleeps until `deadline` on the monotonic clock (steady_clock) with clock_nanosleep(TIMER_ABSTIME),
/// as cyclictest does: no clock read and no relative interval between the decision and the sleep.
void sleepUntil(std::chrono::steady_clock::time_point deadline);

/// The calling thread's timer slack (how late the kernel may wake a sleep, to batch wake-ups: 50 us
/// by default) set to `ns` while alive; the previous value is restored after.
class TimerSlack {
 public:
  explicit TimerSlack(unsigned long ns);
  ~TimerSlack();
  TimerSlack(const TimerSlack&) = delete;
  TimerSlack& operator=(const TimerSlack&) = delete;

 private:
  long saved_;
};

/// While alive, the calling thread (at SCHED_OTHER) asks the EEVDF scheduler (Linux 6.6+) for a
/// short time slice (sched_setattr's sched_runtime, which any user may set, 0.1 to 100 ms): a
/// thread with a short slice gets an early virtual deadline when it wakes, so it preempts a
/// thread that has been running instead of waiting for that thread's slice to end. Restores the
/// previous attributes after. Does nothing on kernels without it (granted() is false then).
class ShortSlice {
 public:
  explicit ShortSlice(std::chrono::nanoseconds slice);
  ~ShortSlice();
  ShortSlice(const ShortSlice&) = delete;
  ShortSlice& operator=(const ShortSlice&) = delete;
  bool granted() const { return granted_; }
  /// The calling thread's slice request now (0: the kernel's default; -1: not readable).
  static std::chrono::nanoseconds current();

 private:
  bool granted_ = false;
  unsigned long long saved_runtime_ = 0;
};

/// The slice a realtime loop at normal priority asks for: the kernel's shortest.
inline constexpr std::chrono::nanoseconds kRealtimeSlice{100'000};

/// Timer slack of a realtime loop's thread (ns).
inline constexpr unsigned long kRealtimeTimerSlackNs = 1000;

/// The calling thread's page faults and context switches so far (getrusage(RUSAGE_THREAD)).
struct ThreadUsage {
  long minor_faults = 0, major_faults = 0;
  long voluntary_switches = 0;    ///< the thread slept or waited
  long involuntary_switches = 0;  ///< the thread was preempted while it could run
  static ThreadUsage now();
};

/// While alive, the process's memory is locked in RAM (mlockall: current and future pages, each
/// as it is first touched) where that is allowed without failing later allocations (root,
/// CAP_IPC_LOCK, or an unlimited RLIMIT_MEMLOCK; not in sanitizer builds); otherwise nothing is
/// locked. Either way the calling thread's stack is touched
/// to `stack_bytes` first, so its first deep call takes no page fault. Unlocks when destroyed.
class MemoryLock {
 public:
  explicit MemoryLock(std::size_t stack_bytes = 256 * 1024);
  ~MemoryLock();
  MemoryLock(const MemoryLock&) = delete;
  MemoryLock& operator=(const MemoryLock&) = delete;
  bool locked() const { return locked_; }
  /// "locked", or why not ("not allowed: RLIMIT_MEMLOCK 8192 kB", "mlockall failed: ...").
  const std::string& state() const { return state_; }

 private:
  bool locked_ = false;
  std::string state_;
};

/// While alive, the calling thread may run only on `cpus` (sched_setaffinity); the previous set
/// is restored after. Threads (and processes) it starts meanwhile inherit the set. active() is
/// false when `cpus` is empty or the system refused it.
class CpuPin {
 public:
  explicit CpuPin(const std::vector<int>& cpus);
  ~CpuPin();
  CpuPin(const CpuPin&) = delete;
  CpuPin& operator=(const CpuPin&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
  std::vector<unsigned char> saved_;  // the previous cpu_set_t's bytes
};

/// The calling thread's CPUs split for a realtime run: the haptic loop's own CPU (the last one the
/// thread may use) and the rest for everything else. haptic is -1 with fewer than two CPUs.
struct CpuSplit {
  int haptic = -1;
  std::vector<int> others;
};
CpuSplit splitCpus();

/// Wake-up lateness of a periodic sleeper.
struct SleeperStats {
  long wakeups = 0;
  long late = 0;               ///< woke more than the threshold after the deadline
  double max_late_us = 0.0;
  double p50_us = 0.0, p99_us = 0.0, p999_us = 0.0;
  LatencyHistogram histogram;  ///< wake-up lateness
  double late_percent() const { return wakeups > 0 ? 100.0 * static_cast<double>(late) / static_cast<double>(wakeups) : 0.0; }
};

/// A thread that only sleeps to absolute deadlines `1/rate_hz` apart for `seconds` and records how
/// late it wakes: what cyclictest measures (SCHED_OTHER, no work, clock_nanosleep(TIMER_ABSTIME),
/// 1 us timer slack), run in the calling thread at its own priority. Threshold in seconds.
SleeperStats runSleeper(double rate_hz, double seconds, double late_threshold);

}  // namespace gf::sim

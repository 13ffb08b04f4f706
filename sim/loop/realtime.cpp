#include "sim/loop/realtime.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>

#include <sched.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

namespace gf::sim {
namespace {

using Clock = std::chrono::steady_clock;

// Touches `bytes` of the calling thread's stack, so those pages exist before the loop needs them.
__attribute__((noinline)) void touchStack(std::size_t bytes) {
  constexpr std::size_t kChunk = 16 * 1024;
  unsigned char chunk[kChunk];
  for (std::size_t i = 0; i < kChunk; i += 4096) *static_cast<volatile unsigned char*>(&chunk[i]) = 0;
  if (bytes > kChunk) touchStack(bytes - kChunk);
  asm volatile("" : : "r"(chunk) : "memory");  // the chunk stays on the stack
}

// Whether mlockall(MCL_FUTURE) leaves later allocations free to grow: the limit is unlimited,
// or the process may lock beyond it (root, CAP_IPC_LOCK).
bool mayLockEverything(rlimit& limit) {
  if (getrlimit(RLIMIT_MEMLOCK, &limit) != 0) return false;
  return limit.rlim_cur == RLIM_INFINITY || geteuid() == 0;
}

}  // namespace

double percentile(std::vector<float>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::min<double>(v.size() - 1, q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

long stepCount(double duration, double rate_hz) { return std::lround(duration * rate_hz); }

void LatencyHistogram::add(double us) {
  const auto* edge = std::lower_bound(kEdgesUs.begin(), kEdgesUs.end(), us);
  ++counts[static_cast<std::size_t>(edge - kEdgesUs.begin())];
}

long LatencyHistogram::total() const {
  long n = 0;
  for (long c : counts) n += c;
  return n;
}

long LatencyHistogram::above(double us) const {
  const auto* edge = std::lower_bound(kEdgesUs.begin(), kEdgesUs.end(), us);
  long n = 0;
  for (std::size_t i = static_cast<std::size_t>(edge - kEdgesUs.begin()) + 1; i < counts.size(); ++i) n += counts[i];
  return n;
}

void sleepUntil(Clock::time_point deadline) {
  const auto since = deadline.time_since_epoch();
  const auto s = std::chrono::duration_cast<std::chrono::seconds>(since);
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(s.count());
  ts.tv_nsec = static_cast<long>(std::chrono::duration_cast<std::chrono::nanoseconds>(since - s).count());
  // steady_clock is CLOCK_MONOTONIC on Linux; a signal's interruption sleeps again to the same deadline.
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

TimerSlack::TimerSlack(unsigned long ns) : saved_(prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0)) {
  prctl(PR_SET_TIMERSLACK, ns, 0, 0, 0);
}

TimerSlack::~TimerSlack() {
  if (saved_ > 0) prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(saved_), 0, 0, 0);
}

namespace {

// The kernel's struct sched_attr (its ABI, SCHED_ATTR_SIZE_VER1; <linux/sched/types.h> clashes
// with glibc's <sched.h>).
struct SchedAttr {
  std::uint32_t size;
  std::uint32_t sched_policy;
  std::uint64_t sched_flags;
  std::int32_t sched_nice;
  std::uint32_t sched_priority;
  std::uint64_t sched_runtime, sched_deadline, sched_period;
  std::uint32_t sched_util_min, sched_util_max;
};
static_assert(sizeof(SchedAttr) == 56);

// The calling thread's scheduling attributes (glibc 2.36 has no wrapper for these calls).
bool getAttributes(SchedAttr& a) {
  a = {};
  return syscall(SYS_sched_getattr, 0, &a, sizeof a, 0) == 0;
}

bool setAttributes(SchedAttr& a) {
  a.size = sizeof a;
  return syscall(SYS_sched_setattr, 0, &a, 0) == 0;
}

}  // namespace

ShortSlice::ShortSlice(std::chrono::nanoseconds slice) {
  SchedAttr a{};
  if (!getAttributes(a) || a.sched_policy != SCHED_OTHER) return;
  saved_runtime_ = a.sched_runtime;
  a.sched_runtime = static_cast<unsigned long long>(slice.count());
  a.sched_flags = 0;
  granted_ = setAttributes(a) && getAttributes(a) && a.sched_runtime == static_cast<unsigned long long>(slice.count());
}

std::chrono::nanoseconds ShortSlice::current() {
  SchedAttr a{};
  if (!getAttributes(a)) return std::chrono::nanoseconds(-1);
  return std::chrono::nanoseconds(static_cast<long long>(a.sched_runtime));
}

ShortSlice::~ShortSlice() {
  SchedAttr a{};
  if (!granted_ || !getAttributes(a)) return;
  a.sched_runtime = saved_runtime_;
  a.sched_flags = 0;
  setAttributes(a);
}

ThreadUsage ThreadUsage::now() {
  rusage u{};
  getrusage(RUSAGE_THREAD, &u);
  return {u.ru_minflt, u.ru_majflt, u.ru_nvcsw, u.ru_nivcsw};
}

MemoryLock::MemoryLock(std::size_t stack_bytes) {
  touchStack(stack_bytes);
  rlimit limit{};
  if (!mayLockEverything(limit)) {
    state_ = "not locked: RLIMIT_MEMLOCK is " + std::to_string(limit.rlim_cur / 1024) +
             " kB (locking more than that would make later allocations fail)";
    return;
  }
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  state_ = "not locked: a sanitizer build (its shadow memory is terabytes of address space)";
  return;
#endif
  // MCL_ONFAULT: what is in memory now stays, and every page is locked as it is first touched
  // (the loop's buffers are touched before it starts); nothing is populated here.
  locked_ = mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) == 0;
  state_ = locked_ ? "locked" : std::string("not locked: mlockall failed: ") + std::strerror(errno);
}

MemoryLock::~MemoryLock() {
  if (locked_) munlockall();
}

CpuPin::CpuPin(const std::vector<int>& cpus) {
  if (cpus.empty()) return;
  cpu_set_t old;
  CPU_ZERO(&old);
  if (sched_getaffinity(0, sizeof old, &old) != 0) return;
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cpus) {
    if (c >= 0 && c < CPU_SETSIZE) CPU_SET(c, &set);
  }
  if (sched_setaffinity(0, sizeof set, &set) != 0) return;
  const auto* bytes = reinterpret_cast<const unsigned char*>(&old);
  saved_.assign(bytes, bytes + sizeof old);
  active_ = true;
}

CpuPin::~CpuPin() {
  if (!active_) return;
  cpu_set_t old;
  std::memcpy(&old, saved_.data(), sizeof old);
  sched_setaffinity(0, sizeof old, &old);
}

CpuSplit splitCpus() {
  CpuSplit split;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0 || CPU_COUNT(&set) < 2) return split;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &set)) split.others.push_back(c);
  }
  split.haptic = split.others.back();
  split.others.pop_back();
  return split;
}

SleeperStats runSleeper(double rate_hz, double seconds, double late_threshold) {
  const long n = std::max(0L, stepCount(seconds, rate_hz));
  std::vector<float> late_us(static_cast<std::size_t>(n));
  const TimerSlack slack(kRealtimeTimerSlackNs);
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
  SleeperStats stats;
  const auto start = Clock::now() + period;
  for (long k = 0; k < n; ++k) {
    const auto deadline = start + k * period;
    sleepUntil(deadline);
    // Kept as float, like the percentiles taken from them.
    const double us = static_cast<float>(std::chrono::duration<double, std::micro>(Clock::now() - deadline).count());
    late_us[static_cast<std::size_t>(k)] = static_cast<float>(us);
    stats.histogram.add(us);
    stats.max_late_us = std::max(stats.max_late_us, us);
    if (us > 1e6 * late_threshold) ++stats.late;
  }
  stats.wakeups = n;
  stats.p50_us = percentile(late_us, 0.5);
  stats.p99_us = percentile(late_us, 0.99);
  stats.p999_us = percentile(late_us, 0.999);
  return stats;
}

}  // namespace gf::sim

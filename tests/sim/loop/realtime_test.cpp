// What the realtime loop measures about the machine: its histograms' bins, the sleeper's and the
// loop's accounting (every step counted once, every late step given one cause), and the short
// scheduler slice restored afterwards. Wall-clock values are only checked for consistency, never
// against thresholds.
#include "sim/loop/realtime.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include <sched.h>

#include "sim/loop/haptic_loop.hpp"
#include "sim/world/world.hpp"

namespace gf::sim {
namespace {

TEST(LatencyHistogram, AValueOnAnEdgeFallsInTheBinItClosesAndTheLastBinIsOpen) {
  LatencyHistogram h;
  for (double us : {0.0, 5.0, 5.001, 500.0, 500.5, 1e9}) h.add(us);
  EXPECT_EQ(h.counts[0], 2);  // 0 and 5 (<= 5)
  EXPECT_EQ(h.counts[1], 1);  // 5.001 (<= 10)
  EXPECT_EQ(h.counts[6], 1);  // 500 (<= 500)
  EXPECT_EQ(h.counts[7], 1);  // 500.5 (<= 1000)
  EXPECT_EQ(h.counts.back(), 1);
  EXPECT_EQ(h.total(), 6);
  EXPECT_EQ(h.above(500.0), 2);  // what is late at the 0.5 ms threshold
  EXPECT_EQ(h.above(50000.0), 1);
}

TEST(Sleeper, CountsEveryWakeUpOnceAndItsLateOnesAmongThem) {
  const SleeperStats s = runSleeper(1000.0, 0.05, 0.0005);
  EXPECT_EQ(s.wakeups, 50);
  EXPECT_EQ(s.histogram.total(), 50);
  EXPECT_EQ(s.late, s.histogram.above(500.0));
  EXPECT_LE(s.p50_us, s.p99_us);
  EXPECT_LE(s.p99_us, s.p999_us);
  EXPECT_LE(s.p999_us, s.max_late_us);
}

// A realtime run of an empty world: every step is in the lateness, step and work histograms once,
// the late ones split among the causes, the first of them kept, and the memory's state named.
TEST(RealtimeLoop, HistogramsHoldEveryStepAndEveryLateStepHasOneCause) {
  SceneDesc scene;
  scene.duration = 0.2;
  World world(scene);
  LoopSettings settings{1000.0, 0.2, ClockMode::kRealtime};
  settings.fifo = false;
  settings.cpu = splitCpus().haptic;  // -1 (not pinned) on one CPU
  const LoopStats stats = runHapticLoop(world, {}, settings, {});
  EXPECT_EQ(stats.cpu, settings.cpu);
  EXPECT_EQ(stats.steps, 200);
  EXPECT_EQ(stats.late_histogram.total(), 200);
  EXPECT_EQ(stats.step_histogram.total(), 200);
  EXPECT_EQ(stats.work_histogram.total(), 200);
  EXPECT_EQ(stats.late_steps, stats.late_histogram.above(500.0));
  EXPECT_EQ(stats.late_woke + stats.late_overran + stats.late_catching_up, stats.late_steps);
  EXPECT_EQ(static_cast<long>(stats.first_late.size()), std::min<long>(stats.late_steps, LoopStats::kLateStepsKept));
  EXPECT_EQ(std::accumulate(stats.late_per_second.begin(), stats.late_per_second.end(), 0L), stats.late_steps);
  EXPECT_FALSE(stats.memory.empty());
  EXPECT_LE(stats.late_p50_us, stats.late_p99_us);
  EXPECT_LE(stats.late_p999_us, stats.max_lateness_us);
  EXPECT_FALSE(stats.fifo_priority);
}

// An offline run measures none of it.
TEST(RealtimeLoop, AnOfflineRunHasNoLatenessFigures) {
  SceneDesc scene;
  World world(scene);
  const LoopStats stats = runHapticLoop(world, {}, {1000.0, 0.05}, {});
  EXPECT_EQ(stats.steps, 50);
  EXPECT_EQ(stats.late_histogram.total(), 0);
  EXPECT_TRUE(stats.memory.empty());
  EXPECT_FALSE(stats.short_slice);
}

TEST(ShortSlice, HoldsWhileAliveAndIsRestoredWhenItEnds) {
  const std::chrono::nanoseconds before = ShortSlice::current();
  {
    const ShortSlice slice(kRealtimeSlice);
    if (!slice.granted()) GTEST_SKIP() << "this kernel has no per-thread slice (sched_setattr sched_runtime, Linux 6.6+)";
    EXPECT_EQ(ShortSlice::current(), kRealtimeSlice);
  }
  EXPECT_EQ(ShortSlice::current(), before);
}

// The CPUs the calling thread may run on.
std::vector<int> allowedCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (CPU_ISSET(c, &set)) cpus.push_back(c);
  }
  return cpus;
}

TEST(CpuPin, HoldsTheThreadOnItsCpusAndRestoresTheSetAfter) {
  const std::vector<int> before = allowedCpus();
  ASSERT_FALSE(before.empty());
  {
    const CpuPin pin({before.front()});
    ASSERT_TRUE(pin.active());
    EXPECT_EQ(allowedCpus(), std::vector<int>{before.front()});
  }
  EXPECT_EQ(allowedCpus(), before);
  EXPECT_FALSE(CpuPin({}).active());
}

TEST(CpuPin, TheSplitGivesTheLoopTheLastCpuAndEverythingElseTheRest) {
  const std::vector<int> cpus = allowedCpus();
  const CpuSplit split = splitCpus();
  if (cpus.size() < 2) {
    EXPECT_EQ(split.haptic, -1);
    EXPECT_TRUE(split.others.empty());
    return;
  }
  EXPECT_EQ(split.haptic, cpus.back());
  EXPECT_EQ(split.others, std::vector<int>(cpus.begin(), cpus.end() - 1));
}

}  // namespace
}  // namespace gf::sim

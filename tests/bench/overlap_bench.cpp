// Benchmark (not a test): the cost of overlap handling (docs/overlap.md) in one haptic step of
// the overlap-pinch scene, its two fingers' patches overlapping under the tile (t = 1.8 s).
// Run: build/release/gf_bench --benchmark_filter=BM_OverlapStep
#include <benchmark/benchmark.h>

#include "tests/sim/test_context.hpp"

namespace {

using namespace gf;

// world.overlap: 0 ignore (measured only), 1 push_apart, 2 merge.
void BM_OverlapStep(benchmark::State& state) {
  static const char* const kModes[] = {"ignore", "push_apart", "merge"};
  test_support::TestContext ctx("overlap-pinch", test_support::kSceneSgo,
                                {std::string("world.overlap=") + kModes[state.range(0)]});
  ctx.simulate(1.8);
  sim::World& world = ctx.world();
  std::vector<sim::DeviceSample> samples;
  for (const sim::DeviceTrack& d : sim::deviceTracks(ctx.scene())) samples.push_back(d.sample(world.time()));
  for (auto _ : state) world.step(0.001, samples);
  state.counters["overlap_mm2"] = benchmark::Counter(world.overlap(0).area * 1e6);
}
BENCHMARK(BM_OverlapStep)->DenseRange(0, 2)->ArgName("mode")->Unit(benchmark::kMicrosecond)
    ->Repetitions(9)->ReportAggregatesOnly(true);

}  // namespace

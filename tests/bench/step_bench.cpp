// Benchmarks (not tests): cost of one haptic step of the two-finger pinch, and of the patch.
// Run: build/release/gf_bench [--benchmark_out=FILE --benchmark_out_format=csv]
#include <benchmark/benchmark.h>

#include <algorithm>

#include "sim/patch/god_finger.hpp"
#include "sim/patch/warm_walk.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/scene/snapshot.hpp"
#include "tests/sim/test_context.hpp"

namespace {

using namespace gf;

// Times one step of the Fig. 8 pinch (the bundled scene, n_SGO per finger, `overrides`) while
// the lifted cylinder is held (t >= 3.5 s); returns the points both fingers injected per step.
int timeHeldPinch(benchmark::State& state, int n_sgo, const std::vector<std::string>& overrides) {
  test_support::TestContext ctx("fig8-pinch-oscillation", n_sgo, overrides);
  ctx.simulate(3.5);
  sim::World& world = ctx.world();
  std::vector<sim::DeviceSample> samples;
  for (const sim::DeviceTrack& d : sim::deviceTracks(ctx.scene())) samples.push_back(d.sample(world.time()));
  for (auto _ : state) world.step(0.001, samples);
  return world.sgoCount(0) + world.sgoCount(1);
}

// One haptic step of the Fig. 8 pinch (the bundled scene) while the lifted cylinder is held
// (t >= 3.5 s): n_SGO per finger, the solver iterations (the scene's 20, or 10) and the contact
// solver (0 points, 1 aggregate).
void BM_PinchStep(benchmark::State& state) {
  const int sgos = timeHeldPinch(state, static_cast<int>(state.range(0)),
                                  {"world.solver_iterations=" + std::to_string(state.range(1)),
                                   std::string("world.contact_solver=") + (state.range(2) == 1 ? "aggregate" : "points")});
  state.counters["sgo_per_step"] = benchmark::Counter(static_cast<double>(sgos));
}
BENCHMARK(BM_PinchStep)->ArgsProduct({{0, 8, 16, 64}, {20, 10}, {0, 1}})->ArgNames({"n_sgo", "iterations", "aggregate"})
    ->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);

// One snapshot of the held Fig. 8 pinch (as a frame takes it, 60 times a second): poses, both
// fingers' patches, and the solver's loads split over their points (solvedLoads). n_SGO per
// finger and the contact solver (0 points, 1 aggregate).
void BM_PinchSnapshot(benchmark::State& state) {
  test_support::TestContext ctx("fig8-pinch-oscillation", static_cast<int>(state.range(0)),
                                {std::string("world.contact_solver=") + (state.range(1) == 1 ? "aggregate" : "points")});
  ctx.simulate(3.5);
  sim::Snapshot snap;
  ctx.world().snapshot(snap);
  for (auto _ : state) {
    ctx.world().snapshot(snap);
    benchmark::DoNotOptimize(snap.fingers[0].contacts.data());
  }
}
BENCHMARK(BM_PinchSnapshot)->ArgsProduct({{8, 64}, {0, 1}})->ArgNames({"n_sgo", "aggregate"})->Unit(benchmark::kMicrosecond);

// One step of the same pinch per contact model at the default 10 iterations: 0 god_object,
// 1 soft_finger, 2 god_finger ring, 3 god_finger filled (3 points per path), at n_SGO 8 and 16.
void BM_ModelStep(benchmark::State& state) {
  static const char* const kModels[] = {"god_object", "soft_finger", "god_finger", "god_finger"};
  const int m = static_cast<int>(state.range(0));
  std::vector<std::string> overrides = {"world.solver_iterations=10"};
  for (const char* finger : {"left", "right"}) {
    overrides.push_back(std::string("fingers.") + finger + ".contact_model=" + kModels[m]);
    overrides.push_back(std::string("fingers.") + finger + ".patch=" + (m == 3 ? "filled" : "ring"));
  }
  const int points = timeHeldPinch(state, static_cast<int>(state.range(1)), overrides);
  state.counters["points_per_step"] = benchmark::Counter(static_cast<double>(points));
}
BENCHMARK(BM_ModelStep)->ArgsProduct({{0, 1, 2, 3}, {8, 16}})->ArgNames({"model", "n_sgo"})
    ->Unit(benchmark::kMicrosecond)->Repetitions(3)->ReportAggregatesOnly(true);

// One step of the held pinch with both fingers' pad model disc (0) or oriented (1), ring (0) or
// filled (1) patches, n_SGO 8, the default 10 iterations. The pinch presses the cylinder's side
// with the devices unturned: the oriented pads stand at 90 degrees, every radial on the tip's
// ellipse. Alternate the cases (--benchmark_enable_random_interleaving=true) and compare medians.
void BM_PadStep(benchmark::State& state) {
  std::vector<std::string> overrides = {"world.solver_iterations=10"};
  for (const char* finger : {"left", "right"}) {
    overrides.push_back(std::string("fingers.") + finger + ".pad_model=" + (state.range(0) == 1 ? "oriented" : "disc"));
    overrides.push_back(std::string("fingers.") + finger + ".patch=" + (state.range(1) == 1 ? "filled" : "ring"));
  }
  const int points = timeHeldPinch(state, 8, overrides);
  state.counters["points_per_step"] = benchmark::Counter(static_cast<double>(points));
}
BENCHMARK(BM_PadStep)->ArgsProduct({{0, 1}, {0, 1}})->ArgNames({"oriented", "filled"})
    ->Unit(benchmark::kMicrosecond)->Repetitions(9)->ReportAggregatesOnly(true);

// The patch alone on the pinch cylinder's walk mesh: time per SGO.
void BM_Patch(benchmark::State& state) {
  const sim::Mesh mesh = sim::tessellateCylinder(0.03, 0.05, 64);
  sim::PatchSettings s;
  s.n_sgo = static_cast<int>(state.range(0));
  const sim::PatchContact c{sim::Vec3(0.03, -0.01, 0.003), sim::Vec3::UnitX(), -2e-4};
  const sim::Vec3 v(-0.005, 0.001, 0.0);
  sim::Patch p;
  for (auto _ : state) {
    sim::computePatch(mesh, c, v, s, p);
    benchmark::DoNotOptimize(p.sgos.data());
  }
  // items_per_second counts SGOs: time per SGO is its inverse.
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * s.n_sgo);
}
BENCHMARK(BM_Patch)->Arg(8)->Arg(16)->Arg(64)->Unit(benchmark::kNanosecond);

// The same patch held, as a haptic step computes it: warm-started walks (the cache of the last
// step) with the device wiggling by 14 nm (10 nm on two axes) between steps, so every walk is
// carried within its slack, as 99.8 % are in the held pinch. Time per SGO is what n_SGO 64 adds
// over n_SGO 8.
void BM_PatchHeld(benchmark::State& state) {
  const sim::Mesh mesh = sim::tessellateCylinder(0.03, 0.05, 64);
  sim::PatchSettings s;
  s.n_sgo = static_cast<int>(state.range(0));
  sim::PatchContact c{sim::Vec3(0.03, -0.01, 0.003), sim::Vec3::UnitX(), -2e-4};
  const sim::Vec3 v(-0.005, 0.001, 0.0);
  sim::Patch p;
  sim::WalkCache warm;
  sim::computePatch(mesh, c, v, s, p, &warm);
  c.ring_reference_local = p.ring_tangent;
  long i = 0;
  for (auto _ : state) {
    const double wiggle = (++i & 1) != 0 ? 1e-8 : 0.0;
    sim::computePatch(mesh, c, v + sim::Vec3(0.0, wiggle, -wiggle), s, p, &warm);
    benchmark::DoNotOptimize(p.sgos.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * s.n_sgo);
  state.counters["slack_share"] = static_cast<double>(warm.slack_walks) /
                                  static_cast<double>(std::max(1L, warm.warm_walks + warm.cold_walks));
}
BENCHMARK(BM_PatchHeld)->Arg(8)->Arg(64)->Unit(benchmark::kNanosecond);

// The patch on fine meshes, pressed to the full 10 mm radius: a 100 352-face plane (98 um
// squares; arg 0) and a 327 680-face sphere of 3 cm radius (0.2 mm edges; arg 1). The walk
// crosses about r / edge length faces per SGO, so the time per SGO grows with the mesh's
// fineness; counters report the crossing-limit stops (none expected) and the mean walked length.
void BM_PatchFineMesh(benchmark::State& state) {
  const bool sphere = state.range(0) == 1;
  const sim::Mesh mesh = sphere ? sim::tessellateSphere(0.03, 7) : sim::tessellatePlane(0.011, 224);
  sim::PatchSettings s;
  s.n_sgo = static_cast<int>(state.range(1));
  s.d0 = 1e-4;  // r = r_max = 10 mm
  const sim::Vec3 n = sphere ? sim::Vec3(0.3, 0.8, -0.5).normalized() : sim::Vec3::UnitY();
  const sim::PatchContact c{sphere ? sim::Vec3(0.03 * n) : sim::Vec3(0.00013, 0, -0.00021), n, -2e-4};
  const sim::Vec3 v = -0.004 * n;
  sim::Patch p;
  for (auto _ : state) {
    sim::computePatch(mesh, c, v, s, p);
    benchmark::DoNotOptimize(p.sgos.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * s.n_sgo);
  int limit = 0;
  double walked = 0.0;
  for (const sim::Sgo& g : p.sgos) limit += g.stop == sim::WalkStop::kCrossingLimit, walked += g.walked;
  state.counters["faces"] = mesh.faceCount();
  state.counters["crossing_limit_stops"] = limit;
  state.counters["walked_mm"] = 1000.0 * walked / static_cast<double>(std::max<std::size_t>(1, p.sgos.size()));
}
BENCHMARK(BM_PatchFineMesh)->ArgsProduct({{0, 1}, {8, 64}})->ArgNames({"sphere", "n_sgo"})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();

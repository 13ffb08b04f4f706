// computePatch and World::step must not allocate in steady state. Counts every operator new of
// this process, and Bullet's own allocations (btAlignedAlloc) while a World steps.
#include <gtest/gtest.h>

#include <LinearMath/btAlignedAllocator.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "sim/patch/god_finger.hpp"
#include "sim/mesh/primitives.hpp"
#include "sim/patch/warm_walk.hpp"
#include "sim/world/world.hpp"
#include "sim/world/world_impl.hpp"
#include "tests/alloc_counter.hpp"
#include "tests/sim/pressed_box.hpp"
#include "tests/sim/test_context.hpp"

namespace gf::sim {
namespace {

void* countedAlloc(std::size_t size) {
  gf::test::countAllocation();
  return std::malloc(size);
}

TEST(PatchAllocation, NoHeapAllocationInSteadyState) {
  const Mesh sphere = tessellateSphere(0.04, 4);
  PatchSettings s;
  s.n_sgo = 16;
  Patch p;
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  auto contact = [&] {
    const Vec3 n = Vec3(g(rng), g(rng), g(rng)).normalized();
    Vec3 tangential(g(rng), g(rng), g(rng));
    tangential -= tangential.dot(n) * n;  // a sideways push; the press depth stays 5 mm
    return std::make_pair(PatchContact{0.04 * n, n, -0.001}, Vec3(-0.005 * n + 0.002 * tangential));
  };
  for (int i = 0; i < 200; ++i) {  // warm-up: the Patch reaches its working capacity
    const auto [c, v] = contact();
    computePatch(sphere, c, v, s, p);
  }
  const long before = gf::test::allocations();
  std::size_t sgos = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto [c, v] = contact();
    computePatch(sphere, c, v, s, p);
    sgos += p.sgos.size();
  }
  EXPECT_EQ(gf::test::allocations() - before, 0);
  EXPECT_EQ(sgos, 2000u * 16u);
}

// Warm-started walks: a finger sliding over a box's top face, its walks carried between patches.
TEST(PatchAllocation, WarmStartedWalksDoNotAllocateInSteadyState) {
  const Mesh box = tessellateBox(Vec3(0.05, 0.05, 0.05), 4);
  PatchSettings s;
  s.n_sgo = 16;
  Patch p;
  WalkCache cache;
  const auto contact = [](int i) {  // sliding 10 um a step, pressed 5 mm
    const Vec3 n = Vec3::UnitY();
    return std::make_pair(PatchContact{Vec3(-0.02 + 1e-5 * i, 0.05, 0.003), n, -0.001}, Vec3(0.002, -0.005, 0.0));
  };
  for (int i = 0; i < 200; ++i) {  // warm-up: the cache reaches its size
    const auto [c, v] = contact(i);
    computePatch(box, c, v, s, p, &cache);
  }
  const long before = gf::test::allocations(), carried = cache.warm_walks;
  for (int i = 200; i < 2200; ++i) {
    const auto [c, v] = contact(i);
    computePatch(box, c, v, s, p, &cache);
  }
  EXPECT_EQ(gf::test::allocations() - before, 0);
  EXPECT_GT(cache.warm_walks - carried, 2000 * 16 / 2) << "most walks carried";
}

// A box on a table pressed by one finger and turned by a torque beyond its torsion limit (the
// patch, its friction block and, per solver, its points or aggregate block every step); with
// the oriented pad, the device turned 40 degrees about z (a tilted pad, its ellipse every step).
long allocationsOfPressedBoxSteps(ContactSolver solver, PatchSettings patch = {}) {
  patch.n_sgo = 16;
  LoadDesc load;
  load.torque = Vec3(0, 0.1, 0);
  SceneDesc s = pressed_box::scene(patch, 0.0, load);
  s.world.contact_solver = solver;
  for (DeviceTrack::Keyframe& k : s.fingers[0].device.keyframes) {
    k.orientation = Quat(Eigen::AngleAxisd(0.6981317007977318, Vec3::UnitZ()));
  }
  btAlignedAllocSetCustom(countedAlloc, std::free);
  const long before_world = gf::test::allocations();
  World w(s);
  EXPECT_GT(gf::test::allocations() - before_world, 0) << "building a World allocates: the counter sees it";
  const auto step = [&] {
    const DeviceSample d = s.fingers[0].device.sample(w.time());
    w.step(1e-3, std::span(&d, 1));
  };
  for (int i = 0; i < 700; ++i) step();  // pressed, turning: storage at its working size
  const long before = gf::test::allocations();
  for (int i = 0; i < 500; ++i) step();
  if (patch.model == ContactModel::kGodFinger && patch.fill == PatchFill::kRing) {
    EXPECT_EQ(w.sgoCount(0), 16);
  }
  return gf::test::allocations() - before;
}

TEST(WorldAllocation, NoHeapAllocationPerStepWithEitherSolver) {
  EXPECT_EQ(allocationsOfPressedBoxSteps(ContactSolver::kPoints), 0);
  EXPECT_EQ(allocationsOfPressedBoxSteps(ContactSolver::kAggregate), 0);
}

// The overlap-pinch scene's two fingers with their patches overlapping (t = 1.7 s on): measuring
// the overlap and handling it (docs/overlap.md) allocate nothing per step.
long allocationsOfOverlappingSteps(const std::string& mode) {
  test_support::TestContext ctx("overlap-pinch", test_support::kSceneSgo, {"world.overlap=" + mode});
  ctx.simulate(1.7);
  World& w = ctx.world();
  std::vector<DeviceSample> samples(ctx.scene().fingers.size());
  const auto step = [&] {
    for (std::size_t f = 0; f < samples.size(); ++f) samples[f] = ctx.scene().fingers[f].device.sample(w.time());
    w.step(1e-3, samples);
  };
  for (int i = 0; i < 50; ++i) step();
  btAlignedAllocSetCustom(countedAlloc, std::free);
  const long before = gf::test::allocations();
  for (int i = 0; i < 200; ++i) step();
  const long counted = gf::test::allocations() - before;
  btAlignedAllocSetCustom(std::malloc, std::free);
  EXPECT_EQ(w.overlapPairCount(), 1);
  return counted;
}

TEST(WorldAllocation, NoHeapAllocationPerStepWithOverlapHandled) {
  EXPECT_EQ(allocationsOfOverlappingSteps("ignore"), 0);
  EXPECT_EQ(allocationsOfOverlappingSteps("push_apart"), 0);
  EXPECT_EQ(allocationsOfOverlappingSteps("merge"), 0);
}

// The Fig. 8 pinch held at the largest patch a setting allows (n_SGO 64, filled with 8 rings:
// 512 points per finger, 128 injected manifolds each step with the points solver; the aggregate
// solver injects none): Bullet's pools, sized for the scene (collisionPools: 1 044 manifolds
// where Bullet's default is 4096), hold every manifold the fingers inject, so no step takes one
// from the heap.
TEST(WorldAllocation, TheLargestPatchesTakeTheirManifoldsFromBulletsPools) {
  test_support::TestContext ctx("fig8-pinch-oscillation", kMaxSgo,
                                {"fingers.left.patch=filled", "fingers.right.patch=filled",
                                 "fingers.left.rings=" + std::to_string(kMaxRings),
                                 "fingers.right.rings=" + std::to_string(kMaxRings), "world.contact_solver=points"});
  const btDefaultCollisionConstructionInfo pools = collisionPools(ctx.scene());
  EXPECT_EQ(pools.m_defaultMaxPersistentManifoldPoolSize, 2 * 10 + 2 * kMaxContactsPerFinger * 128);  // 4 objects: 10 pairs
  EXPECT_EQ(pools.m_defaultMaxCollisionAlgorithmPoolSize, 256);
  ctx.simulate(1.2);  // grasped: both patches full
  World& w = ctx.world();
  std::vector<DeviceSample> samples;
  for (const DeviceTrack& d : deviceTracks(ctx.scene())) samples.push_back(d.sample(w.time()));
  for (int i = 0; i < 20; ++i) w.step(1e-3, samples);
  btAlignedAllocSetCustom(countedAlloc, std::free);
  const long before = gf::test::allocations();
  for (int i = 0; i < 100; ++i) w.step(1e-3, samples);
  const long counted = gf::test::allocations() - before;
  btAlignedAllocSetCustom(std::malloc, std::free);
  EXPECT_EQ(w.sgoCount(0), kMaxSgo * kMaxRings);
  EXPECT_EQ(w.sgoCount(1), kMaxSgo * kMaxRings);
  EXPECT_EQ(counted, 0);
}

// The walk caches are sized for the n_SGO a finger uses (kWarmCrossingsPerSgo crossings each),
// not for kMaxSgo: a live change to more radial vectors sizes them again, between steps, and a
// scripted one was sized for when the World was made; either way the steps from the change on
// allocate nothing and every radial vector is walked; a realtime session's World is sized for
// kMaxSgo up front (sizeForLiveSettings), so the call allocates nothing either. (The aggregate
// solver: with the points solver Bullet's own arrays grow once for the points a larger patch adds.)
long allocationsAfterGrowingNSgo(bool scripted, bool sized_for_live = false) {
  sim::SceneDesc scene =
      test_support::TestContext::load("fig8-pinch-oscillation", 8, {"world.contact_solver=aggregate"});
  if (scripted) {
    for (int f = 0; f < 2; ++f) {
      PatchChange change{1.2, f, scene.fingers[static_cast<std::size_t>(f)].patch};
      change.patch.n_sgo = kMaxSgo;
      scene.changes.push_back(change);
    }
  }
  World w(scene);
  if (sized_for_live) w.sizeForLiveSettings();
  std::vector<DeviceTrack> tracks = deviceTracks(scene);
  std::vector<DeviceSample> samples(tracks.size());
  const auto step = [&] {
    for (std::size_t f = 0; f < tracks.size(); ++f) samples[f] = tracks[f].sample(w.time());
    w.step(1e-3, samples);
  };
  while (w.time() < 1.1) step();  // grasped with 8 radial vectors a finger
  EXPECT_EQ(w.sgoCount(0), 8);
  const auto grow = [&] {
    for (int f = 0; f < 2; ++f) {
      PatchSettings bigger = scene.fingers[static_cast<std::size_t>(f)].patch;
      bigger.n_sgo = kMaxSgo;
      w.setPatchSettings(f, bigger);
    }
  };
  if (!scripted && !sized_for_live) grow();
  btAlignedAllocSetCustom(countedAlloc, std::free);
  const long before = gf::test::allocations();
  if (sized_for_live) grow();  // as a realtime haptic thread applies a setting from the browser
  for (int i = 0; i < 300; ++i) step();  // past the scripted change at 1.2 s
  const long counted = gf::test::allocations() - before;
  btAlignedAllocSetCustom(std::malloc, std::free);
  EXPECT_EQ(w.sgoCount(0), kMaxSgo);
  EXPECT_EQ(w.sgoCount(1), kMaxSgo);
  return counted;
}

TEST(WorldAllocation, WalkCachesFollowAGrowingNSgoWithoutAllocatingInASteps) {
  EXPECT_EQ(allocationsAfterGrowingNSgo(false), 0);
  EXPECT_EQ(allocationsAfterGrowingNSgo(true), 0);
}

// A World sized for live settings (a realtime session's) takes a larger n_SGO from
// setPatchSettings without allocating, in the call as in the steps after it.
TEST(WorldAllocation, AWorldSizedForLiveSettingsGrowsNSgoWithoutAllocating) {
  EXPECT_EQ(allocationsAfterGrowingNSgo(false, true), 0);
}

// A scene without bodies or fingers still gets pools Bullet can make (it cannot make an empty
// one), and a World of it steps.
TEST(WorldAllocation, AnEmptySceneGetsPoolsBulletCanMake) {
  const SceneDesc empty;
  EXPECT_EQ(collisionPools(empty).m_defaultMaxPersistentManifoldPoolSize, 64);
  EXPECT_EQ(collisionPools(empty).m_defaultMaxCollisionAlgorithmPoolSize, 256);
  World w(empty);
  for (int i = 0; i < 10; ++i) w.step(1e-3, {});
  EXPECT_NEAR(w.time(), 0.01, 1e-12);
}

// Pools never grow past Bullet's default, however many bodies a scene has (the pairs grow with
// their square): 100 spheres and two fingers would ask for 11 530 manifolds and 21 012 algorithms.
TEST(WorldAllocation, ManyBodiesGetNoMoreThanBulletsDefaultPools) {
  SceneDesc many;
  many.bodies.resize(100);
  for (BodyDesc& b : many.bodies) b.shape = ShapeKind::kSphere;
  many.fingers.resize(2);
  EXPECT_EQ(collisionPools(many).m_defaultMaxPersistentManifoldPoolSize, 4096);
  EXPECT_EQ(collisionPools(many).m_defaultMaxCollisionAlgorithmPoolSize, 4096);
}

// Scenes whose bodies open a manifold per touching part (convex parts, triangle meshes, soft
// bodies) keep Bullet's default pools.
TEST(WorldAllocation, ScenesOfPartsKeepBulletsDefaultPools) {
  for (const char* name : {"concave-mesh", "soft-ball-pinch"}) {
    const test_support::TestContext ctx(name);
    EXPECT_EQ(collisionPools(ctx.scene()).m_defaultMaxPersistentManifoldPoolSize, 4096) << name;
  }
}

TEST(WorldAllocation, NoHeapAllocationPerStepWithTheOrientedPad) {
  for (const PatchFill fill : {PatchFill::kRing, PatchFill::kFilled}) {
    PatchSettings pad;
    pad.pad_model = PadModel::kOriented;
    pad.fill = fill;
    EXPECT_EQ(allocationsOfPressedBoxSteps(ContactSolver::kPoints, pad), 0) << fill;
    EXPECT_EQ(allocationsOfPressedBoxSteps(ContactSolver::kAggregate, pad), 0) << fill;
    pad.model = ContactModel::kSoftFinger;
    EXPECT_EQ(allocationsOfPressedBoxSteps(ContactSolver::kPoints, pad), 0) << "soft finger";
  }
}

}  // namespace
}  // namespace gf::sim

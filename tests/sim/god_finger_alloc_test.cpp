// computePatch must not allocate in steady state. Counts every operator new of this process.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <random>

#include "sim/god_finger.hpp"
#include "sim/primitives.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace gf::sim {
namespace {

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
  const long before = g_allocations.load();
  std::size_t sgos = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto [c, v] = contact();
    computePatch(sphere, c, v, s, p);
    sgos += p.sgos.size();
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(sgos, 2000u * 16u);
}

}  // namespace
}  // namespace gf::sim

// Heap allocations of this process, counted by a replaced operator new (tests/alloc_counter.cpp,
// linked into gf_alloc_tests only: sanitizers replace the allocator themselves).
#pragma once

namespace gf::test {

/// operator new calls so far (and countAllocation's), from any thread.
long allocations();
/// Counts an allocation made another way (Bullet's btAlignedAlloc hook).
void countAllocation();

}  // namespace gf::test

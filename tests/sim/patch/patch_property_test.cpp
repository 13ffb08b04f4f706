// The patch's properties over 10^4 random and adversarial patches (the default run).
#include <gtest/gtest.h>

#include "patch_property.hpp"

namespace gf::sim::testing {
namespace {

TEST(PatchProperty, TenThousandPatchesStayFiniteOnTheSurfaceAndBounded) { expectSweepHolds(2013, 10'000); }

// The same sweep with every patch also computed from walks carried from a micrometre earlier:
// within 1e-9 m of the cold patch, most walks carried.
TEST(PatchProperty, WarmStartedWalksAgreeWithColdOnesOverTheSweep) { expectSweepHolds(2013, 10'000, true); }

}  // namespace
}  // namespace gf::sim::testing

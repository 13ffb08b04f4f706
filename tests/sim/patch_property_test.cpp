// The patch's properties over 10^4 random and adversarial patches (the default run).
#include <gtest/gtest.h>

#include "patch_property.hpp"

namespace gf::sim::testing {
namespace {

TEST(PatchProperty, TenThousandPatchesStayFiniteOnTheSurfaceAndBounded) { expectSweepHolds(2013, 10'000); }

}  // namespace
}  // namespace gf::sim::testing

// The patch's properties over 10^6 random and adversarial patches: ctest label "long", run with
// `ctest --preset long` (not in the default run).
#include <gtest/gtest.h>

#include "patch_property.hpp"

namespace gf::sim::testing {
namespace {

TEST(PatchPropertyLong, MillionPatchesStayFiniteOnTheSurfaceAndBounded) { expectSweepHolds(3013, 1'000'000); }

}  // namespace
}  // namespace gf::sim::testing

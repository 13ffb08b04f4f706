// The patch's properties over 10^6 random and adversarial patches: ctest label "long", run with
// `ctest --preset long` (not in the default run).
#include <gtest/gtest.h>

#include "patch_property.hpp"

namespace gf::sim::testing {
namespace {

TEST(PatchPropertyLong, MillionPatchesStayFiniteOnTheSurfaceAndBounded) {
  const PropertySweep sweep = sweepPatchProperties(3013, 1'000'000);
  EXPECT_EQ(sweep.patches, 1'000'000);
  EXPECT_EQ(sweep.failures, 0) << sweep.first_failure;
  EXPECT_GT(sweep.sgos, 10 * sweep.patches);
  std::printf("%ld patches on %ld meshes, %ld points checked, %ld failures\n", sweep.patches, sweep.meshes, sweep.sgos,
              sweep.failures);
}

}  // namespace
}  // namespace gf::sim::testing

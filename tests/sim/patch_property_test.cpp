// The patch's properties over 10^4 random and adversarial patches (the default run).
#include <gtest/gtest.h>

#include "patch_property.hpp"

namespace gf::sim::testing {
namespace {

TEST(PatchProperty, TenThousandPatchesStayFiniteOnTheSurfaceAndBounded) {
  const PropertySweep sweep = sweepPatchProperties(2013, 10'000);
  EXPECT_EQ(sweep.patches, 10'000);
  EXPECT_EQ(sweep.failures, 0) << sweep.first_failure;
  // The sweep must exercise the walk, not only reject or skip: most patches carry points.
  EXPECT_GT(sweep.sgos, 10 * sweep.patches);
  RecordProperty("patches", std::to_string(sweep.patches));
  RecordProperty("points", std::to_string(sweep.sgos));
  std::printf("%ld patches on %ld meshes, %ld points checked\n", sweep.patches, sweep.meshes, sweep.sgos);
}

}  // namespace
}  // namespace gf::sim::testing

// Pure parts of the scene description: how much of a load acts at a given time.
#include "sim/scene/scene_desc.hpp"

#include <gtest/gtest.h>

namespace gf::sim {
namespace {

TEST(LoadFactor, ZeroBeforeStartThenTheRampThenOneUntilStop) {
  LoadDesc load;
  load.start = 0.5;
  load.ramp = 0.25;
  load.stop = 2.0;
  EXPECT_EQ(loadFactor(load, 0.0), 0.0);
  EXPECT_EQ(loadFactor(load, 0.499), 0.0);
  EXPECT_EQ(loadFactor(load, 0.5), 0.0) << "the ramp grows from zero";
  EXPECT_DOUBLE_EQ(loadFactor(load, 0.5625), 0.25);
  EXPECT_DOUBLE_EQ(loadFactor(load, 0.625), 0.5);
  EXPECT_EQ(loadFactor(load, 0.75), 1.0);
  EXPECT_EQ(loadFactor(load, 1.999), 1.0);
  EXPECT_EQ(loadFactor(load, 2.0), 0.0) << "inactive at stop";
  EXPECT_EQ(loadFactor(load, 7.0), 0.0);
}

TEST(LoadFactor, ZeroRampIsAStepAndNoStopHoldsForever) {
  LoadDesc load;
  load.start = 1.0;
  EXPECT_EQ(loadFactor(load, 0.999), 0.0);
  EXPECT_EQ(loadFactor(load, 1.0), 1.0);
  EXPECT_EQ(loadFactor(load, 1e6), 1.0);
  load.stop = 1.5;
  load.ramp = 1.0;  // stopped half way up the ramp
  EXPECT_DOUBLE_EQ(loadFactor(load, 1.4), 0.4);
  EXPECT_EQ(loadFactor(load, 1.5), 0.0);
}

}  // namespace
}  // namespace gf::sim

// Image comparison of the visual-regression test.
#include "render/frames/image_compare.hpp"

#include <gtest/gtest.h>

namespace gf {
namespace {

// The comparison itself: a changed picture is caught, an identical one passes.
TEST(ImageCompare, CatchesAChangedRegionAndPassesAnIdenticalImage) {
  render::Image a{40, 20, std::vector<std::uint8_t>(40 * 20 * 3, 100)};
  render::Image b = a;
  EXPECT_EQ(render::compareImages(a, b, 0).differing_share, 0.0);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) b.rgb[3 * (y * 40 + x)] = 200;  // 20 of 800 pixels
  }
  const render::ImageDifference d = render::compareImages(b, a, 24);
  EXPECT_DOUBLE_EQ(d.differing_share, 20.0 / 800.0);
  EXPECT_EQ(d.max_channel_difference, 100);
  EXPECT_EQ(render::compareImages(b, a, 100).differing_share, 0.0);  // within tolerance
  const render::Image diff = render::differenceImage(b, a, 24);
  EXPECT_EQ(diff.rgb[0], 255);
  EXPECT_EQ(diff.rgb[1], 0);
}

}  // namespace
}  // namespace gf

// shrinkFactor and shrinkByBlocks: each output pixel the mean of its block, in closed form.
#include "render/frames/shrink.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <random>

namespace gf::render {
namespace {

Image grey(int width, int height, const std::vector<int>& values) {
  Image image{width, height, {}};
  for (int v : values) image.rgb.insert(image.rgb.end(), 3, static_cast<std::uint8_t>(v));
  return image;
}

int at(const Image& image, int x, int y) { return image.rgb[3 * (static_cast<std::size_t>(y) * image.width + x)]; }

// The largest whole factor that keeps the copy at least as wide as it is shown.
TEST(Shrink, TheFactorKeepsTheCopyAtLeastAsWideAsShown) {
  EXPECT_EQ(shrinkFactor(1280, 0), 1);
  EXPECT_EQ(shrinkFactor(1280, 1280), 1);
  EXPECT_EQ(shrinkFactor(1280, 2000), 1);
  EXPECT_EQ(shrinkFactor(1280, 1090), 1);  // 1280 / 2 = 640 would be narrower than shown
  EXPECT_EQ(shrinkFactor(1280, 640), 2);
  EXPECT_EQ(shrinkFactor(1280, 427), 2);   // 426 whole blocks of 3 < 427
  EXPECT_EQ(shrinkFactor(1280, 426), 3);
  EXPECT_EQ(shrinkFactor(1280, 16), 80);
}

// Halving: each pixel the mean of a 2x2 block, rounded to the nearest byte.
TEST(Shrink, HalvingAveragesEachTwoByTwoBlock) {
  const Image in = grey(4, 2, {0, 10, 100, 200,  //
                               20, 30, 50, 251});
  Image out;
  shrinkByBlocks(in, 2, out);
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 1);
  EXPECT_EQ(at(out, 0, 0), 15);   // (0 + 10 + 20 + 30) / 4
  EXPECT_EQ(at(out, 1, 0), 150);  // (100 + 200 + 50 + 251) / 4 = 150.25
}

// Blocks cut short by the frame's edge average the pixels they hold: 5x4 by 3 is 2x2 pixels,
// of 3x3, 2x3, 3x1 and 2x1 source pixels.
TEST(Shrink, EdgeBlocksAverageThePixelsTheyHold) {
  std::vector<int> values(20);
  std::iota(values.begin(), values.end(), 0);  // pixel (x, y) = 5 y + x
  Image out;
  shrinkByBlocks(grey(5, 4, values), 3, out);
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 2);
  EXPECT_EQ(at(out, 0, 0), 6);   // mean of x 0..2, y 0..2: 1 + 5
  EXPECT_EQ(at(out, 1, 0), 9);   // x 3..4, y 0..2: 3.5 + 5 = 8.5, rounded up
  EXPECT_EQ(at(out, 0, 1), 16);  // x 0..2, y 3: 1 + 15
  EXPECT_EQ(at(out, 1, 1), 19);  // x 3..4, y 3: 3.5 + 15 = 18.5, rounded up
}

// No source pixel is skipped or counted twice: the mean of a random picture is kept, to the
// rounding of each output pixel, at every factor from 2 to 5 (1280 x 720 is cut short by 3).
TEST(Shrink, TheWholePicturesMeanIsKept) {
  std::mt19937 random(7);
  Image in{1280, 720, std::vector<std::uint8_t>(1280 * 720 * 3)};
  for (std::uint8_t& c : in.rgb) c = static_cast<std::uint8_t>(random() % 256);
  const auto mean = [](const Image& image) {
    return std::accumulate(image.rgb.begin(), image.rgb.end(), 0.0) / static_cast<double>(image.rgb.size());
  };
  for (int factor = 2; factor <= 5; ++factor) {
    Image out;
    shrinkByBlocks(in, factor, out);
    EXPECT_EQ(out.width, (1280 + factor - 1) / factor);
    EXPECT_EQ(out.height, (720 + factor - 1) / factor);
    // Weighted by block size, the means agree; unweighted, the short edge blocks shift it a little.
    EXPECT_NEAR(mean(out), mean(in), 0.6) << factor;
  }
}

// A factor of 1 gives the image unchanged.
TEST(Shrink, AFactorOfOneLeavesTheImageAsItIs) {
  const Image in = grey(3, 1, {1, 2, 3});
  Image out;
  shrinkByBlocks(in, 1, out);
  EXPECT_EQ(out.width, 3);
  EXPECT_EQ(out.rgb, in.rgb);
}

}  // namespace
}  // namespace gf::render

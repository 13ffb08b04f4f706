// Visual regression: every reference picture is rendered offline and compared with its golden
// in screenshots/ (per-channel tolerance, maximum share of differing pixels). On failure the
// actual picture and a difference image go to <build>/visual-diff/. Re-bless with
// `build/release/godfinger screenshots --out screenshots` from the repository root.
#include <gtest/gtest.h>

#include <filesystem>

#include "app/screenshots.hpp"
#include "render/image_compare.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

class VisualRegression : public ::testing::TestWithParam<Shot> {};

TEST_P(VisualRegression, MatchesGolden) {
  const Shot& shot = GetParam();
  const fs::path golden = fs::path(GF_SOURCE_DIR) / "screenshots" / (shot.name + ".png");
  ASSERT_TRUE(fs::exists(golden)) << golden << " missing: bless with godfinger screenshots --out screenshots";
  const render::Image expected = render::readPng(golden.string());
  const render::Image actual = renderShot(shot);
  const render::ImageDifference d = render::compareImages(actual, expected, kShotChannelThreshold);
  if (d.same_size && d.differing_share <= kShotMaxDifferingShare) return;
  const fs::path out = fs::path(GF_BINARY_DIR) / "visual-diff";
  fs::create_directories(out);
  render::writePng((out / (shot.name + "-actual.png")).string(), actual);
  render::writePng((out / (shot.name + "-diff.png")).string(),
                   render::differenceImage(actual, expected, kShotChannelThreshold));
  ADD_FAILURE() << shot.name << ": " << 100.0 * d.differing_share << " % of pixels differ by more than "
                << kShotChannelThreshold << " (allowed " << 100.0 * kShotMaxDifferingShare
                << " %); see " << out.string();
}

INSTANTIATE_TEST_SUITE_P(Screenshots, VisualRegression, ::testing::ValuesIn(referenceShots()),
                         [](const ::testing::TestParamInfo<Shot>& param) {
                           std::string name = param.param.name;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

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
}  // namespace gf::app

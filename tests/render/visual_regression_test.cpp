// Visual regression: every reference picture is rendered offline and compared with its golden
// in screenshots/ (per-channel tolerance, maximum share of differing pixels). On failure the
// actual picture and a difference image go to <build>/visual-diff/. Re-bless with
// `build/release/godfinger screenshots --out screenshots` from the repository root.
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>

#include "app/compare/screenshots.hpp"
#include "render/frames/image_compare.hpp"

namespace gf::app {

// How gtest (and `ctest -N`) names a shot: "fig5-push-ball at 1.5 s".
void PrintTo(const Shot& shot, std::ostream* out) { *out << shot.name << " at " << shot.time << " s"; }

namespace {

namespace fs = std::filesystem;

class VisualRegression : public ::testing::TestWithParam<Shot> {};

TEST_P(VisualRegression, MatchesGolden) {
  const Shot& shot = GetParam();
#ifdef GF_UNDER_SANITIZER
  // A soft body's 4 s take minutes under the sanitizers; the release build compares them.
  if (shot.scene.rfind("soft-", 0) == 0) GTEST_SKIP() << shot.name << ": a soft body's scene, compared by the release build";
#endif
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

}  // namespace
}  // namespace gf::app

// PNG files: encoding round trip and errors that name the file.
#include "render/frames/image.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include "tests/scratch.hpp"

namespace gf {
namespace {

namespace fs = std::filesystem;

TEST(Png, RoundTripsExactly) {
  render::Image image{37, 11, {}};
  for (int i = 0; i < 37 * 11 * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7919) % 251));
  const fs::path path = gf::test::scratchRoot() / "gf_png_roundtrip.png";
  render::writePng(path.string(), image);
  const render::Image back = render::readPng(path.string());
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.rgb, image.rgb);
}

// The encoder tells the last image it encoded from any other by its pixels and its size: one
// byte changed in the last row, or the same bytes as another shape, is not the same image.
TEST(Png, AnEncoderKnowsTheLastImageItEncoded) {
  render::Image image{37, 11, {}};
  for (int i = 0; i < 37 * 11 * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7919) % 251));
  render::PngEncoder encoder;
  EXPECT_FALSE(encoder.sameAsLast(image));  // nothing encoded yet
  const std::vector<std::uint8_t> bytes = encoder.encode(image);
  EXPECT_EQ(bytes, render::encodePng(image));
  EXPECT_TRUE(encoder.sameAsLast(image));
  render::Image changed = image;
  changed.rgb.back() ^= 1;
  EXPECT_FALSE(encoder.sameAsLast(changed));
  render::Image reshaped{11, 37, image.rgb};
  EXPECT_FALSE(encoder.sameAsLast(reshaped));
  encoder.encode(changed);
  EXPECT_TRUE(encoder.sameAsLast(changed));
  EXPECT_FALSE(encoder.sameAsLast(image));
}

TEST(Png, ReadingAMissingFileNamesIt) {
  try {
    render::readPng("/nonexistent/golden.png");
    FAIL() << "no error";
  } catch (const render::ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/golden.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace gf

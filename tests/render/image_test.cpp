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

// PNG files: encoding round trip and errors that name the file.
#include "render/frames/image.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
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

// The scanlines a PNG's one IDAT chunk inflates to, by zlib (which checks the stream's ends and
// its Adler-32, where stb_image does not); empty when zlib finds it invalid.
std::vector<std::uint8_t> inflatedRows(const std::vector<std::uint8_t>& png, std::size_t rows_size) {
  // Signature (8), IHDR (4 + 4 + 13 + 4), then the IDAT's length and type.
  const std::size_t at = 8 + 25;
  const std::uint32_t length = (std::uint32_t{png[at]} << 24) | (std::uint32_t{png[at + 1]} << 16) |
                               (std::uint32_t{png[at + 2]} << 8) | std::uint32_t{png[at + 3]};
  EXPECT_EQ(std::memcmp(png.data() + at + 4, "IDAT", 4), 0);
  std::vector<std::uint8_t> rows(rows_size + 1);  // one byte more: a longer stream shows
  uLongf size = static_cast<uLongf>(rows.size());
  if (uncompress(rows.data(), &size, png.data() + at + 8, length) != Z_OK) return {};
  rows.resize(size);
  return rows;
}

// A sequence whose frames change in a few bands (a held scene's time stamp) is encoded band by
// band, the unchanged bands' bytes kept: every file must still be a valid zlib stream (zlib's
// inflate checks the Adler-32 combined from the bands') holding that frame's pixels, through a
// frame that changed everywhere (deflated whole), a changed size and a last band shorter than the
// others.
TEST(Png, BandedFramesAreValidAndHoldTheirPixels) {
  const int w = 29, h = 5 * render::kPngBandRows + 3;  // 6 bands, the last of 3 rows
  render::Image image{w, h, {}};
  for (int i = 0; i < w * h * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7919) % 251));
  const auto rowsOf = [](const render::Image& im) {
    std::vector<std::uint8_t> rows;
    for (int y = 0; y < im.height; ++y) {
      rows.push_back(0);
      rows.insert(rows.end(), im.rgb.begin() + 3 * y * im.width, im.rgb.begin() + 3 * (y + 1) * im.width);
    }
    return rows;
  };
  const auto setPixel = [](render::Image& im, int x, int y, std::uint8_t v) { im.rgb[3 * (y * im.width + x)] = v; };
  render::PngEncoder encoder;
  const fs::path path = gf::test::scratchRoot() / "gf_png_banded.png";
  const auto check = [&](const render::Image& im, long banded, long bands, const char* what) {
    SCOPED_TRACE(what);
    const std::vector<std::uint8_t> png = encoder.encode(im);
    EXPECT_EQ(encoder.bandedImages(), banded);
    EXPECT_EQ(encoder.bandsCompressed(), bands);
    EXPECT_EQ(inflatedRows(png, rowsOf(im).size()), rowsOf(im));
    render::writeFileAtomically(path.string(), png);
    const render::Image back = render::readPng(path.string());
    EXPECT_EQ(back.width, im.width);
    EXPECT_EQ(back.height, im.height);
    EXPECT_EQ(back.rgb, im.rgb);
  };
  check(image, 0, 0, "the first frame: whole");
  setPixel(image, 3, 2, 1);
  check(image, 1, 6, "one band changed: banded, every band compressed (none kept yet)");
  setPixel(image, 0, h - 1, 2);
  check(image, 2, 7, "the short last band changed: only it compressed");
  check(image, 3, 7, "the same pixels: every band kept");
  setPixel(image, 5, render::kPngBandRows, 3);
  check(image, 4, 8, "the second band changed");
  for (std::uint8_t& v : image.rgb) v = static_cast<std::uint8_t>(v + 1);
  check(image, 4, 8, "every band changed: whole");
  setPixel(image, 7, 40, 4);
  check(image, 5, 14, "banded again after a whole frame: every band compressed");
  render::Image other{w + 1, h, std::vector<std::uint8_t>(static_cast<std::size_t>((w + 1) * h * 3), 9)};
  check(other, 5, 14, "another size: whole");
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

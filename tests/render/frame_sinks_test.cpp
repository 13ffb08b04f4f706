// The PNG sequence sink: every frame a file named by its index, equal frames written from the
// bytes of the one before without encoding them again.
#include "render/frames/frame_sinks.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "tests/scratch.hpp"

namespace gf {
namespace {

namespace fs = std::filesystem;

render::Image pattern(int seed) {
  render::Image image{24, 9, {}};
  for (int i = 0; i < 24 * 9 * 3; ++i) image.rgb.push_back(static_cast<std::uint8_t>((i * 7919 + seed) % 251));
  return image;
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Frames A, A, B, A: the second A is a repeat (same file bytes as the first), B and the last A
// are encoded (each differs from the frame before it); every file reads back as its frame.
TEST(PngSequence, EqualFramesRepeatTheFileAndOthersAreEncoded) {
  const fs::path folder = gf::test::scratchRoot() / "gf_png_sequence_repeat";
  fs::remove_all(folder);
  const render::Image a = pattern(0), b = pattern(1);
  render::SinkStats stats;
  {
    render::PngSequenceWriter writer(folder.string(), 1);
    for (const render::Image* frame : {&a, &a, &b, &a}) writer.push(render::Image(*frame));
    stats = writer.finish();
  }
  EXPECT_EQ(stats.frames, 4);
  EXPECT_EQ(stats.repeated, 1);
  EXPECT_EQ(fileBytes(folder / "000001.png"), fileBytes(folder / "000000.png"));
  EXPECT_EQ(fileBytes(folder / "000003.png"), fileBytes(folder / "000000.png"));
  EXPECT_EQ(render::readPng((folder / "000001.png").string()).rgb, a.rgb);
  EXPECT_EQ(render::readPng((folder / "000002.png").string()).rgb, b.rgb);
  EXPECT_EQ(render::readPng((folder / "000003.png").string()).rgb, a.rgb);
  for (const auto& entry : fs::directory_iterator(folder)) EXPECT_EQ(entry.path().extension(), ".png");
}

// A frame one byte away from the one before is encoded, not repeated.
TEST(PngSequence, AFrameOneByteOffIsEncoded) {
  const fs::path folder = gf::test::scratchRoot() / "gf_png_sequence_one_byte";
  fs::remove_all(folder);
  const render::Image a = pattern(0);
  render::Image near = a;
  near.rgb[near.rgb.size() / 2] ^= 1;
  render::SinkStats stats;
  {
    render::PngSequenceWriter writer(folder.string(), 1);
    writer.push(render::Image(a));
    writer.push(render::Image(near));
    writer.push(render::Image(near));
    stats = writer.finish();
  }
  EXPECT_EQ(stats.frames, 3);
  EXPECT_EQ(stats.repeated, 1);  // the third only
  EXPECT_EQ(render::readPng((folder / "000001.png").string()).rgb, near.rgb);
  EXPECT_EQ(fileBytes(folder / "000002.png"), fileBytes(folder / "000001.png"));
}

}  // namespace
}  // namespace gf

// 8-bit RGB images in memory, rows from top to bottom, and their PNG files.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct libdeflate_compressor;

namespace gf::render {

/// An RGB8 image; pixel (x, y) starts at rgb[3 * (y * width + x)], y = 0 is the top row.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

/// A PNG file that cannot be read or written; what() names the file.
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Encodes `image` as PNG bytes: rows unfiltered (filter type 0), deflated into a zlib stream
/// by libdeflate at `zlib_level` (1 = fastest, 12 = smallest). Any thread; allocates.
std::vector<std::uint8_t> encodePng(const Image& image, int zlib_level = 1);

/// A PNG encoder as encodePng, keeping its scratch between images: the last image's rows, which
/// tell whether the next image is the same without a copy of it kept. One thread at a time.
class PngEncoder {
 public:
  /// libdeflate at `zlib_level` (1 = fastest, 12 = smallest). Throws ImageError.
  explicit PngEncoder(int zlib_level = 1);
  ~PngEncoder();
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;
  int level() const { return level_; }
  /// The PNG bytes of `image`, as encodePng. Throws ImageError.
  std::vector<std::uint8_t> encode(const Image& image);
  /// Whether `image` has the size and pixels of the last image encode() returned bytes for
  /// (false before the first, and after an encode that threw).
  bool sameAsLast(const Image& image) const;

 private:
  int level_;
  libdeflate_compressor* compressor_;
  std::vector<std::uint8_t> rows_;  // the last image's scanlines, each with its filter byte
  std::unique_ptr<std::uint8_t[]> packed_;
  std::size_t packed_room_ = 0;
  int rows_width_ = 0, rows_height_ = 0;  // the image rows_ holds (0: none)
};

/// Writes encodePng(image) to `path` through a temporary file and a rename, so a reader never
/// sees half a file. Throws ImageError naming the path.
void writePng(const std::string& path, const Image& image, int zlib_level = 1);

/// Writes `bytes` to `path` as writePng does (a temporary file `path.part`, removed when the
/// write fails, then a rename). Throws ImageError naming the path. Any thread.
void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// Reads a PNG (any bit depth and colour type stb_image reads) as RGB8. Throws ImageError.
Image readPng(const std::string& path);

}  // namespace gf::render

// 8-bit RGB images in memory, rows from top to bottom, and their PNG files.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct libdeflate_compressor;
struct z_stream_s;

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
/// tell whether the next image is the same without a copy of it kept, and which of its bands of
/// kPngBandRows rows changed. A frame in a sequence that differs from the one before in at most
/// a quarter of its bands (a held scene whose time stamp and labels change) is deflated band by
/// band by zlib (level 1, each band a flushed, independent part of one zlib stream): bands that
/// did not change keep their compressed bytes from the frame before, so only the changed ones are
/// compressed. Its file is valid PNG holding the same pixels; it is bigger than libdeflate's
/// (about a fifth). Other frames are deflated whole by libdeflate. One thread at a time.
class PngEncoder {
 public:
  /// libdeflate at `zlib_level` (1 = fastest, 12 = smallest) for whole images. Throws ImageError.
  explicit PngEncoder(int zlib_level = 1);
  ~PngEncoder();
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;
  int level() const { return level_; }
  /// The PNG bytes of `image`, as encodePng but for the banded deflate. Throws ImageError.
  std::vector<std::uint8_t> encode(const Image& image);
  /// The PNG bytes of `image` deflated whole, as encodePng's (the same bytes whatever was encoded
  /// before). Throws ImageError.
  std::vector<std::uint8_t> encodeWhole(const Image& image);
  /// Whether `image` has the size and pixels of the last image encode() returned bytes for
  /// (false before the first, and after an encode that threw).
  bool sameAsLast(const Image& image) const;
  /// Images encoded band by band, and the bands compressed for them (the others were kept).
  long bandedImages() const { return banded_images_; }
  long bandsCompressed() const { return bands_compressed_; }

 private:
  std::size_t markChangedBands(const Image& image, std::size_t band_count);
  std::size_t deflateBanded(const Image& image, bool kept_parts_valid);
  std::size_t deflateWhole(const Image& image);
  std::vector<std::uint8_t> pngBytes(const Image& image, std::size_t packed_size);
  void compressBand(std::size_t band, std::size_t row_bytes, int rows);
  int level_;
  libdeflate_compressor* compressor_;
  std::unique_ptr<z_stream_s> zlib_;  // made at the first banded image
  std::vector<std::uint8_t> rows_;  // the last image's scanlines, each with its filter byte
  std::unique_ptr<std::uint8_t[]> packed_;
  std::size_t packed_room_ = 0;
  int rows_width_ = 0, rows_height_ = 0;  // the image rows_ holds (0: none)
  // Banded: each band's deflate part and its rows' Adler-32, valid for rows_ when bands_valid_.
  std::vector<std::vector<std::uint8_t>> bands_;
  std::vector<std::uint32_t> band_adler_;
  std::vector<char> changed_;
  bool bands_valid_ = false;
  long banded_images_ = 0, bands_compressed_ = 0;
};

/// Rows in a band of PngEncoder's banded deflate (a 1280×720 frame: 45 bands of 61 kB).
inline constexpr int kPngBandRows = 16;

/// Writes encodePng(image) to `path` through a temporary file and a rename, so a reader never
/// sees half a file. Throws ImageError naming the path.
void writePng(const std::string& path, const Image& image, int zlib_level = 1);

/// Writes `bytes` to `path` as writePng does (a temporary file `path.part`, removed when the
/// write fails, then a rename). Throws ImageError naming the path. Any thread.
void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// Reads a PNG (any bit depth and colour type stb_image reads) as RGB8. Throws ImageError.
Image readPng(const std::string& path);

}  // namespace gf::render

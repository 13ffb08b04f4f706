#include "render/frames/image.hpp"

#include <libdeflate.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace gf::render {
namespace {

void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift : {24, 16, 8, 0}) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// One PNG chunk: length, type, data, CRC over type and data.
void appendChunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data,
                 std::size_t size) {
  appendU32(out, static_cast<std::uint32_t>(size));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + size);
  const std::uint32_t crc = libdeflate_crc32(0, out.data() + start, size + 4);
  appendU32(out, static_cast<std::uint32_t>(crc));
}

// Scanlines with a filter byte each, all 0 (no filter). Measured on 1280x720 frames of fig8 and
// of the overlay demo with libdeflate level 1: unfiltered rows compress in 11 ms to 349 kB,
// "Up"-filtered ones in 15 ms (+2 ms filtering) to 462 kB. Flat colours, fog and the grid
// repeat along rows, which the matcher finds without a filter.
void filterRows(const Image& image, std::vector<std::uint8_t>& rows) {
  const std::size_t stride = 3 * static_cast<std::size_t>(image.width);
  rows.resize((stride + 1) * image.height);
  for (int y = 0; y < image.height; ++y) {
    std::uint8_t* dst = rows.data() + y * (stride + 1);
    const std::uint8_t* src = image.rgb.data() + y * stride;
    dst[0] = 0;
    std::copy(src, src + stride, dst + 1);
  }
}

}  // namespace

PngEncoder::PngEncoder(int zlib_level)
    : level_(zlib_level), compressor_(libdeflate_alloc_compressor(std::clamp(zlib_level, 0, 12))) {
  if (!compressor_) throw ImageError("cannot allocate a deflate compressor");
}

PngEncoder::~PngEncoder() {
  libdeflate_free_compressor(compressor_);
  if (zlib_) deflateEnd(zlib_.get());
}

// Deflates band `band` of rows_ on its own (no match reaches into another band) into bands_,
// ending byte-aligned without a final block (a sync flush), so that the bands' parts joined make
// one deflate stream once a final empty block follows.
void PngEncoder::compressBand(std::size_t band, std::size_t row_bytes, int rows) {
  z_stream& z = *zlib_;
  std::uint8_t* in = rows_.data() + band * kPngBandRows * row_bytes;
  const auto in_size = static_cast<uLong>(row_bytes * static_cast<std::size_t>(rows));
  if (deflateReset(&z) != Z_OK) throw ImageError("could not compress a frame (zlib reset)");
  std::vector<std::uint8_t>& out = bands_[band];
  out.resize(deflateBound(&z, in_size) + 16);  // the bound is for a finished stream; a flush adds 5 bytes
  z.next_in = in;
  z.avail_in = static_cast<uInt>(in_size);
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  if (deflate(&z, Z_SYNC_FLUSH) != Z_OK || z.avail_in != 0 || z.avail_out == 0) {
    throw ImageError("could not compress a frame (zlib)");
  }
  out.resize(out.size() - z.avail_out);
  band_adler_[band] = static_cast<std::uint32_t>(adler32(1L, in, static_cast<uInt>(in_size)));
  ++bands_compressed_;
}

// Marks in changed_ the bands of kPngBandRows rows in which `image` differs from the image rows_
// holds, and returns how many (all of them when the sizes differ).
std::size_t PngEncoder::markChangedBands(const Image& image, std::size_t band_count) {
  const std::size_t stride = 3 * static_cast<std::size_t>(image.width);
  changed_.assign(band_count, 1);
  const bool same_size = rows_width_ == image.width && rows_height_ == image.height &&
                         image.rgb.size() == stride * static_cast<std::size_t>(image.height);
  if (!same_size) return band_count;
  std::size_t changed_count = 0;
  for (std::size_t b = 0; b < band_count; ++b) {
    const int first = static_cast<int>(b) * kPngBandRows;
    const int end = std::min(image.height, first + kPngBandRows);
    bool differs = false;
    for (int y = first; y < end && !differs; ++y) {
      differs = std::memcmp(rows_.data() + static_cast<std::size_t>(y) * (stride + 1) + 1,
                            image.rgb.data() + static_cast<std::size_t>(y) * stride, stride) != 0;
    }
    changed_[b] = differs ? 1 : 0;
    changed_count += differs ? 1 : 0;
  }
  return changed_count;
}

// Deflates the changed bands (all of them when the kept parts are not of rows_) and joins the
// parts into packed_ as one zlib stream; returns its size.
std::size_t PngEncoder::deflateBanded(const Image& image, bool kept_parts_valid) {
  const std::size_t stride = 3 * static_cast<std::size_t>(image.width);
  const std::size_t row_bytes = stride + 1;
  const std::size_t band_count = changed_.size();
  if (!zlib_) {
    zlib_ = std::make_unique<z_stream>();
    if (deflateInit2(zlib_.get(), 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
      zlib_.reset();
      throw ImageError("could not compress a frame (zlib init)");
    }
  }
  bands_.resize(band_count);
  band_adler_.resize(band_count);
  uLong adler = 1;
  std::size_t size = 2 + 2 + 4;  // zlib header, the final empty block, Adler-32
  for (std::size_t b = 0; b < band_count; ++b) {
    const int first = static_cast<int>(b) * kPngBandRows;
    const int rows = std::min(image.height - first, kPngBandRows);
    if (changed_[b] || !kept_parts_valid) {
      for (int y = first; y < first + rows; ++y) {
        std::uint8_t* dst = rows_.data() + static_cast<std::size_t>(y) * row_bytes;
        dst[0] = 0;
        std::memcpy(dst + 1, image.rgb.data() + static_cast<std::size_t>(y) * stride, stride);
      }
      compressBand(b, row_bytes, rows);
    }
    adler = adler32_combine(adler, band_adler_[b], static_cast<z_off_t>(row_bytes * static_cast<std::size_t>(rows)));
    size += bands_[b].size();
  }
  if (packed_room_ < size) packed_.reset(new std::uint8_t[size]), packed_room_ = size;
  std::uint8_t* out = packed_.get();
  *out++ = 0x78, *out++ = 0x01;  // deflate, 32 kB window, fastest (0x7801 is a multiple of 31)
  for (const std::vector<std::uint8_t>& part : bands_) out = std::copy(part.begin(), part.end(), out);
  *out++ = 0x03, *out++ = 0x00;  // a final, empty block of fixed codes
  for (int shift : {24, 16, 8, 0}) *out++ = static_cast<std::uint8_t>(adler >> shift);
  ++banded_images_;
  return size;
}

// Deflates the whole image by libdeflate into packed_; returns the stream's size.
std::size_t PngEncoder::deflateWhole(const Image& image) {
  filterRows(image, rows_);
  // The output's room, left uninitialized: a frame compresses to a seventh of its bound, and
  // zeroing it wrote all of it (pages the heap had not used before stay unused).
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor_, rows_.size());
  if (packed_room_ < bound) packed_.reset(new std::uint8_t[bound]), packed_room_ = bound;
  const std::size_t size = libdeflate_zlib_compress(compressor_, rows_.data(), rows_.size(), packed_.get(), bound);
  if (size == 0) throw ImageError("could not compress a frame");
  return size;
}

std::vector<std::uint8_t> PngEncoder::encode(const Image& image) {
  const std::size_t band_count = (static_cast<std::size_t>(image.height) + kPngBandRows - 1) / kPngBandRows;
  const std::size_t changed_count = markChangedBands(image, band_count);
  const bool banded = band_count > 0 && 4 * changed_count <= band_count;
  const bool kept_parts_valid = bands_valid_;
  rows_width_ = rows_height_ = 0;  // until the rows hold this image and it compressed
  bands_valid_ = false;
  // The first banded image of a sequence compresses all its bands (the image before was deflated
  // whole); after it, only the changed bands' rows are copied and compressed.
  const std::size_t packed_size = banded ? deflateBanded(image, kept_parts_valid) : deflateWhole(image);
  std::vector<std::uint8_t> out = pngBytes(image, packed_size);
  bands_valid_ = banded;
  return out;
}

std::vector<std::uint8_t> PngEncoder::encodeWhole(const Image& image) {
  rows_width_ = rows_height_ = 0;
  bands_valid_ = false;
  return pngBytes(image, deflateWhole(image));
}

// The PNG file around packed_'s first `packed_size` bytes, rows_ then holding `image`'s rows.
std::vector<std::uint8_t> PngEncoder::pngBytes(const Image& image, std::size_t packed_size) {
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  out.reserve(out.size() + 3 * 12 + 13 + packed_size);
  std::vector<std::uint8_t> header;
  appendU32(header, static_cast<std::uint32_t>(image.width));
  appendU32(header, static_cast<std::uint32_t>(image.height));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, adaptive, no interlace
  appendChunk(out, "IHDR", header.data(), header.size());
  appendChunk(out, "IDAT", packed_.get(), packed_size);
  appendChunk(out, "IEND", nullptr, 0);
  rows_width_ = image.width, rows_height_ = image.height;
  return out;
}

// The rows are filter type 0 (filterRows): each holds its pixels as they are, after its filter
// byte. With another filter this would have to undo it.
bool PngEncoder::sameAsLast(const Image& image) const {
  if (rows_width_ == 0 || image.width != rows_width_ || image.height != rows_height_) return false;
  const std::size_t stride = 3 * static_cast<std::size_t>(image.width);
  if (image.rgb.size() != stride * static_cast<std::size_t>(image.height)) return false;
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* row = rows_.data() + static_cast<std::size_t>(y) * (stride + 1) + 1;
    if (std::memcmp(row, image.rgb.data() + static_cast<std::size_t>(y) * stride, stride) != 0) return false;
  }
  return true;
}

std::vector<std::uint8_t> encodePng(const Image& image, int zlib_level) {
  // One encoder per thread and level, its scratch kept: allocating a compressor costs more than
  // compressing a frame, and clearing fresh megabytes each frame more than a tenth of it.
  thread_local std::unique_ptr<PngEncoder> encoder;
  if (!encoder || encoder->level() != zlib_level) encoder = std::make_unique<PngEncoder>(zlib_level);
  return encoder->encodeWhole(image);
}

void writePng(const std::string& path, const Image& image, int zlib_level) {
  writeFileAtomically(path, encodePng(image, zlib_level));
}

void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);  // no half picture left behind
      throw ImageError(path + ": cannot write (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) throw ImageError(path + ": cannot write: " + ec.message());
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (!pixels) {
    std::string message = path;
    throw ImageError(message.append(": cannot read PNG: ").append(stbi_failure_reason()));
  }
  Image image{w, h, std::vector<std::uint8_t>(pixels, pixels + 3 * static_cast<std::size_t>(w) * h)};
  stbi_image_free(pixels);
  return image;
}

}  // namespace gf::render

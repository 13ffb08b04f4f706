#include "render/frames/image.hpp"

#include <libdeflate.h>

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

PngEncoder::~PngEncoder() { libdeflate_free_compressor(compressor_); }

std::vector<std::uint8_t> PngEncoder::encode(const Image& image) {
  rows_width_ = rows_height_ = 0;  // until the rows hold this image and it compressed
  filterRows(image, rows_);
  // The output's room, left uninitialized: a frame compresses to a seventh of its bound, and
  // zeroing it wrote all of it (pages the heap had not used before stay unused).
  const std::size_t bound = libdeflate_zlib_compress_bound(compressor_, rows_.size());
  if (packed_room_ < bound) packed_.reset(new std::uint8_t[bound]), packed_room_ = bound;
  const std::size_t packed_size = libdeflate_zlib_compress(compressor_, rows_.data(), rows_.size(), packed_.get(), bound);
  if (packed_size == 0) throw ImageError("could not compress a frame");
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
  return encoder->encode(image);
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

#include "render/frames/video_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>

#include <sys/types.h>

namespace gf::render {
namespace {

struct CloseFile {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, CloseFile>;

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::uint64_t bigEndian(const unsigned char* b, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | b[i];
  return v;
}

// ISO base media (MP4, MOV): a sequence of boxes, each [size:4][type:4] (size 1: a 64-bit size
// follows; 0: to the end of the file), covering the file exactly; the index is the `moov` box.
std::optional<std::string> isoMediaProblem(std::FILE* f, std::uint64_t length) {
  bool moov = false;
  for (std::uint64_t at = 0; at < length;) {
    unsigned char head[16];
    if (length - at < 8 || fseeko(f, static_cast<off_t>(at), SEEK_SET) != 0 || std::fread(head, 1, 8, f) != 8) {
      return "a box header is cut off at byte " + std::to_string(at) + " (the file is truncated)";
    }
    std::uint64_t size = bigEndian(head, 4), header = 8;
    if (size == 1) {  // a 64-bit size after the type: the header is 16 bytes
      header = 16;
      if (std::fread(head + 8, 1, 8, f) != 8) return "a box header is cut off at byte " + std::to_string(at);
      size = bigEndian(head + 8, 8);
    } else if (size == 0) {
      size = length - at;
    }
    if (size < header || size > length - at) {
      return "the box at byte " + std::to_string(at) + " runs past the end of the file (the file is truncated)";
    }
    moov = moov || std::string(reinterpret_cast<const char*>(head + 4), 4) == "moov";
    at += size;
  }
  if (!moov) return "no moov box (the index a player needs is written last: the writer did not finish)";
  return std::nullopt;
}

// An EBML variable-length integer at `b` (at most 8 bytes): its length, and its value with the
// length marker removed (all ones: unknown).
std::pair<int, std::uint64_t> ebmlNumber(const unsigned char* b) {
  int n = 1;
  while (n <= 8 && !(b[0] & (0x80 >> (n - 1)))) ++n;
  if (n > 8) return {0, 0};
  std::uint64_t v = b[0] & (0xFFu >> n);
  for (int i = 1; i < n; ++i) v = (v << 8) | b[i];
  return {n, v};
}

// Matroska: the EBML header element, then the Segment (ID 18 53 80 67) with a known size that
// fits the file (ffmpeg writes the size when it finishes the file).
std::optional<std::string> matroskaProblem(std::FILE* f, std::uint64_t length) {
  std::array<unsigned char, 64> b{};
  const std::size_t got = std::fread(b.data(), 1, b.size(), f);
  if (got < 16 || bigEndian(b.data(), 4) != 0x1A45DFA3) return "no EBML header";
  const auto [head_len, head_size] = ebmlNumber(b.data() + 4);
  const std::uint64_t segment = 4 + static_cast<std::uint64_t>(head_len) + head_size;
  if (head_len == 0 || segment + 12 > length || fseeko(f, static_cast<off_t>(segment), SEEK_SET) != 0 ||
      std::fread(b.data(), 1, 12, f) != 12 || bigEndian(b.data(), 4) != 0x18538067) {
    return "no segment after the EBML header (the file is truncated)";
  }
  const auto [size_len, size] = ebmlNumber(b.data() + 4);
  if (size_len == 0 || size == (std::uint64_t{1} << (7 * size_len)) - 1) {
    return "the segment's size was never written (the writer did not finish)";
  }
  if (segment + 4 + static_cast<std::uint64_t>(size_len) + size > length) {
    return "the segment runs past the end of the file (the file is truncated)";
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> videoContainer(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".mp4") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  return std::nullopt;
}

std::optional<std::string> videoFileProblem(const std::string& path, const std::string& container) {
  std::error_code ec;
  const std::uintmax_t length = std::filesystem::file_size(path, ec);
  if (ec) return "cannot be read: " + ec.message();
  if (length == 0) return "is empty";
  const File f(std::fopen(path.c_str(), "rb"));
  if (!f) return "cannot be opened";
  return container == "matroska" ? matroskaProblem(f.get(), length) : isoMediaProblem(f.get(), length);
}

}  // namespace gf::render

#include "render/frames/shrink.hpp"

#include <algorithm>

namespace gf::render {
namespace {

// Adds one source row's pixels into the sums of `blocks` whole blocks of `factor` pixels (F,
// when not 0, is `factor` known at compile time: the usual halving runs unrolled).
template <int F>
void addBlocks(const std::uint8_t* src, std::uint32_t* sums, int blocks, int factor) {
  const int f = F > 0 ? F : factor;
  for (int x = 0; x < blocks; ++x, sums += 3) {
    for (int k = 0; k < f; ++k, src += 3) sums[0] += src[0], sums[1] += src[1], sums[2] += src[2];
  }
}

}  // namespace

int shrinkFactor(int frame_width, int shown_width) {
  if (shown_width <= 0 || shown_width >= frame_width) return 1;
  return std::max(1, frame_width / shown_width);
}

void shrinkByBlocks(const Image& in, int factor, Image& out) {
  if (factor <= 1) {
    out = in;
    return;
  }
  const int width = (in.width + factor - 1) / factor, height = (in.height + factor - 1) / factor;
  const std::size_t in_row = 3 * static_cast<std::size_t>(in.width);
  out.width = width;
  out.height = height;
  out.rgb.resize(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  std::vector<std::uint32_t> sums(3 * static_cast<std::size_t>(width));
  for (int y = 0; y < height; ++y) {
    // The block row's sums, column block by column block; then each sum over its pixel count.
    std::fill(sums.begin(), sums.end(), 0u);
    const int y0 = y * factor, y1 = std::min(in.height, y0 + factor);
    const int whole = in.width / factor;  // blocks of `factor` pixels; then one cut short, or none
    for (int sy = y0; sy < y1; ++sy) {
      const std::uint8_t* src = in.rgb.data() + static_cast<std::size_t>(sy) * in_row;
      if (factor == 2) {
        addBlocks<2>(src, sums.data(), whole, factor);
      } else {
        addBlocks<0>(src, sums.data(), whole, factor);
      }
      std::uint32_t* s = sums.data() + 3 * static_cast<std::size_t>(whole);
      for (int sx = whole * factor; sx < in.width; ++sx) {
        const std::uint8_t* p = src + 3 * static_cast<std::size_t>(sx);
        s[0] += p[0], s[1] += p[1], s[2] += p[2];
      }
    }
    std::uint8_t* dst = out.rgb.data() + 3 * static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    // (sum + count / 2) / count, by a multiplication: the sums are below 2^24, so the double's
    // quotient is within 1e-12 of the exact one and the margin of 1e-6 keeps exact quotients.
    for (int x = 0; x < width; ++x) {
      const int count = (std::min(in.width, (x + 1) * factor) - x * factor) * (y1 - y0);
      const double inverse = 1.0 / count, half = 0.5 * (count - count % 2);
      for (int c = 0; c < 3; ++c) {
        const std::size_t i = 3 * static_cast<std::size_t>(x) + static_cast<std::size_t>(c);
        dst[i] = static_cast<std::uint8_t>((sums[i] + half) * inverse + 1e-6);
      }
    }
  }
}

}  // namespace gf::render

#include "render/frames/image_compare.hpp"

#include <algorithm>
#include <cstdlib>

namespace gf::render {
namespace {

int pixelDifference(const Image& a, const Image& b, std::size_t i) {
  int worst = 0;
  for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c])));
  return worst;
}

}  // namespace

ImageDifference compareImages(const Image& actual, const Image& expected, int channel_threshold) {
  ImageDifference d;
  d.same_size = actual.width == expected.width && actual.height == expected.height &&
                actual.rgb.size() == expected.rgb.size();
  if (!d.same_size) {
    d.differing_share = 1.0;
    return d;
  }
  const std::size_t pixels = actual.rgb.size() / 3;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const int diff = pixelDifference(actual, expected, i);
    d.max_channel_difference = std::max(d.max_channel_difference, diff);
    differing += diff > channel_threshold;
  }
  d.differing_share = pixels ? double(differing) / pixels : 0.0;
  return d;
}

Image differenceImage(const Image& actual, const Image& expected, int channel_threshold) {
  Image out = expected;
  if (actual.rgb.size() != expected.rgb.size()) return actual;
  for (std::size_t i = 0; i < out.rgb.size() / 3; ++i) {
    const bool differs = pixelDifference(actual, expected, i) > channel_threshold;
    const int grey = (out.rgb[3 * i] + out.rgb[3 * i + 1] + out.rgb[3 * i + 2]) / 6 + 64;
    out.rgb[3 * i] = static_cast<std::uint8_t>(differs ? 255 : grey);
    out.rgb[3 * i + 1] = static_cast<std::uint8_t>(differs ? 0 : grey);
    out.rgb[3 * i + 2] = static_cast<std::uint8_t>(differs ? 0 : grey);
  }
  return out;
}

}  // namespace gf::render

// Image comparison for visual regression: per-channel tolerance and a share of differing pixels.
#pragma once

#include "render/frames/image.hpp"

namespace gf::render {

/// How two images differ.
struct ImageDifference {
  bool same_size = false;
  double differing_share = 0.0;  ///< pixels with any channel off by more than the threshold
  int max_channel_difference = 0;
};

/// Compares `actual` with `expected`: a pixel differs when any channel is off by more than
/// `channel_threshold` (0..255).
ImageDifference compareImages(const Image& actual, const Image& expected, int channel_threshold);

/// The expected image dimmed to grey, with differing pixels in red: where to look.
Image differenceImage(const Image& actual, const Image& expected, int channel_threshold);

}  // namespace gf::render

// Smaller copies of a frame for watchers who show it smaller (the browser view's stream at the
// size its page draws it): shrunk by a whole factor, each pixel the mean of a block of the
// frame's. A whole factor costs one pass over the frame with integer sums (1.8 ms at 1280x720
// by 2), where a fractional one cost more than the smaller JPEG saved.
#pragma once

#include "render/frames/image.hpp"

namespace gf::render {

/// The whole factor to shrink a frame `frame_width` pixels wide by for a watcher showing it
/// `shown_width` pixels wide: the largest k with frame_width / k >= shown_width (whole blocks
/// alone as wide as shown), 1 (as drawn) for a width of 0 or of at least the frame's.
int shrinkFactor(int frame_width, int shown_width);

/// `in` shrunk by `factor`: ceil(width / factor) x ceil(height / factor) pixels, each the
/// mean (rounded) of its factor x factor block of `in`, the blocks along the right and bottom
/// edges cut short by the frame's edge. A factor of 1 or less copies `in`. Into `out` (storage
/// reused). Any thread; allocates a row of sums, and `out` when it must grow.
void shrinkByBlocks(const Image& in, int factor, Image& out);

}  // namespace gf::render

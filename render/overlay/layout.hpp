// Where a frame's labels go: the screen boxes of what the frame shows (the bodies, the proxies,
// the patches) and a placement of the patch insets' block and the time stamp in corners clear
// of them. Plain data and arithmetic, no GL: the render thread places with it every frame, and a
// test checks every bundled scene's frames with it.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "render/view/view_desc.hpp"
#include "sim/mesh/mesh.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// A rectangle on the picture, in pixels from its top-left corner (x0 <= x1, y0 <= y1).
struct ScreenBox {
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;
  float area() const { return (x1 - x0) * (y1 - y0); }
  /// The area `this` and `o` share (pixels^2); 0 when they only touch.
  float overlap(const ScreenBox& o) const;
};

/// The screen boxes of what a frame of `snapshot` from `camera` (width x height pixels) is
/// about: each body but the ground (the corners of its render surface's box at its pose, from
/// `surfaces`, one per body as DrawListBuilder takes them; null for a plane), each proxy (as far
/// as what is drawn there reaches: its sphere, marks, a fingertip drawn as `look`, a fem_pad's
/// skin; with its force arrow at `arrow_m_per_n` when it touches something, as far as the
/// longest arrow, 8 cm; 0: none drawn) and each contact's patch (a disc of its radius, at least
/// r_max, across the normal), cut to the picture; those entirely behind the camera or outside
/// the picture are left out.
std::vector<ScreenBox> subjectBoxes(const sim::SceneDesc& scene,
                                    const std::vector<std::shared_ptr<const sim::Mesh>>& surfaces,
                                    const sim::Snapshot& snapshot, const view::Camera& camera, int width, int height,
                                    double arrow_m_per_n = 0.0, view::ProxyLook look = view::ProxyLook::kSphere);

/// A corner of the picture, in the order a label is tried there by default.
enum class Corner : std::uint8_t { kBottomRight, kBottomLeft, kTopRight, kTopLeft };
inline constexpr std::array<Corner, 4> kCorners = {Corner::kBottomRight, Corner::kBottomLeft, Corner::kTopRight,
                                                   Corner::kTopLeft};

/// A block of `w` x `h` pixels in corner `c` of a width x height picture, `margin` pixels in.
ScreenBox cornerBox(Corner c, float w, float h, int width, int height, float margin);

/// Where a frame's labels go.
struct LabelPlacement {
  Corner insets = Corner::kBottomRight;  ///< the patch insets' block (with the captions above)
  bool column = false;                   ///< the insets one above the other, not side by side
  Corner stamp = Corner::kBottomLeft;    ///< the time stamp

  bool operator==(const LabelPlacement&) const = default;
};

/// What is placed: the sizes (pixels) of the insets' block (0 x 0: none) and of the stamp.
struct LabelSizes {
  float insets_w = 0.0f, insets_h = 0.0f;  ///< side by side
  float column_w = 0.0f, column_h = 0.0f;  ///< one above the other (0 x 0: not offered)
  float stamp_w = 0.0f, stamp_h = 0.0f;
  float margin = 0.0f;  ///< from the picture's edges (pixels)
};

/// The sizes of a frame's labels: the patch insets' block of `fingers` fingers (with `insets`;
/// patch_insets.hpp) and the time stamp (with `stamp`, at stampLabelPx(height), its arrow line
/// when arrow_m_per_n > 0), 1.5 % of the height from the edges.
LabelSizes frameLabelSizes(int width, int height, int fingers, bool insets, bool stamp, double time,
                           double arrow_m_per_n);

/// The placement of `sizes` in a width x height picture clear of `subjects`: the insets' block
/// first, side by side in the first corner of kCorners (allowed by `insets_allowed`, indexed by
/// Corner) that covers no subject, else one above the other in the same order, else where it
/// covers the least of them, staying where `previous` put it while it covers nothing there (no
/// jump from frame to frame); then the stamp in the same way in another corner allowed by
/// `stamp_allowed`, its default bottom left.
LabelPlacement placeLabels(const std::vector<ScreenBox>& subjects, const LabelSizes& sizes, int width, int height,
                           const LabelPlacement& previous, const std::array<bool, 4>& insets_allowed = {true, true, true, true},
                           const std::array<bool, 4>& stamp_allowed = {true, true, true, true});

/// The boxes `placement` gives `sizes` in a width x height picture: the insets' block, the stamp.
std::array<ScreenBox, 2> placedBoxes(const LabelPlacement& placement, const LabelSizes& sizes, int width, int height);

}  // namespace gf::render

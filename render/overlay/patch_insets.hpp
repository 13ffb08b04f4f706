// The `patch_insets` effect: a picture-in-picture close-up of each finger's contact patch in a
// bottom corner of every frame, seen down the contact normal with the proxies, their shadows and
// the arrows that would point at the camera hidden, framed in the finger's colour and labelled
// (render/overlay/labels.hpp) with the finger, its contact model, F_n and F_t, the tangential force as
// an arrow in the picture, a mm scale bar and the load colour bar. Render thread only.
#pragma once

#include <memory>

#include "render/scene/camera.hpp"
#include "render/gl/imgui_layer.hpp"
#include "render/overlay/layout.hpp"
#include "render/scene/scene_renderer.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// The close-up of finger `finger`'s first contact: `only` becomes `snapshot` with that finger's
/// contacts alone, and other fingers' patches that overlap its patch (reusing its storage), `camera` looks down the contact normal at a square
/// view holding the patch (r_max and the radius drawn, with a margin). False, and nothing
/// changed, when the finger touches nothing.
bool contactCloseUp(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, std::size_t finger,
                    sim::Snapshot& only, view::Camera& camera);

/// The corner the insets go in (layout.hpp places them off the frame's subjects; beside the
/// overlay's bottom-right panel they keep to the bottom left).
using InsetCorner = Corner;

/// A finger's inset: its square, in pixels from the frame's top-left corner.
struct InsetRect {
  int x = 0, y = 0, size = 0;
};

/// The insets' squares of `fingers` fingers in a width x height frame: side 30 % of the height
/// (narrower when they would not fit side by side), a margin of 1.5 % of the height, in finger
/// order from left to right, or with `column` from top to bottom. Their captions go above them:
/// the squares sit insetCaptionReserve() below the block's top or the square above.
std::vector<InsetRect> insetRects(int width, int height, int fingers, InsetCorner corner, bool column = false);

/// The block the insets of `fingers` fingers take in a width x height frame, captions included,
/// side by side and (when two or more fit the height) one above the other: their sizes for
/// placeLabels (the margin is the frame's).
LabelSizes insetBlock(int width, int height, int fingers);

class PatchInsets {
 public:
  /// Makes the insets' framebuffer (anti-aliased like the frame). Throws GlError.
  PatchInsets(const sim::SceneDesc& scene, int frame_width, int frame_height, InsetCorner corner,
              view::Antialiasing antialiasing, int msaa_samples);
  ~PatchInsets();
  PatchInsets(const PatchInsets&) = delete;
  PatchInsets& operator=(const PatchInsets&) = delete;

  /// Moves the insets to `corner`, in a row or a `column` (placeLabels' choice for the frame
  /// about to be drawn).
  void place(InsetCorner corner, bool column);
  /// Draws every finger's inset picture into framebuffer `target` (the frame, already
  /// anti-aliased) with `renderer`, whose settings it changes for the close-ups and restores.
  /// `target` is bound on return.
  void draw(SceneRenderer& renderer, const sim::Snapshot& snapshot, unsigned target);
  /// Adds the labels of the insets last drawn (of `snapshot`) to the frame of `layer` (a layer of
  /// the frame's size, between its beginFrame() and render()).
  void drawLabels(const ImGuiLayer& layer, const sim::Snapshot& snapshot) const;
  /// The text height of the insets' labels (pixels): a font `layer` should have.
  float labelPx() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

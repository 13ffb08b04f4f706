// The backdrop and the bodies' layer each view of a SceneRenderer keeps (one view: a camera and a
// picture size; the frame, two patch insets and a close-up are four): which slot a view takes
// and what each slot holds. Render thread only (its Backdrops are GL objects).
#pragma once

#include <array>
#include <memory>

#include "render/gl/gpu.hpp"
#include "render/view/view_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// The switches a view's bodies' layer is drawn with.
struct LayerSwitches {
  bool shadows = false, ground = false, fingers = false;
  view::BodyPattern pattern = view::BodyPattern::kStripes;
  view::ProxyLook proxy = view::ProxyLook::kSphere;
  bool operator==(const LayerSwitches&) const = default;
};

/// One view's backdrop (the clear colour and the ground under its camera) and its bodies' layer:
/// the backdrop with the bodies and the ground's shadows of `layer_state` drawn on it, kept from
/// the second frame that places everything alike (samePlaces) and restored while nothing moves.
struct ViewSlot {
  std::unique_ptr<Backdrop> backdrop, layer;
  view::Camera camera;
  bool ground = true;  ///< drawn with the ground planes
  sim::Snapshot layer_state;
  LayerSwitches layer_switches;
  bool layer_state_valid = false, layer_kept = false;
  long layer_number = 0;  ///< given each time `layer` is taken (HeldLayer::layer)
  long used = -1;  ///< when it was last drawn with (draws counted)
};

class ViewLayers {
 public:
  /// The slot of the view `camera` at `width` x `height` (`samples` per pixel, with the ground or
  /// not): its own (sameView); else an empty one; else the least recently used of its size;
  /// else the least recently used, given a new backdrop. `stale`: its backdrop must be drawn (a
  /// new view), and its layer was dropped.
  ViewSlot& slotFor(const view::Camera& camera, int width, int height, int samples, bool ground, bool& stale);

 private:
  std::array<ViewSlot, 4> slots_;
  long draws_ = 0;
};

/// Two cameras that give the same view: position and target within kSamePictureTolerance (a
/// patch inset's camera follows its contact point, which a held body's solver jitter moves by
/// about 1e-12 m), the same field of view.
bool sameView(const view::Camera& a, const view::Camera& b);

}  // namespace gf::render

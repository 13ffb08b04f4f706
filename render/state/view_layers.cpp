#include "render/state/view_layers.hpp"

#include <algorithm>
#include <cmath>

#include "render/state/same_picture.hpp"

namespace gf::render {

bool sameView(const view::Camera& a, const view::Camera& b) {
  const auto near = [](const sim::Vec3& x, const sim::Vec3& y) {
    return (x - y).cwiseAbs().maxCoeff() <= kSamePictureTolerance;  // false for NaN
  };
  return near(a.position, b.position) && near(a.target, b.target) && a.fov_deg == b.fov_deg;
}

ViewSlot& ViewLayers::slotFor(const view::Camera& camera, int width, int height, int samples, bool ground,
                              bool& stale) {
  const auto fits = [&](const ViewSlot& s) { return s.backdrop && s.backdrop->fits(width, height, samples); };
  const auto leastRecent = [&](bool of_its_size) {
    ViewSlot* best = nullptr;
    for (ViewSlot& s : slots_) {
      if ((!of_its_size || fits(s)) && (!best || s.used < best->used)) best = &s;
    }
    return best;
  };
  ViewSlot* slot = nullptr;
  for (ViewSlot& s : slots_) {  // this view's own
    if (!slot && fits(s) && sameView(camera, s.camera) && s.ground == ground) slot = &s;
  }
  for (ViewSlot& s : slots_) {  // else an empty one: two insets of one size keep a slot each
    if (!slot && !s.backdrop) slot = &s;
  }
  if (!slot) slot = leastRecent(true);
  if (!slot) slot = leastRecent(false);
  if (!fits(*slot)) {
    slot->backdrop = std::make_unique<Backdrop>(width, height, samples);
    slot->layer.reset();
    slot->camera.fov_deg = -1.0;  // matches no camera: drawn by the caller
  }
  slot->used = ++draws_;
  stale = !sameView(camera, slot->camera) || slot->ground != ground;
  if (stale) {
    slot->camera = camera;
    slot->ground = ground;
    slot->layer_state_valid = slot->layer_kept = false;
  }
  return *slot;
}

}  // namespace gf::render

#include "render/state/view_layers.hpp"

#include <algorithm>

namespace gf::render {

bool sameView(const view::Camera& a, const view::Camera& b) {
  return a.position == b.position && a.target == b.target && a.fov_deg == b.fov_deg;
}

ViewSlot& ViewLayers::slotFor(const view::Camera& camera, int width, int height, int samples, bool ground,
                              bool& stale) {
  ViewSlot* slot = nullptr;
  for (ViewSlot& s : slots_) {
    if (!s.backdrop || !s.backdrop->fits(width, height, samples)) continue;
    if (sameView(camera, s.camera) && s.ground == ground) {
      slot = &s;
      break;
    }
    if (!slot || s.used < slot->used) slot = &s;
  }
  if (!slot) {
    slot = &*std::min_element(slots_.begin(), slots_.end(),
                              [](const ViewSlot& a, const ViewSlot& b) { return a.used < b.used; });
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

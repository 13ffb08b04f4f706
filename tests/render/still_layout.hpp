// Where a frame's labels went: the placement the render thread makes (render/overlay/layout.hpp)
// from the frame's settings, for tests that look at the insets or the stamp.
#pragma once

#include <memory>
#include <vector>

#include "render/overlay/layout.hpp"
#include "render/render_thread.hpp"
#include "render/scene/geometry.hpp"

namespace gf::test {

/// The sizes and placement of the labels of renderStill(scene, snap, settings).
struct StillLayout {
  render::LabelSizes sizes;
  render::LabelPlacement placement;
  std::vector<render::ScreenBox> subjects;  ///< what the labels keep clear of
};

/// Each body's render surface, as SceneRenderer makes them.
inline std::vector<std::shared_ptr<const sim::Mesh>> renderSurfaces(const sim::SceneDesc& scene) {
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces;
  for (const sim::BodyDesc& b : scene.bodies) surfaces.push_back(render::bodyRenderMesh(b));
  return surfaces;
}

/// `surfaces`: renderSurfaces(scene); `previous`: the placement of the frame before (a still has
/// none), kept while it is clear.
inline StillLayout stillLayout(const sim::SceneDesc& scene, const std::vector<std::shared_ptr<const sim::Mesh>>& surfaces,
                               const sim::Snapshot& snap, const render::FrameOutputSettings& settings,
                               const render::LabelPlacement& previous = {}) {
  const int w = settings.width, h = settings.height;
  const bool arrows = settings.scene.patch_highlight && settings.scene.contact_arrows;
  const double arrow_m_per_n = arrows ? settings.scene.force_arrow_m_per_n : 0.0;
  StillLayout out;
  out.sizes = render::frameLabelSizes(w, h, static_cast<int>(scene.fingers.size()), settings.patch_insets,
                                      settings.time_stamp && !settings.overlay, snap.time, arrow_m_per_n);
  const bool free = !settings.overlay, top_left = !settings.top_left_taken;
  out.subjects = render::subjectBoxes(scene, surfaces, snap, settings.camera, w, h, arrow_m_per_n, settings.scene.proxy);
  out.placement = render::placeLabels(out.subjects, out.sizes, w, h, previous, {free, true, free, free && top_left},
                                      {true, true, true, top_left});
  return out;
}

inline StillLayout stillLayout(const sim::SceneDesc& scene, const sim::Snapshot& snap,
                               const render::FrameOutputSettings& settings) {
  return stillLayout(scene, renderSurfaces(scene), snap, settings);
}

}  // namespace gf::test

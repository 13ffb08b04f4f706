// Where a still's labels went: the placement the render thread made for a frame with no frame
// before it (render/overlay/layout.hpp), for tests that look at the insets or the stamp.
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
};

inline StillLayout stillLayout(const sim::SceneDesc& scene, const sim::Snapshot& snap,
                               const render::FrameOutputSettings& settings) {
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces;
  for (const sim::BodyDesc& b : scene.bodies) surfaces.push_back(render::bodyRenderMesh(b));
  const int w = settings.width, h = settings.height;
  const bool arrows = settings.scene.patch_highlight && settings.scene.contact_arrows;
  const double arrow_m_per_n = arrows ? settings.scene.force_arrow_m_per_n : 0.0;
  StillLayout out;
  out.sizes = render::frameLabelSizes(w, h, static_cast<int>(scene.fingers.size()), settings.patch_insets,
                                      settings.time_stamp && !settings.overlay, snap.time, arrow_m_per_n);
  const bool free = !settings.overlay, top_left = !settings.top_left_taken;
  out.placement = render::placeLabels(render::subjectBoxes(scene, surfaces, snap, settings.camera, w, h, arrow_m_per_n),
                                      out.sizes, w, h, {}, {free, true, free, free && top_left}, {true, true, true, top_left});
  return out;
}

}  // namespace gf::test

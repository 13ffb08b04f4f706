// The ImGui overlay: scene and time, per-finger god-finger settings (widgets a session script
// operates with injected mouse and keyboard events), timings and a live coupling-force plot.
// It is an effect: built only for scenes that ask for it. Render thread only.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/imgui_layer.hpp"
#include "sim/scene_desc.hpp"
#include "sim/settings.hpp"
#include "sim/snapshot.hpp"
#include "sim/view_desc.hpp"

namespace gf::render {

/// What the overlay shows and does.
struct OverlaySettings {
  std::vector<sim::WidgetAction> actions;  ///< sorted by time
  double plot_seconds = 5.0;          ///< span of the force plot (s)
  float font_px = 15.0f;              ///< at 720 rows; scaled with the frame height
};

/// Per-frame render timing the overlay displays.
struct RenderTimings {
  double render_ms = 0.0;  ///< last frame's draw + read-back time
};

class Overlay {
 public:
  Overlay(const sim::SceneDesc& scene, const OverlaySettings& settings, int width, int height);
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  /// Runs the scripted input due at snapshot.time, builds the panels and draws them over the
  /// bound framebuffer. Returns the settings changes the widgets made this frame.
  std::vector<sim::SettingsCommand> draw(const sim::Snapshot& snapshot, const RenderTimings& timings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

// The ImGui overlay: scene and time, per-finger god-finger settings (widgets a session script
// operates with injected mouse and keyboard events), timings and a live coupling-force plot.
// It is an effect: built only for scenes that ask for it. Render thread only.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/gl/imgui_layer.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/settings.hpp"
#include "sim/scene/snapshot.hpp"
#include "render/view/view_desc.hpp"

namespace gf::render {

/// Timings the overlay shows instead of measured ones: a reference picture's, fixed so that it
/// is the same in every run (each figure says where it was measured).
struct ScriptedTimings {
  double step_median_us = 0.0;
  double step_p99_us = 0.0;
  long late_steps = 0;
  double render_ms = 0.0;
};

/// What the overlay shows and does.
struct OverlaySettings {
  std::vector<view::WidgetAction> actions;  ///< sorted by time
  double plot_seconds = 5.0;          ///< span of the force plot (s)
  float font_px = 15.0f;              ///< at 720 rows; scaled with the frame height, never under 13 px
  /// The snapshots' haptic timings are measured (a realtime run). Offline they are zero, and the
  /// panel says the run is offline instead of showing them.
  bool wall_clock = false;
  std::optional<ScriptedTimings> scripted_timings;  ///< shown instead of any measured timing
  double arrow_m_per_n = 0.0;         ///< the frame's force-arrow scale, stated in the scene panel; 0: none drawn
};

/// Per-frame render timing the overlay displays.
struct RenderTimings {
  double render_ms = 0.0;  ///< last frame's draw + read-back time
};

/// Where a panel or widget was laid out (pixels from the frame's top-left corner).
struct OverlayRect {
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;
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
  /// Adds `snapshot` to the force plot's history without drawing (a still's lead-in: the frames
  /// a run would have drawn before it).
  void record(const sim::Snapshot& snapshot);
  /// The last frame's layout: "panel/TITLE" for each panel, "FINGER/FIELD" for each widget.
  std::map<std::string, OverlayRect> layout() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

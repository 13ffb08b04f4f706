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
#include "sim/snapshot.hpp"

namespace gf::render {

/// One scripted use of a widget: at `time` (s, simulated) the overlay moves the mouse to the
/// widget and operates it with real input events over the next frames (click for a checkbox;
/// ctrl+click, select all, type `value`, Enter for a slider), as a user would.
struct WidgetAction {
  double time = 0.0;
  std::string widget;  ///< "FINGER/FIELD": FIELD one of god_finger, n_sgo, r_max, alpha, tau_a, friction
  std::string value;   ///< checkbox: "on" / "off"; sliders: the number in the widget's unit
};

/// Frames an action takes from its first frame to the frame whose settings change takes effect.
inline constexpr int kActionFrames = 7;

/// Names of the widget fields, in panel order.
const std::vector<std::string>& widgetFields();

/// What the overlay shows and does.
struct OverlaySettings {
  std::vector<WidgetAction> actions;  ///< sorted by time
  double plot_seconds = 5.0;          ///< span of the force plot (s)
  float font_px = 15.0f;              ///< at 720 rows; scaled with the frame height
};

/// A settings change made in the overlay, for the haptic thread to apply.
struct SettingsCommand {
  int finger = 0;
  sim::PatchSettings patch;  ///< the finger's whole new patch settings (n_sgo 0: god-object)
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
  std::vector<SettingsCommand> draw(const sim::Snapshot& snapshot, const RenderTimings& timings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

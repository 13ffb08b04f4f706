// Plain descriptions of how a scene is looked at: cameras, anti-aliasing and scripted overlay
// input. Header-only data below both readers of it: the scene reader (app/scene) fills them, the
// renderer (render/) draws with them, and neither needs the other.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "sim/math.hpp"
#include "sim/patch/patch_settings.hpp"

namespace gf::view {

using sim::Quat;
using sim::Vec3;

/// A pinhole camera looking from `position` at `target`.
struct Camera {
  std::string name;                                ///< as in the scene file ([cameras.NAME])
  Vec3 position = Vec3(0.3, 0.25, 0.4);  ///< m
  Vec3 target = Vec3::Zero();            ///< m: the point looked at
  double fov_deg = 40.0;                           ///< vertical field of view (degrees)
};

/// How a frame is anti-aliased. FXAA is a post-process pass over the finished scene; on fig8 at
/// 1280x720 it adds 3.5 ms to a frame where 4x MSAA adds 21 ms (llvmpipe shades, stores and
/// resolves every sample on the CPU).
enum class Antialiasing { kNone, kFxaa, kMsaa };

/// The scene-file names of the Antialiasing values, in enum order.
inline constexpr std::array<std::string_view, 3> kAntialiasingNames = {"none", "fxaa", "msaa"};

/// Parses "none", "fxaa" or "msaa"; nullopt for anything else.
inline std::optional<Antialiasing> parseAntialiasing(std::string_view name) {
  for (std::size_t i = 0; i < kAntialiasingNames.size(); ++i) {
    if (name == kAntialiasingNames[i]) return static_cast<Antialiasing>(i);
  }
  return std::nullopt;
}
inline const char* antialiasingName(Antialiasing aa) {
  return kAntialiasingNames[static_cast<std::size_t>(aa)].data();
}

/// How rigid bodies are patterned so that a turn shows (`[render] body_pattern`).
enum class BodyPattern { kStripes, kNone };

/// The scene-file names of the BodyPattern values, in enum order: "stripes" (eight bands about
/// the body's own y axis, lighter and darker by turns, strong on its upper half, faint and
/// shifted by one band on the lower) or "none" (one colour).
inline constexpr std::array<std::string_view, 2> kBodyPatternNames = {"stripes", "none"};

/// How a finger's proxy is drawn (`[render] proxy`).
enum class ProxyLook { kSphere, kFingertip };

/// The scene-file names of the ProxyLook values, in enum order: "sphere" (the god-object as it
/// is) or "fingertip" (the sphere as the pad of a fingertip going up from it).
inline constexpr std::array<std::string_view, 2> kProxyLookNames = {"sphere", "fingertip"};

/// One scripted use of a widget: at `time` (s, simulated) the overlay moves the mouse to the
/// widget and operates it with real input events over the next frames (click for a checkbox;
/// ctrl+click, select all, type `value`, Enter for a slider), as a user would.
struct WidgetAction {
  double time = 0.0;
  std::string widget;  ///< "FINGER/FIELD": FIELD one of kOverlayWidgets
  std::string value;   ///< checkbox: "on" / "off"; sliders: the number in the setting's unit
};

/// Frames an action takes from its first frame to the frame whose settings change takes effect.
inline constexpr int kActionFrames = 7;

/// A widget of a finger's overlay panel: the god-finger checkbox, or a slider of the live
/// finger setting of the same name (settings.hpp), shown in its unit times `shown_per_unit`.
struct OverlayWidget {
  std::string_view field;       ///< FIELD of "FINGER/FIELD"
  double shown_per_unit = 1.0;  ///< r_max is shown (and typed) in mm
  float lo = 0.0f, hi = 0.0f;   ///< span of the slider, shown units (inside the legal range)
  const char* label = "";
  const char* format = "%.2f";
};

/// The widgets of each finger's panel, in panel order. n_SGO spans its legal range
/// (kMinSgo..kMaxSgo); the other sliders span what a fingertip uses.
inline constexpr std::array<OverlayWidget, 6> kOverlayWidgets = {{
    {"god_finger", 1.0, 0.0f, 1.0f, "god-finger", ""},
    {"n_sgo", 1.0, float{sim::kMinSgo}, float{sim::kMaxSgo}, "n_SGO", "%d"},
    {"r_max", 1000.0, 1.0f, 30.0f, "r_max (mm)", "%.1f"},
    {"alpha", 1.0, 1.0f, 5.0f, "alpha", "%.2f"},
    {"tau_a", 1.0, 0.0f, 90.0f, "tau_a (deg)", "%.0f"},
    {"friction", 1.0, 0.0f, 2.0f, "friction", "%.2f"},
}};

/// The widget of `field`, or null.
inline const OverlayWidget* findOverlayWidget(std::string_view field) {
  for (const OverlayWidget& w : kOverlayWidgets) {
    if (w.field == field) return &w;
  }
  return nullptr;
}

/// A target drawn in the frames (a scene's `[targets.NAME]`): where a task wants a body. A ghost
/// of a body's surface at a pose, a zone (a box outline), or both.
struct Target {
  std::string name;
  int body = -1;  ///< the body whose ghost is drawn (index into the scene's bodies); -1: none
  Vec3 position = Vec3::Zero();            ///< m: the ghost's pose (world frame)
  Quat orientation = Quat::Identity();
  bool has_zone = false;
  Vec3 zone_min = Vec3::Zero(), zone_max = Vec3::Zero();  ///< m: the zone's corners
};

}  // namespace gf::view

// The 2D labels drawn with ImGui over pictures so that they explain themselves: a frame's time
// stamp and force-arrow scale, and a contact view's (patch inset or close-up PNG) caption, mm
// scale bar, load colour bar and tangential force as an in-plane arrow. Render thread (ImGui).
#pragma once

#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"
#include "render/view/view_desc.hpp"

struct ImDrawList;
struct ImFont;

namespace gf::render {

class ImGuiLayer;

/// The smallest label text (pixels high): ImGui's built-in font is drawn at its own 13 px grid
/// there, crisp; smaller it smears ("0.09" read as "0.89" at 6 px).
inline constexpr float kMinLabelPx = 13.0f;

/// The text height of a contact view of `size_px` pixels: 7 % of its side, at least kMinLabelPx
/// and at most 18 px.
float contactLabelPx(int size_px);

/// The text height of a frame's time stamp for a frame `height_px` high: 2.2 % of it, at least
/// kMinLabelPx.
float stampLabelPx(int height_px);

/// The height kept above an inset for its caption (pixels) at text height `px`: its most lines.
float insetCaptionReserve(float px);

/// The size (pixels) of a frame stamp's backdrop at text height `px`, with the force arrows'
/// scale line when `arrow_m_per_n` > 0 (the built-in font is monospaced: no font is needed).
struct StampSize {
  float w = 0.0f, h = 0.0f;
};
StampSize stampSize(float px, double time, double arrow_m_per_n);

/// A square contact view on the picture, in pixels from its top-left corner.
struct LabelBox {
  float x = 0.0f, y = 0.0f, size = 0.0f;
};

/// What one contact view shows, and how much it says.
struct ContactLabel {
  const sim::FingerDesc* finger = nullptr;          ///< the finger's description
  int finger_index = 0;                             ///< its colour
  const sim::FingerSnapshot* state = nullptr;       ///< its state
  const sim::ContactSnapshot* contact = nullptr;    ///< the contact shown; null: "no contact"
  view::Camera camera;                               ///< the view's camera (closeUpCamera())
  double time = 0.0;                                ///< s
  double arrow_m_per_n = 0.01;                      ///< the frame's force-arrow scale (m/N), kept for F_t
  /// A close-up PNG: the caption inside the picture's top with the time, every figure and the
  /// legend's words. Otherwise an inset: the caption above the view, as much as fits its width.
  bool close_up = false;
  bool load_arrows = false;  ///< the view draws the points' loads as arrows: a close-up states their scale
};

/// Draws `label`'s annotations over `box` with `font` at `px` pixels: the caption (finger,
/// model, F_n, F_t, radius, SGOs; a close-up adds the time and the arrow scale), the tangential
/// force on the body as an arrow from the contact point in the picture's plane (at the frame's
/// force-arrow scale, read against the scale bar; at most 45 % of the view; none under 2 % of
/// F_n), a mm scale bar in the bottom-left corner, and with per-point
/// loads the colour bar of the load scale (contact_load.hpp) in the bottom-right corner. An
/// inset's caption goes above the box (outside the picture); a close-up's inside its top.
void drawContactLabel(ImDrawList& d, ImFont* font, float px, const LabelBox& box, const ContactLabel& label);

/// Adds a frame's stamp to the frame of `layer` (of the frame's size, between its beginFrame()
/// and render()) at the top-left corner `at` of its backdrop (layout.hpp places it), at `px`:
/// "t = 1.250 s" and, when `arrow_m_per_n` > 0, the force arrows' scale ("force arrow 1 cm = 1 N").
void drawFrameStamp(const ImGuiLayer& layer, float px, float at_x, float at_y, double time, double arrow_m_per_n);

/// The length (m) of a scale bar for a view `view_m` metres wide: the longest of 0.1, 0.2, 0.5,
/// 1, 2, 5, ... mm that is at most 30 % of the view.
double scaleBarMetres(double view_m);

}  // namespace gf::render

#include "render/overlay/labels.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>

#include "render/scene/camera.hpp"
#include "render/state/contact_load.hpp"
#include "render/scene/draw_list.hpp"
#include "render/scene/load_marks.hpp"
#include "render/gl/imgui_layer.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr float kContactLabelShare = 0.07f;  // text height, of a contact view's side...
constexpr float kMaxContactLabelPx = 18.0f;  // ...up to this (a 480-pixel close-up's)
constexpr float kStampLabelShare = 0.022f;   // text height, of a frame's height
constexpr float kPadShare = 0.3f;            // padding, of the text height
constexpr float kLineShare = 1.15f;          // line spacing, of the text height
constexpr int kSmallInsetPx = 90;            // below this an inset's caption is the finger and F_n
constexpr int kDetailInsetPx = 180;          // from this an inset's caption adds the SGOs and radius
constexpr double kArrowViewShare = 0.45;     // the longest tangential arrow, of the view's side
constexpr double kMinArrowRatio = 0.02;      // F_t / F_n under which no arrow is drawn
constexpr double kScaleBarShare = 0.3;       // the longest a scale bar may be, of the view's width
constexpr float kColourBarShare = 0.38f;     // the load colour bar's length, of the view's side
constexpr int kColourBarSteps = 20;          // gradient pieces of the colour bar
constexpr int kMaxLines = 4;
constexpr float kGlyphAdvance = 7.0f / 13.0f;  // the built-in (monospaced) font's advance, of its height
constexpr std::size_t kLineChars = 128;
const ImU32 kText = IM_COL32(255, 255, 255, 255);
const ImU32 kSoftText = IM_COL32(215, 220, 228, 255);
const ImU32 kBox = IM_COL32(15, 18, 24, 170);
const ImU32 kStampBox = IM_COL32(15, 18, 24, 225);  // nearly opaque: the ground's grid lines would cross the time
const ImU32 kOutline = IM_COL32(10, 10, 12, 230);

// Short pieces of text packed into lines no wider than `width`, joined by two spaces.
struct Caption {
  std::array<std::array<char, kLineChars>, kMaxLines> lines{};
  int count = 0;
  std::array<char, kLineChars> token{};  // the piece being added

  void add(ImFont* font, float px, float width) {
    if (token[0] == '\0') return;
    if (count > 0) {
      std::array<char, kLineChars>& last = lines[static_cast<std::size_t>(count - 1)];
      char joined[2 * kLineChars];
      std::snprintf(joined, sizeof joined, "%s  %s", last.data(), token.data());
      if (font->CalcTextSizeA(px, FLT_MAX, 0.0f, joined).x <= width && std::strlen(joined) < kLineChars) {
        std::memcpy(last.data(), joined, std::strlen(joined) + 1);
        return;
      }
    }
    if (count < kMaxLines) std::memcpy(lines[static_cast<std::size_t>(count++)].data(), token.data(), kLineChars);
  }
};

// The caption's pieces of `label` in the order they are read.
Caption caption(ImFont* font, float px, float width, const ContactLabel& label, bool small, bool detail) {
  Caption c;
  char* t = c.token.data();
  const auto add = [&] { c.add(font, px, width); };
  // The finger and its model, on one line when they fit, else the model on the next: a reader
  // of any inset can tell which model it shows.
  std::snprintf(t, kLineChars, "%s: %s", label.finger->name.c_str(), sim::modelLabel(label.finger->patch).data());
  if (font->CalcTextSizeA(px, FLT_MAX, 0.0f, t).x > width) {
    std::snprintf(t, kLineChars, "%s:", label.finger->name.c_str());
    add();
    std::snprintf(t, kLineChars, "%s", sim::modelLabel(label.finger->patch).data());
    c.add(font, px, 0.0f);  // no width to join the name's line: a line of its own
  } else {
    add();
  }
  if (label.close_up) {
    std::snprintf(t, kLineChars, "t = %.3f s", label.time);
    add();
  }
  if (!label.contact) {
    std::snprintf(t, kLineChars, "no contact");
    add();
    return c;
  }
  const ContactForce force = contactForce(*label.state, *label.contact);
  std::snprintf(t, kLineChars, "F_n %.2f N", force.normal);
  add();
  if (small) return c;
  std::snprintf(t, kLineChars, "F_t %.2f N", force.tangential.norm());
  add();
  // The twist the patch resists, when its arc is drawn (load_marks.hpp).
  if (const std::optional<TorsionArc> arc = torsionArc(*label.contact, label.finger->patch.friction, label.finger->patch.r_max)) {
    std::snprintf(t, kLineChars, "M_n %.3f N m", std::abs(arc->moment));
    add();
  }
  if (detail && label.state->sgo_count > 0) {
    std::snprintf(t, kLineChars, "r %.1f mm", 1000.0 * label.contact->radius);
    add();
    std::snprintf(t, kLineChars, "%d SGOs", label.state->sgo_count);
    add();
  } else if (detail) {
    std::snprintf(t, kLineChars, "one point");
    add();
  }
  if (label.contact->sliding) {
    std::snprintf(t, kLineChars, "sliding");
    add();
  }
  if (label.close_up && label.arrow_m_per_n > 0.0) {
    std::snprintf(t, kLineChars, "F_t arrow 1 cm = %g N", 0.01 / label.arrow_m_per_n);
    add();
  }
  const double load_m_per_n = label.load_arrows ? loadArrowScale(*label.contact, label.finger->patch.r_max) : 0.0;
  if (label.close_up && load_m_per_n > 0.0) {
    std::snprintf(t, kLineChars, "SGO friction arrow 1 mm = %.2g N", 0.001 / load_m_per_n);
    add();
  }
  return c;
}

// The view's right and up directions (world, unit) and its pixels per metre at the target.
struct ViewAxes {
  Vec3 right, up;
  double px_per_m = 0.0;
};

ViewAxes viewAxes(const view::Camera& camera, float size) {
  const Vec3 f = (camera.target - camera.position).normalized();
  ViewAxes a;
  a.right = f.cross(upFor(f)).normalized();
  a.up = a.right.cross(f);
  const double half_m = (camera.target - camera.position).norm() * std::tan(0.5 * camera.fov_deg * std::numbers::pi / 180.0);
  a.px_per_m = 0.5 * size / half_m;
  return a;
}

// An arrow from `from` to `to` (pixels) in `colour` with a dark outline.
void arrow2d(ImDrawList& d, const ImVec2& from, const ImVec2& to, float thickness, ImU32 colour) {
  const float dx = to.x - from.x, dy = to.y - from.y, length = std::hypot(dx, dy);
  if (length < 1.0f) return;
  const float ux = dx / length, uy = dy / length, head = std::min(0.45f * length, 3.5f * thickness);
  const ImVec2 base(to.x - head * ux, to.y - head * uy);
  const ImVec2 left(base.x - 0.6f * head * uy, base.y + 0.6f * head * ux), right(base.x + 0.6f * head * uy, base.y - 0.6f * head * ux);
  d.AddLine(from, base, kOutline, thickness + 2.0f);
  d.AddTriangleFilled(ImVec2(to.x + ux, to.y + uy), ImVec2(left.x - ux - uy, left.y - uy + ux),
                      ImVec2(right.x - ux + uy, right.y - uy - ux), kOutline);
  d.AddLine(from, base, colour, thickness);
  d.AddTriangleFilled(to, left, right, colour);
}

// The mm scale bar in the view's bottom-left corner, its length over it.
void scaleBar(ImDrawList& d, ImFont* font, float px, const LabelBox& box, double px_per_m) {
  const double metres = scaleBarMetres(box.size / px_per_m);
  const float length = static_cast<float>(metres * px_per_m), pad = kPadShare * px;
  char text[32];
  std::snprintf(text, sizeof text, "%g mm", 1000.0 * metres);
  const float text_w = font->CalcTextSizeA(px, FLT_MAX, 0.0f, text).x;
  const float x0 = box.x + 2.0f * pad, y = box.y + box.size - 2.0f * pad, tick = 0.35f * px;
  d.AddRectFilled(ImVec2(x0 - pad, y - tick - px - 2.0f * pad), ImVec2(x0 + std::max(length, text_w) + pad, y + pad), kBox, pad);
  const ImVec2 a(x0, y), b(x0 + length, y);
  d.AddLine(a, b, kText, 2.0f);
  d.AddLine(ImVec2(a.x, y - tick), ImVec2(a.x, y), kText, 2.0f);
  d.AddLine(ImVec2(b.x, y - tick), ImVec2(b.x, y), kText, 2.0f);
  d.AddText(font, px, ImVec2(x0, y - tick - px - pad), kText, text);
}

// The load scale's colour bar in the view's bottom-right corner: its ends' and middle's loads in
// N over it (the middle, the contact's mean, left out when the three would not fit), and its
// label above: "SGO load, N" with the least and most loaded points' loads, or, when not even the
// ends' ticks fit, the ends' loads as a range; only the label when that does not fit the view. In close-ups,
// the slip ring's meaning above that when a point slips. Each row's backdrop is as wide as the
// row, so the scale bar in the other corner stays clear.
void colourBar(ImDrawList& d, ImFont* font, float px, const LabelBox& box, const ContactLabel& label) {
  const ContactLoads loads = contactLoads(*label.contact);
  const float pad = kPadShare * px, length = kColourBarShare * box.size, height = std::max(4.0f, 0.45f * px);
  const float x1 = box.x + box.size - 2.0f * pad, x0 = x1 - length, y1 = box.y + box.size - 2.0f * pad, y0 = y1 - height;
  const float line = kLineShare * px;
  bool slipping = label.contact->point_load.slipping;
  for (const sim::PointLoad& l : label.contact->loads) slipping |= l.slipping;
  const auto width = [&](const char* text) { return font->CalcTextSizeA(px, FLT_MAX, 0.0f, text).x; };
  // A row of text right-aligned at x1, its top at y, on a backdrop as wide as it.
  const auto row = [&](float y, const char* text, ImU32 colour) {
    const float w = width(text);
    d.AddRectFilled(ImVec2(x1 - w - 1.5f * pad, y - 0.5f * pad), ImVec2(x1 + pad, y + line), kBox, pad);
    d.AddText(font, px, ImVec2(x1 - w, y), colour, text);
    return w;
  };
  d.AddRectFilled(ImVec2(x0 - 1.5f * pad, y0 - line - pad), ImVec2(x1 + pad, y1 + pad), kBox, pad);  // the bar and its ticks
  for (int k = 0; k < kColourBarSteps; ++k) {
    const float a = x0 + length * static_cast<float>(k) / kColourBarSteps, b = x0 + length * static_cast<float>(k + 1) / kColourBarSteps;
    const ImU32 ca = imguiColour(viridis(static_cast<double>(k) / kColourBarSteps));
    const ImU32 cb = imguiColour(viridis(static_cast<double>(k + 1) / kColourBarSteps));
    d.AddRectFilledMultiColor(ImVec2(a, y0), ImVec2(b + 0.5f, y1), ca, cb, cb, ca);
  }
  const float ty = y0 - line;
  char ticks[3][16];
  for (int k = 0; k < 3; ++k) std::snprintf(ticks[k], sizeof ticks[k], "%.3g", loads.loadAt(0.5 * k));
  const float w0 = width(ticks[0]), w1 = width(ticks[1]), w2 = width(ticks[2]);
  const bool ticked = w0 + w2 + px <= length;
  char name[96];
  if (ticked) {
    d.AddText(font, px, ImVec2(x0, ty), kText, ticks[0]);
    d.AddText(font, px, ImVec2(x1 - w2, ty), kText, ticks[2]);
    if (w0 + w1 + w2 + 2.0f * px <= length) d.AddText(font, px, ImVec2(x0 + 0.5f * (length - w1), ty), kText, ticks[1]);
    std::snprintf(name, sizeof name, "SGO load, N: min %.3g, max %.3g", loads.min_normal, loads.max_normal);
  } else {
    std::snprintf(name, sizeof name, "SGO load, N: %.2g - %.2g", loads.loadAt(0.0), loads.loadAt(1.0));
  }
  if (width(name) > box.size - 4.0f * pad) std::snprintf(name, sizeof name, "SGO load, N");
  const float name_y = ty - line;
  row(name_y, name, kSoftText);
  if (!label.close_up || !slipping) return;
  const float sw = row(name_y - line, "slipping", kSoftText);
  d.AddCircle(ImVec2(x1 - sw - 0.8f * px, name_y - line + 0.5f * px), 0.35f * px, kText, 0, 2.0f);
}

}  // namespace

float contactLabelPx(int size_px) {
  return std::clamp(std::round(kContactLabelShare * static_cast<float>(size_px)), kMinLabelPx, kMaxContactLabelPx);
}

float stampLabelPx(int height_px) { return std::max(kMinLabelPx, std::round(kStampLabelShare * static_cast<float>(height_px))); }

double scaleBarMetres(double view_m) {
  constexpr double kDecades[] = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};  // m
  double best = kDecades[0];
  for (const double decade : kDecades) {
    for (const double step : {1.0, 2.0, 5.0}) {
      if (step * decade <= kScaleBarShare * view_m) best = step * decade;
    }
  }
  return best;
}

void drawContactLabel(ImDrawList& d, ImFont* font, float px, const LabelBox& box, const ContactLabel& label) {
  const bool small = !label.close_up && box.size < kSmallInsetPx;
  const bool detail = label.close_up || box.size >= kDetailInsetPx;
  const float pad = kPadShare * px;
  const Caption c = caption(font, px, box.size - 2.0f * pad, label, small, detail);
  const float caption_h = static_cast<float>(c.count) * kLineShare * px + 2.0f * pad;
  const float top = label.close_up ? box.y : box.y - caption_h;
  d.AddRectFilled(ImVec2(box.x, top), ImVec2(box.x + box.size, top + caption_h), kBox);
  for (int k = 0; k < c.count; ++k) {
    d.AddText(font, px, ImVec2(box.x + pad, top + pad + kLineShare * px * static_cast<float>(k)), k == 0 ? kText : kSoftText,
              c.lines[static_cast<std::size_t>(k)].data());
  }
  const ImVec2 lo(box.x, box.y), hi(box.x + box.size, box.y + box.size);
  if (!label.contact) d.AddRectFilled(lo, hi, IM_COL32(40, 44, 52, 150));
  d.AddRect(ImVec2(lo.x, top), hi, imguiColour(fingerColour(label.finger_index)), 0.0f, 0, std::max(2.0f, 0.012f * box.size));
  if (!label.contact) return;
  const ViewAxes axes = viewAxes(label.camera, box.size);
  d.PushClipRect(lo, hi, true);
  const ContactForce force = contactForce(*label.state, *label.contact);
  const double ratio = force.normal > 0.0 ? force.tangential.norm() / force.normal : 0.0;
  if (ratio > kMinArrowRatio) {
    const Vec3 t = force.tangential.normalized();
    const float length = static_cast<float>(
        std::min(kArrowViewShare * box.size, force.tangential.norm() * label.arrow_m_per_n * axes.px_per_m));
    const ImVec2 centre(box.x + 0.5f * box.size, box.y + 0.5f * box.size);
    const ImVec2 tip(centre.x + length * static_cast<float>(t.dot(axes.right)), centre.y - length * static_cast<float>(t.dot(axes.up)));
    arrow2d(d, centre, tip, std::max(2.0f, 0.02f * box.size), imguiColour(Eigen::Vector3f(1.0f, 0.75f, 0.1f)));
  }
  scaleBar(d, font, px, box, axes.px_per_m);
  if (contactLoads(*label.contact).shown) colourBar(d, font, px, box, label);
  d.PopClipRect();
}

float insetCaptionReserve(float px) { return static_cast<float>(kMaxLines) * kLineShare * px + 2.0f * kPadShare * px; }

namespace {

// The stamp's lines; returns how many.
int stampLines(char (&lines)[2][64], double time, double arrow_m_per_n) {
  std::snprintf(lines[0], sizeof lines[0], "t = %.3f s", time);
  if (!(arrow_m_per_n > 0.0)) return 1;
  std::snprintf(lines[1], sizeof lines[1], "force arrow 1 cm = %g N", 0.01 / arrow_m_per_n);
  return 2;
}

}  // namespace

StampSize stampSize(float px, double time, double arrow_m_per_n) {
  char lines[2][64];
  const int count = stampLines(lines, time, arrow_m_per_n);
  std::size_t chars = 0;
  for (int k = 0; k < count; ++k) chars = std::max(chars, std::strlen(lines[k]));
  const float pad = kPadShare * px;
  return {static_cast<float>(chars) * kGlyphAdvance * px + 2.0f * pad, static_cast<float>(count) * kLineShare * px + 2.0f * pad};
}

void drawFrameStamp(const ImGuiLayer& layer, float px, float at_x, float at_y, double time, double arrow_m_per_n) {
  ImDrawList& d = *ImGui::GetForegroundDrawList();
  ImFont* font = layer.font(px);
  char lines[2][64];
  const int count = stampLines(lines, time, arrow_m_per_n);
  const StampSize size = stampSize(px, time, arrow_m_per_n);
  const float pad = kPadShare * px;
  d.AddRectFilled(ImVec2(at_x, at_y), ImVec2(at_x + size.w, at_y + size.h), kStampBox, pad);
  for (int k = 0; k < count; ++k) {
    d.AddText(font, px, ImVec2(at_x + pad, at_y + pad + kLineShare * px * static_cast<float>(k)), k == 0 ? kText : kSoftText, lines[k]);
  }
}

}  // namespace gf::render

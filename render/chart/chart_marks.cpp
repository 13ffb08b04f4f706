#include "render/chart/chart_marks.hpp"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <optional>
#include <utility>

namespace gf::render::chart_marks {
namespace {

constexpr ImU32 kOutline = IM_COL32(40, 40, 40, 255);

// A dash pattern: lengths (pixels) of alternating on and off stretches, starting on. Dots are
// short dashes of a wider stroke, long enough to read as dots rather than a thin line.
struct Pattern {
  std::array<float, 4> stretch;
  int count;
};

Pattern pattern(LineDash dash) {
  switch (dash) {
    case LineDash::kSolid: break;
    case LineDash::kDashed: return {{11.0f, 6.0f, 0.0f, 0.0f}, 2};
    case LineDash::kDashDot: return {{11.0f, 4.5f, 2.5f, 4.5f}, 4};
    case LineDash::kDotted: return {{2.5f, 4.0f, 0.0f, 0.0f}, 2};
  }
  return {{1.0f, 0.0f, 0.0f, 0.0f}, 1};
}

}  // namespace

int drawOrder(LineDash dash) { return static_cast<int>(dash); }

void strokePath(ChartPen& pen, const std::vector<ImVec2>& path, ImU32 colour, float width, LineDash dash) {
  if (path.size() < 2) return;
  const Pattern p = pattern(dash);
  pen.svgPolyline(path, colour, width,
                  dash == LineDash::kSolid ? std::vector<float>{}
                                           : std::vector<float>(p.stretch.begin(), p.stretch.begin() + p.count));
  ImDrawList& d = pen.list();
  if (dash == LineDash::kSolid) {
    for (std::size_t i = 1; i < path.size(); ++i) d.AddLine(path[i - 1], path[i], colour, width);
    return;
  }
  int stretch = 0;
  float left = p.stretch[0];  // pixels left of the current stretch
  for (std::size_t i = 1; i < path.size(); ++i) {
    ImVec2 a = path[i - 1];
    const ImVec2 b = path[i];
    float length = std::hypot(b.x - a.x, b.y - a.y);
    while (length > 0.0f) {
      const float step = std::min(left, length);
      const float t = step / length;
      const ImVec2 end(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
      if (stretch % 2 == 0) d.AddLine(a, end, colour, width);
      a = end;
      length -= step;
      left -= step;
      if (left <= 0.0f) {
        stretch = (stretch + 1) % p.count;
        left = p.stretch[static_cast<std::size_t>(stretch)];
      }
    }
  }
}

namespace {

// A cross or plus: two bars, a dark one under a coloured one. `diagonal`: a cross.
void drawBars(ChartPen& d, ImVec2 c, ImU32 colour, bool diagonal) {
  const float h = diagonal ? 0.95f * kMarkerRadiusPx : 1.2f * kMarkerRadiusPx;
  const ImVec2 a = diagonal ? ImVec2(h, h) : ImVec2(h, 0.0f), b = diagonal ? ImVec2(h, -h) : ImVec2(0.0f, h);
  for (const auto& [ink, width] : {std::pair{kOutline, 4.2f}, std::pair{colour, 2.4f}}) {
    d.line(ImVec2(c.x - a.x, c.y - a.y), ImVec2(c.x + a.x, c.y + a.y), ink, width);
    d.line(ImVec2(c.x - b.x, c.y - b.y), ImVec2(c.x + b.x, c.y + b.y), ink, width);
  }
}

}  // namespace

void drawMarker(ChartPen& d, ImVec2 c, ImU32 colour, MarkerShape shape) {
  const float r = kMarkerRadiusPx;
  const auto polygon = [&](const std::vector<ImVec2>& p) {
    d.polygonFilled(p, colour);
    d.polygon(p, kOutline);
  };
  switch (shape) {
    case MarkerShape::kCircle:
      d.circleFilled(c, r, colour);
      d.circle(c, r, kOutline);
      return;
    case MarkerShape::kSquare: {
      const float h = 0.85f * r;  // the same ink as the circle's
      d.rectFilled(ImVec2(c.x - h, c.y - h), ImVec2(c.x + h, c.y + h), colour);
      d.rect(ImVec2(c.x - h, c.y - h), ImVec2(c.x + h, c.y + h), kOutline);
      return;
    }
    case MarkerShape::kTriangle:
    case MarkerShape::kTriangleDown: {
      const float h = 1.25f * r, s = shape == MarkerShape::kTriangle ? 1.0f : -1.0f;
      polygon({ImVec2(c.x, c.y - s * h), ImVec2(c.x - h, c.y + s * 0.75f * h), ImVec2(c.x + h, c.y + s * 0.75f * h)});
      return;
    }
    case MarkerShape::kDiamond: {
      const float h = 1.2f * r;
      polygon({ImVec2(c.x, c.y - h), ImVec2(c.x + h, c.y), ImVec2(c.x, c.y + h), ImVec2(c.x - h, c.y)});
      return;
    }
    case MarkerShape::kCross:
    case MarkerShape::kPlus: drawBars(d, c, colour, shape == MarkerShape::kCross); return;
  }
}

void markersAlong(ChartPen& d, const std::vector<ImVec2>& path, float x0, float spacing, float phase, ImU32 colour,
                  MarkerShape shape) {
  if (path.size() < 2 || !(spacing > 0.0f)) return;
  // The first marker position at or right of the path's start.
  float next = x0 + phase * spacing;
  if (next < path.front().x) next += std::ceil((path.front().x - next) / spacing) * spacing;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const ImVec2 a = path[i - 1], b = path[i];
    while (b.x > a.x && next >= a.x && next < b.x) {
      const float t = (next - a.x) / (b.x - a.x);
      drawMarker(d, ImVec2(next, a.y + t * (b.y - a.y)), colour, shape);
      next += spacing;
    }
  }
}

void wrapText(const std::string& text, float size, float width, std::vector<std::string>& lines) {
  const auto wide = [&](const std::string& s) { return ImGui::GetFont()->CalcTextSizeA(size, FLT_MAX, 0.0f, s.c_str()).x; };
  std::string line;
  for (std::size_t a = 0; a < text.size();) {
    const std::size_t b = std::min(text.find(' ', a), text.size());
    const std::string word = text.substr(a, b - a);
    a = b + 1;
    if (!line.empty() && wide(line + " " + word) > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) lines.push_back(line);
}

Placed placeLabel(ImVec2 plot_lo, ImVec2 plot_hi, ImVec2 p, ImVec2 size, const std::vector<Box>& taken) {
  const float r = 0.75f * kMarkerRadiusPx, right = p.x + r, left = p.x - r - size.x;
  const float up = p.y - r - size.y, down = p.y + r, level = p.y - size.y / 2;
  const std::array<ImVec2, 6> near = {ImVec2(right, up),   ImVec2(right, down),
                                      ImVec2(left, up),    ImVec2(left, down),
                                      ImVec2(p.x + 1.5f * kMarkerRadiusPx, level),
                                      ImVec2(p.x - 1.5f * kMarkerRadiusPx - size.x, level)};
  const auto free = [&](const Box& b) {
    return std::none_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); });
  };
  std::optional<Box> fallback;
  for (const ImVec2& corner : near) {
    const Box b{corner, ImVec2(corner.x + size.x, corner.y + size.y)};
    if (!b.inside(plot_lo, plot_hi)) continue;
    if (free(b)) return {b, false};
    if (!fallback) fallback = b;
  }
  // Further out, in the same order of directions, up and down as well.
  const std::array<ImVec2, 8> ways = {ImVec2(1, -1), ImVec2(1, 1),  ImVec2(-1, -1), ImVec2(-1, 1),
                                      ImVec2(1, 0),  ImVec2(-1, 0), ImVec2(0, -1),  ImVec2(0, 1)};
  for (const float reach : {1.5f, 3.0f, 5.0f}) {
    const float d = reach * size.y;
    for (const ImVec2& w : ways) {
      // The box's corner nearest the marker sits `d` away along `w`.
      const ImVec2 at(p.x + w.x * d - (w.x < 0 ? size.x : w.x == 0 ? size.x / 2 : 0.0f),
                      p.y + w.y * d - (w.y < 0 ? size.y : w.y == 0 ? size.y / 2 : 0.0f));
      const Box b{at, ImVec2(at.x + size.x, at.y + size.y)};
      if (b.inside(plot_lo, plot_hi) && free(b)) return {b, true};
    }
  }
  if (fallback) return {*fallback, false};
  // Larger than the room left: pushed inside the plot from the up-right place.
  const ImVec2 lo(std::clamp(right, plot_lo.x, std::max(plot_lo.x, plot_hi.x - size.x)),
                  std::clamp(up, plot_lo.y, std::max(plot_lo.y, plot_hi.y - size.y)));
  return {{lo, ImVec2(lo.x + size.x, lo.y + size.y)}, false};
}

}  // namespace gf::render::chart_marks

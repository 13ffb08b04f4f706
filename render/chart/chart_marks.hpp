// The strokes and marks of render/chart/chart.cpp: dashed polylines, marker shapes, markers spaced
// along a curve. Internal to the chart code (ImGui draw lists, render thread only).
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

#include "render/chart/chart_pen.hpp"
#include "render/chart/chart_style.hpp"

namespace gf::render::chart_marks {

/// The marker's size: the radius of a circle, half the side of a square (pixels).
inline constexpr float kMarkerRadiusPx = 4.5f;

/// Draws `path` (pixels) in `dash`'s pattern, the pattern running on across its corners (in the
/// SVG, one polyline with its dash array).
void strokePath(ChartPen& d, const std::vector<ImVec2>& path, ImU32 colour, float width, LineDash dash);

/// A filled marker of `shape` centred at `centre`, with a dark outline.
void drawMarker(ChartPen& d, ImVec2 centre, ImU32 colour, MarkerShape shape);

/// Markers of `shape` where `path` (left to right) crosses x = x0 + (k + phase) * spacing.
void markersAlong(ChartPen& d, const std::vector<ImVec2>& path, float x0, float spacing, float phase, ImU32 colour,
                  MarkerShape shape);

/// A rectangle of pixels.
struct Box {
  ImVec2 lo, hi;
  bool overlaps(const Box& o) const { return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y; }
  bool inside(ImVec2 a, ImVec2 b) const { return lo.x >= a.x && lo.y >= a.y && hi.x <= b.x && hi.y <= b.y; }
};

/// Where a point label goes, and whether it is away from its marker (drawn with a leader line).
struct Placed {
  Box box;
  bool leader = false;
};

/// A label of `size` for the marker at `p` inside the plot [plot_lo, plot_hi]: up-right of it,
/// else down-right, up-left, down-left, right or left, whichever first lies inside the plot and
/// off `taken`; else the same eight ways further out (1.5, 3 and 5 label heights: a leader line
/// joins it to its marker); else the first place inside, on what it overlaps.
Placed placeLabel(ImVec2 plot_lo, ImVec2 plot_hi, ImVec2 p, ImVec2 size, const std::vector<Box>& taken);

/// Appends `text` to `lines` wrapped at spaces into lines of at most `width` pixels in text
/// `size` pixels high (a word longer than that is a line of its own).
void wrapText(const std::string& text, float size, float width, std::vector<std::string>& lines);

/// The order lines are drawn in: solid first, then the broken patterns, sparsest last.
int drawOrder(LineDash dash);

}  // namespace gf::render::chart_marks

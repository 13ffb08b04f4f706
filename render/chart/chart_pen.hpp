// What the chart code draws with: each primitive goes to an ImGui draw list (the PNG) and, when
// asked, to an SVG document of the same picture (lines, polylines with their dash pattern,
// polygons, circles, text as text). Internal to the chart code; render thread only (the ImGui
// font measures text); allocates.
#pragma once

#include <imgui.h>

#include <string>
#include <vector>

namespace gf::render {

/// The SVG elements of a chart, appended by a ChartPen; svgDocument() wraps them.
struct SvgText {
  std::string body;  ///< elements, one a line
  int next_clip = 0;  ///< ids of clip paths: c0, c1, ...
};

/// An SVG document of `width` x `height` pixels holding `svg`'s elements on a white ground.
std::string svgDocument(const SvgText& svg, int width, int height);

/// Draws to `list` and, when `svg` is not null, writes the same into it.
class ChartPen {
 public:
  ChartPen(ImDrawList& list, SvgText* svg) : list_(list), svg_(svg) {}

  /// The draw list, for strokes the SVG writes otherwise (a dashed line: see polyline()).
  ImDrawList& list() { return list_; }

  void line(ImVec2 a, ImVec2 b, ImU32 colour, float width = 1.0f);
  void rect(ImVec2 lo, ImVec2 hi, ImU32 colour, float width = 1.0f);
  void rectFilled(ImVec2 lo, ImVec2 hi, ImU32 colour);
  /// A convex polygon (a triangle, a quad), filled.
  void polygonFilled(const std::vector<ImVec2>& points, ImU32 colour);
  /// A closed polygon's outline.
  void polygon(const std::vector<ImVec2>& points, ImU32 colour, float width = 1.0f);
  void circleFilled(ImVec2 centre, float radius, ImU32 colour);
  void circle(ImVec2 centre, float radius, ImU32 colour, float width = 1.0f);
  /// `text` in the font at `size` pixels, its top-left corner at `at`.
  void text(ImVec2 at, float size, ImU32 colour, const std::string& text);
  /// The SVG only: a polyline with `dash` (on, off, ... lengths in pixels; empty: solid). The
  /// draw list gets its dashes from the caller.
  void svgPolyline(const std::vector<ImVec2>& points, ImU32 colour, float width, const std::vector<float>& dash);
  /// Clips what follows to [lo, hi] until popClip().
  void pushClip(ImVec2 lo, ImVec2 hi);
  void popClip();

 private:
  ImDrawList& list_;
  SvgText* svg_;
};

}  // namespace gf::render

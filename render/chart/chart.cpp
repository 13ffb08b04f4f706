#include "render/chart/chart.hpp"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/chart/chart_axes.hpp"
#include "render/chart/chart_marks.hpp"
#include "render/gl/context.hpp"
#include "render/gl/imgui_layer.hpp"

namespace gf::render {
namespace {

using chart_marks::Box;
using chart_marks::kMarkerRadiusPx;
using namespace chart_axes;
constexpr ImU32 kInk = IM_COL32(30, 30, 30, 255), kGrid = IM_COL32(220, 220, 220, 255);
constexpr ImU32 kMinorGrid = IM_COL32(238, 238, 238, 255);

// One legend entry: its series and its width in pixels (swatch, gap, text, gap).
struct LegendEntry {
  const ChartSeries* series;
  float width;
};

// Where the parts of the chart go, in pixels.
struct Layout {
  ImVec2 lo, hi;          // the plot's top-left and bottom-right corners
  ImVec2 title, y_label;  // top-left corners of the texts
  // The legend: rows of entries above the plot, right-aligned, off the data.
  std::vector<std::vector<LegendEntry>> legend;
  float legend_top = 0.0f;
  float stamp_y = 0.0f;  // the stamp's text's top: on the title's line, or a line of its own under it
};

float legendRowHeight(float font) { return 1.3f * font; }
// A legend entry's sample of line and marker: long enough for two dashes of a dashed line.
float legendSwatch(float font) { return 2.5f * font; }
// Notes under the x axis's label: smaller text, one line each.
float noteSize(float font) { return 0.85f * font; }
float noteRowHeight(float font) { return 1.2f * noteSize(font); }
// The notes' lines: each note wrapped at spaces to the chart's width.
std::vector<std::string> noteLines(const ChartSpec& chart, float font) {
  std::vector<std::string> out;
  for (const std::string& note : chart.notes) {
    chart_marks::wrapText(note, noteSize(font), static_cast<float>(chart.width) - 0.8f * font, out);
  }
  return out;
}

// `origin`: the chart's top-left corner in the frame (pixels).
Layout layout(const ChartSpec& chart, float font, ImVec2 origin) {
  Layout l;
  l.lo = ImVec2(origin.x + 5.5f * font, origin.y + 2.5f * font);
  l.hi = ImVec2(origin.x + static_cast<float>(chart.width) - 1.5f * font,
                origin.y + static_cast<float>(chart.height) - 3.5f * font -
                    static_cast<float>(noteLines(chart, font).size()) * noteRowHeight(font));
  // A y label that would run into the title gets a line of its own above the plot.
  const float y_label_end = origin.x + 0.4f * font + ImGui::CalcTextSize(chart.y_label.c_str()).x;
  if (!chart.title.empty() && y_label_end > l.lo.x - 0.5f * font) l.lo.y += 1.4f * font;
  // The stamp on the title's line at the right, or on a line of its own when the title fills it.
  l.stamp_y = origin.y + 0.6f * font;
  if (!chart.stamp.empty()) {
    const float title_end = l.lo.x + ImGui::CalcTextSize(chart.title.c_str()).x;
    if (title_end + 2.0f * font + ImGui::CalcTextSize(chart.stamp.c_str()).x > l.hi.x) {
      l.stamp_y += 1.5f * font;
      l.lo.y += 1.5f * font;
    }
  }
  // Legend rows between the title and the plot, as many as its entries need beside the y label.
  const float room = l.hi.x - std::max(l.lo.x, y_label_end + font);
  float used = 0.0f;
  for (const ChartSeries& s : chart.series) {
    if (s.label.empty()) continue;
    const float width = legendSwatch(font) + 0.5f * font + ImGui::CalcTextSize(s.label.c_str()).x + 1.2f * font;
    if (l.legend.empty() || (used + width > room && !l.legend.back().empty())) {
      l.legend.emplace_back();
      used = 0.0f;
    }
    l.legend.back().push_back({&s, width});
    used += width;
  }
  l.legend_top = l.lo.y - 0.2f * font;
  l.lo.y += static_cast<float>(l.legend.size()) * legendRowHeight(font);
  // The y label sits just above the plot, on the last legend row's line: a line of its own when
  // that row reaches back over it.
  if (!l.legend.empty()) {
    float last = 0.0f;
    for (const LegendEntry& e : l.legend.back()) last += e.width;
    if (l.hi.x - last + 1.2f * font < y_label_end + font) l.lo.y += 1.4f * font;
  }
  l.title = ImVec2(l.lo.x, origin.y + 0.6f * font);
  l.y_label = ImVec2(origin.x + 0.4f * font, l.lo.y - 1.6f * font);
  return l;
}

// The chart being drawn: its draw list, fitted axes and plot corners.
struct Canvas {
  ChartPen& d;
  Axis x, y;
  ImVec2 lo, hi;
  float font;

  bool drawable(const ChartSeries& s, std::size_t i) const {
    return onAxis(s.x[i], x.log) && onAxis(s.y[i], y.log);
  }
  ImVec2 at(const ChartSeries& s, std::size_t i) const {
    return {x.pixel(s.x[i]), y.pixel(s.y[i])};
  }
};

Canvas canvas(ChartPen& d, const ChartSpec& chart, const Layout& l, float font) {
  DrawnValues v = drawnValues(chart);
  for (const ChartBand& b : chart.bands) {  // a log axis fitted to the data shows the bands too
    for (double y : {b.y_lo, b.y_hi}) {
      if (chart.log_y && onAxis(y, true) && !v.y.empty()) v.y.push_back(y);
    }
  }
  const Range xr = chart.log_x ? fitLog(v.x) : chart.x_max > chart.x_min ? Range{chart.x_min, chart.x_max} : fitLinearX(v.x);
  return {d,
          {xr, chart.log_x, l.lo.x, l.hi.x},
          {fitY(chart, v.y), chart.log_y, l.hi.y, l.lo.y},
          l.lo,
          l.hi,
          font};
}

// Grid lines (minor ones first, so major ones lie on top) and tick labels.
void drawGrid(const Canvas& c) {
  const std::vector<Tick> xt = ticks(c.x, 10), yt = ticks(c.y, 6);
  for (const bool major : {false, true}) {
    const ImU32 colour = major ? kGrid : kMinorGrid;
    for (const Tick& t : xt) {
      if (t.major == major)
        c.d.line(ImVec2(c.x.pixel(t.value), c.lo.y), ImVec2(c.x.pixel(t.value), c.hi.y), colour);
    }
    for (const Tick& t : yt) {
      if (t.major == major)
        c.d.line(ImVec2(c.lo.x, c.y.pixel(t.value)), ImVec2(c.hi.x, c.y.pixel(t.value)), colour);
    }
  }
  for (const Tick& t : xt) {
    if (!t.labelled) continue;
    const std::string text = tickText(t.value);
    const float width = ImGui::CalcTextSize(text.c_str()).x;
    c.d.text(ImVec2(c.x.pixel(t.value) - width / 2, c.hi.y + 0.3f * c.font), c.font, kInk, text);
  }
  for (const Tick& t : yt) {
    if (!t.labelled) continue;
    const std::string text = tickText(t.value);
    const float width = ImGui::CalcTextSize(text.c_str()).x;
    c.d.text(ImVec2(c.lo.x - width - 0.4f * c.font, c.y.pixel(t.value) - c.font / 2), c.font, kInk, text);
  }
}

// The series' polylines in pixels, broken where a point cannot be drawn. A run of points
// within one pixel column is kept as its first, lowest, highest and last point in their order
// (what a 1-pixel line shows of it), so a series of 25 000 samples costs a few thousand
// segments, not 25 000: the renderer's memory and time stay bounded by the chart's width.
std::vector<std::vector<ImVec2>> linePaths(const Canvas& c, const ChartSeries& s) {
  std::vector<std::vector<ImVec2>> paths;
  const std::size_t n = std::min(s.x.size(), s.y.size());
  bool have = false;  // a drawn point to continue from
  const auto to = [&](ImVec2 p) {
    if (!have) paths.emplace_back();
    paths.back().push_back(p);
    have = true;
  };
  for (std::size_t i = 0; i < n;) {
    if (!c.drawable(s, i)) {
      have = false;  // the line breaks here
      ++i;
      continue;
    }
    // The run of drawable points in i's pixel column: [i, j).
    const ImVec2 first = c.at(s, i);
    const float column = std::floor(first.x);
    std::size_t j = i + 1, low = i, high = i;
    for (; j < n && c.drawable(s, j); ++j) {
      const ImVec2 p = c.at(s, j);
      if (std::floor(p.x) != column) break;
      if (p.y < c.at(s, low).y) low = j;
      if (p.y > c.at(s, high).y) high = j;
    }
    to(first);
    const std::size_t a = std::min(low, high), b = std::max(low, high);
    if (a != i) to(c.at(s, a));
    if (b != a && b != i) to(c.at(s, b));
    if (j - 1 != b && j - 1 != i) to(c.at(s, j - 1));
    i = j;
  }
  return paths;
}

// A line in its dash pattern (dots a little wider, to read as dots).
constexpr float kLineWidthPx = 1.6f, kDotWidthPx = 2.6f;

void drawLines(const Canvas& c, const ChartSeries& s) {
  const float width = s.dash == LineDash::kDotted ? kDotWidthPx : kLineWidthPx;
  for (const std::vector<ImVec2>& path : linePaths(c, s)) {
    chart_marks::strokePath(c.d, path, imguiColour(s.colour), width, s.dash);
  }
}

// A line's markers along it (after every line, so no line covers them).
void drawLineMarkers(const Canvas& c, const ChartSeries& s) {
  if (s.style != SeriesStyle::kLine || !(s.marker_spacing_px > 0.0f)) return;
  for (const std::vector<ImVec2>& path : linePaths(c, s)) {
    chart_marks::markersAlong(c.d, path, c.lo.x, s.marker_spacing_px, s.marker_phase, imguiColour(s.colour), s.marker);
  }
}

void drawMarkers(const Canvas& c, const ChartSeries& s) {
  const ImU32 colour = imguiColour(s.colour);
  for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    if (c.drawable(s, i)) chart_marks::drawMarker(c.d, c.at(s, i), colour, s.marker);
  }
}

// The square inside each drawn marker: point labels keep off them.
std::vector<Box> markerBoxes(const Canvas& c, const ChartSpec& chart) {
  std::vector<Box> out;
  const float r = 0.7f * kMarkerRadiusPx;
  for (const ChartSeries& s : chart.series) {
    if (s.style == SeriesStyle::kLine) continue;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!c.drawable(s, i)) continue;
      const ImVec2 p = c.at(s, i);
      out.push_back({{p.x - r, p.y - r}, {p.x + r, p.y + r}});
    }
  }
  return out;
}

// A point label's ink: its series' colour, darkened to read on white (Okabe–Ito's orange and
// sky blue are pale as text).
ImU32 labelInk(const Eigen::Vector3f& colour) { return imguiColour(0.45f * colour); }

// Point labels in small text in their series' colour on a faint white backing, by their markers or, where those
// places are taken, further out with a thin leader line; each kept off the markers and the
// labels placed before it.
void drawPointLabels(const Canvas& c, const ChartSpec& chart, const std::vector<Box>& band_labels) {
  std::vector<Box> taken = markerBoxes(c, chart);
  taken.insert(taken.end(), band_labels.begin(), band_labels.end());
  const float size = 0.8f * c.font;
  for (const ChartSeries& s : chart.series) {
    for (std::size_t i = 0; i < s.point_labels.size() && i < s.x.size() && i < s.y.size(); ++i) {
      const char* text = s.point_labels[i].c_str();
      if (!*text || !c.drawable(s, i)) continue;
      const ImVec2 p = c.at(s, i);
      const chart_marks::Placed placed = chart_marks::placeLabel(
          c.lo, c.hi, p, ImGui::GetFont()->CalcTextSizeA(size, FLT_MAX, 0.0f, text), taken);
      const Box& box = placed.box;
      taken.push_back(box);
      if (placed.leader) {
        const ImVec2 end(std::clamp(p.x, box.lo.x, box.hi.x), std::clamp(p.y, box.lo.y, box.hi.y));
        c.d.line(p, end, IM_COL32(90, 90, 90, 255), 1.0f);
      }
      c.d.rectFilled(box.lo, box.hi, IM_COL32(255, 255, 255, 170));
      c.d.text(box.lo, size, labelInk(s.colour), text);
    }
  }
}

// The legend's rows above the plot, right-aligned: per labelled series its line, marker or both,
// then its label. Nothing of it lies on the data.
void drawLegend(const Canvas& c, const Layout& l) {
  const float f = c.font, swatch = legendSwatch(f);
  float y = l.legend_top;
  for (const std::vector<LegendEntry>& row : l.legend) {
    float width = 0.0f;
    for (const LegendEntry& e : row) width += e.width;
    float x = c.hi.x - width + 1.2f * f;
    for (const LegendEntry& e : row) {
      const ChartSeries& s = *e.series;
      const float middle = y + f / 2;
      if (s.style != SeriesStyle::kMarkers || s.legend_line) {
        chart_marks::strokePath(c.d, {ImVec2(x, middle), ImVec2(x + swatch, middle)}, imguiColour(s.colour),
                                s.dash == LineDash::kDotted ? 3.4f : 3.0f, s.dash);
      }
      if (s.style != SeriesStyle::kLine || s.marker_spacing_px > 0.0f)
        chart_marks::drawMarker(c.d, ImVec2(x + swatch / 2, middle), imguiColour(s.colour), s.marker);
      c.d.text(ImVec2(x + swatch + 0.5f * f, y), f, kInk, s.label);
      x += e.width;
    }
    y += legendRowHeight(f);
  }
}

// Where a series leaves the y axis's range (an outlier clipped by the fit, or a fixed range): a
// small triangle in its colour at the plot's top or bottom edge, one per pixel column and side.
// Returns whether any was drawn.
bool markBeyondRange(const Canvas& c, const ChartSeries& s) {
  if (c.y.log) return false;
  const ImU32 colour = imguiColour(s.colour);
  const float size = 0.35f * c.font;
  float last_above = -1e9f, last_below = -1e9f;
  bool any = false;
  for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
    if (!onAxis(s.x[i], c.x.log) || !std::isfinite(s.y[i])) continue;
    const bool above = s.y[i] > c.y.range.hi, below = s.y[i] < c.y.range.lo;
    if (!above && !below) continue;
    const float x = c.x.pixel(s.x[i]);
    float& last = above ? last_above : last_below;
    if (std::floor(x) == std::floor(last)) continue;
    last = x;
    any = true;
    if (above) {
      c.d.polygonFilled({ImVec2(x, c.lo.y), ImVec2(x - size, c.lo.y + 1.6f * size), ImVec2(x + size, c.lo.y + 1.6f * size)}, colour);
    } else {
      c.d.polygonFilled({ImVec2(x, c.hi.y), ImVec2(x - size, c.hi.y - 1.6f * size), ImVec2(x + size, c.hi.y - 1.6f * size)}, colour);
    }
  }
  return any;
}


// Each band: a translucent fill across the plot between its bounds (a bound the axis cannot
// show is the plot's edge), its label in small text inside it on the left.
// Returns the boxes of their labels, which point labels keep off.
std::vector<Box> drawBands(const Canvas& c, const ChartSpec& chart) {
  std::vector<Box> labels;
  const float size = 0.8f * c.font;
  for (const ChartBand& b : chart.bands) {
    // Inside the frame's pixels, which stay the frame's colour.
    const float top = c.lo.y + 1.0f, bottom = c.hi.y - 1.0f;
    const float lo = onAxis(b.y_lo, c.y.log) ? std::clamp(c.y.pixel(b.y_lo), top, bottom) : bottom;
    const float hi = onAxis(b.y_hi, c.y.log) ? std::clamp(c.y.pixel(b.y_hi), top, bottom) : top;
    if (!(lo > hi)) continue;
    const Eigen::Vector3f& k = b.colour;
    c.d.rectFilled(ImVec2(c.lo.x + 1.0f, hi), ImVec2(c.hi.x - 1.0f, lo), imguiColour(k, 0.22f));
    c.d.line(ImVec2(c.lo.x + 1.0f, hi), ImVec2(c.hi.x - 1.0f, hi), imguiColour(k, 0.8f), 1.0f);
    if (!b.label.empty()) {
      // At the band's bottom-left when there is room under its top (points at the band's edge,
      // e.g. at the floor itself, keep off it), else at its top-left.
      const ImVec2 extent = ImGui::GetFont()->CalcTextSizeA(size, FLT_MAX, 0.0f, b.label.c_str());
      const bool room = lo - hi > 2.0f * extent.y + 0.3f * c.font;
      const ImVec2 at(c.lo.x + 0.4f * c.font, room ? lo - extent.y - 0.15f * c.font : hi + 0.15f * c.font);
      c.d.text(at, size, kInk, b.label);
      labels.push_back({at, ImVec2(at.x + extent.x, at.y + extent.y)});
    }
  }
  return labels;
}

// The cursor: a line across the plot at cursor_x, and its label beside it at the plot's top on
// a white box (right of the line, or left of it where the right has no room).
void drawCursor(const Canvas& c, const ChartSpec& chart) {
  if (!std::isfinite(chart.cursor_x) || !onAxis(chart.cursor_x, chart.log_x)) return;
  const float x = c.x.pixel(chart.cursor_x);
  c.d.line(ImVec2(x, c.lo.y), ImVec2(x, c.hi.y), kInk, 1.5f);
  if (chart.cursor_label.empty()) return;
  const ImVec2 size = ImGui::CalcTextSize(chart.cursor_label.c_str());
  const float pad = 0.3f * c.font;
  const bool right = x + 2 * pad + size.x <= c.hi.x;
  const ImVec2 lo(right ? x + 1.0f : x - 1.0f - 2 * pad - size.x, c.lo.y + 1.0f);
  c.d.rectFilled(lo, ImVec2(lo.x + 2 * pad + size.x, lo.y + size.y + pad), IM_COL32(255, 255, 255, 230));
  c.d.text(ImVec2(lo.x + pad, lo.y + 0.5f * pad), c.font, kInk, chart.cursor_label);
}

// The data, clipped to the plot: bands under everything, every series' lines (solid ones first),
// then markers over them, then point labels, edge marks and the cursor. Returns whether a value
// lay beyond the y axis.
bool drawData(const Canvas& c, const ChartSpec& chart) {
  c.d.pushClip(c.lo, c.hi);
  const std::vector<Box> band_labels = drawBands(c, chart);
  std::vector<const ChartSeries*> lines;
  for (const ChartSeries& s : chart.series) {
    if (s.style != SeriesStyle::kMarkers) lines.push_back(&s);
  }
  std::stable_sort(lines.begin(), lines.end(), [](const ChartSeries* a, const ChartSeries* b) {
    return chart_marks::drawOrder(a->dash) < chart_marks::drawOrder(b->dash);
  });
  for (const ChartSeries* s : lines) drawLines(c, *s);
  for (const ChartSeries* s : lines) drawLineMarkers(c, *s);
  for (const ChartSeries& s : chart.series) {
    if (s.style != SeriesStyle::kLine) drawMarkers(c, s);
  }
  drawPointLabels(c, chart, band_labels);
  bool beyond = false;
  for (const ChartSeries& s : chart.series) beyond = markBeyondRange(c, s) || beyond;
  drawCursor(c, chart);
  c.d.popClip();
  return beyond;
}

// The stamp at the title's line on the right, in a box of its own: what the chart lacks.
void drawStamp(const Canvas& c, const ChartSpec& chart, const Layout& l) {
  if (chart.stamp.empty()) return;
  const ImVec2 size = ImGui::CalcTextSize(chart.stamp.c_str());
  const float pad = 0.3f * c.font;
  const ImVec2 lo(c.hi.x - size.x - 2 * pad, l.stamp_y - 0.5f * pad), hi(c.hi.x, l.stamp_y + size.y + 0.5f * pad);
  c.d.rectFilled(lo, hi, IM_COL32(255, 244, 214, 255));
  c.d.rect(lo, hi, IM_COL32(160, 90, 0, 255));
  c.d.text(ImVec2(lo.x + pad, l.stamp_y), c.font, kInk, chart.stamp);
}

}  // namespace

void addChart(ImDrawList& list, const ChartSpec& chart, float left, float top, SvgText* svg) {
  const float font = ImGui::GetFontSize();
  ChartPen d(list, svg);
  const Layout l = layout(chart, font, ImVec2(left, top));
  const Canvas c = canvas(d, chart, l, font);
  const float right = left + static_cast<float>(chart.width), bottom = top + static_cast<float>(chart.height);
  d.rectFilled(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(255, 255, 255, 255));
  drawGrid(c);
  const bool beyond = drawData(c, chart);
  d.rect(l.lo, l.hi, kInk);  // the frame, over the bands
  // Title, axis labels, legend, stamp, notes.
  const float x_label_y = l.hi.y + 1.9f * font;
  d.text(l.title, font, kInk, chart.title);
  d.text(ImVec2((l.lo.x + l.hi.x - ImGui::CalcTextSize(chart.x_label.c_str()).x) / 2, x_label_y), font, kInk,
         chart.x_label);
  d.text(l.y_label, font, kInk, chart.y_label);
  drawLegend(c, l);
  drawStamp(c, chart, l);
  if (beyond) {  // say what the edge triangles mean, under the plot on the right
    const char* note = "triangles at the edges: values beyond the y axis";
    d.text(ImVec2(l.hi.x - ImGui::CalcTextSize(note).x, x_label_y), font, kInk, note);
  }
  const std::vector<std::string> notes = noteLines(chart, font);
  for (std::size_t k = 0; k < notes.size(); ++k) {
    const float y = x_label_y + 1.3f * font + static_cast<float>(k) * noteRowHeight(font);
    d.text(ImVec2(left + 0.4f * font, y), noteSize(font), kInk, notes[k]);
  }
}

void drawChart(ImGuiLayer& layer, const ChartSpec& chart, SvgText* svg) {
  GF_ASSERT_GL_THREAD();
  layer.beginFrame(1.0 / 60.0, {});
  addChart(*ImGui::GetForegroundDrawList(), chart, 0.0f, 0.0f, svg);
  layer.render();
}

}  // namespace gf::render

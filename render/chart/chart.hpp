// Charts drawn with ImGui's draw lists into a PNG, and the same picture as SVG: the Fig. 8 force
// curve (lines on linear axes) and work-precision diagrams (markers with point labels on log-log
// axes). Series are told apart by colour, marker and dash together (seriesLook()).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "render/chart/chart_style.hpp"

struct ImDrawList;

namespace gf::render {

/// One curve or set of points. A point is drawn only when both its coordinates can be drawn
/// on their axes (finite; positive on a log axis); a segment only when both its ends are.
struct ChartSeries {
  std::string label;  ///< legend text; empty: not in the legend
  Eigen::Vector3f colour = Eigen::Vector3f(0.1f, 0.3f, 0.9f);  ///< linear RGB
  std::vector<double> x, y;
  SeriesStyle style = SeriesStyle::kLine;
  /// Empty, or one per point (as many as x): small text in the series' colour (darkened) up-right
  /// of each point's marker, kept inside the plot and off other labels and markers. Empty
  /// strings are not drawn.
  std::vector<std::string> point_labels = {};
  LineDash dash = LineDash::kSolid;
  MarkerShape marker = MarkerShape::kCircle;
  /// A line's markers along its curve (kLine only): one every `marker_spacing_px` pixels along
  /// x, shifted by `marker_phase` (a share of the spacing), so that curves lying on one another
  /// keep their markers apart; 0: none.
  float marker_spacing_px = 0.0f, marker_phase = 0.0f;
  /// kMarkers: the legend's swatch shows a line in `dash` behind the marker too (for markers
  /// joined by a line drawn as an unlabelled series of its own).
  bool legend_line = false;
};

/// A horizontal band shaded across the plot (e.g. a reference's own noise floor), with its
/// label in small text inside it on the left (at its bottom when it has room for two lines, so
/// points on its top edge keep off it); point labels keep off it. A bound that cannot be drawn on the y
/// axis (not finite; not positive on a log axis) is the plot's edge. A log axis fitted to the
/// data also spans the band's finite, positive bounds.
struct ChartBand {
  double y_lo = 0.0, y_hi = 0.0;
  std::string label;
  Eigen::Vector3f colour = Eigen::Vector3f(0.5f, 0.5f, 0.5f);  ///< linear RGB, drawn translucent
};

/// A chart: axes fitted to the data, ticks, labels and a legend above the plot (right-aligned,
/// in as many rows as it needs, never on the data). A linear x axis spans the data; a linear y
/// axis every value, padded by 5 %, unless that is more than 4 times the span of the 0.2 % to
/// 99.8 % quantiles (a few impacts would flatten every curve): then the quantiles, padded by
/// 5 %, and each value beyond is marked by a triangle in its series' colour at the plot's edge,
/// with a note under the plot (as are values beyond a fixed range).
/// A log axis spans the positive data (at least one decade, centred on it), snapped outward to
/// decades when that is more than one decade, then padded by 4 % of its span in decades on each side; it has a tick at each decade
/// (labelled 1e-3, 0.01, 1, 100, ...) and faint minor lines at 2..9 times a decade, the 2 and 5
/// labelled too when the axis spans less than a decade.
struct ChartSpec {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  /// Fixed y range, used when y_max > y_min (and y_min > 0 on a log axis); otherwise fitted.
  double y_min = 0.0, y_max = 0.0;
  /// Fixed x range of a linear x axis, used when x_max > x_min (e.g. categories 1..n with room
  /// on either side); otherwise the data's span.
  double x_min = 0.0, x_max = 0.0;
  bool log_x = false, log_y = false;  ///< logarithmic (base 10) axes
  int width = 1200, height = 600;     ///< pixels
  /// A vertical line across the plot at this x (e.g. the time a video frame shows); none
  /// when not finite.
  double cursor_x = std::numeric_limits<double>::quiet_NaN();
  /// Text beside the cursor at the plot's top (e.g. "t = 2.50 s"): right of the line, or left of
  /// it near the plot's right edge.
  std::string cursor_label;
  std::vector<ChartBand> bands;
  /// Lines of small text under the x axis's label, left-aligned (e.g. what the point labels
  /// mean); the plot gives up their height.
  std::vector<std::string> notes;
  /// A stamp at the top right in a box of its own, e.g. "88 of 104 runs" when runs are missing;
  /// none when empty.
  std::string stamp;
};

class ImGuiLayer;
struct SvgText;

/// Builds the chart as an ImGui frame in `layer` (whose size must match) and renders it over
/// the bound framebuffer; also writes it into `svg` when not null (svgDocument() of
/// render/chart/chart_pen.hpp makes it a file). Render thread only; allocates.
void drawChart(ImGuiLayer& layer, const ChartSpec& chart, SvgText* svg = nullptr);

/// Adds the chart, chart.width x chart.height pixels with its top-left corner at (left, top),
/// to `list` inside an ImGui frame the caller has begun (e.g. under other pictures of a
/// frame), and into `svg` when not null. Render thread only; allocates.
void addChart(ImDrawList& list, const ChartSpec& chart, float left, float top, SvgText* svg = nullptr);

}  // namespace gf::render

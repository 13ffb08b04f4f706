// How a chart's series look: line or markers, the line's dash, the markers' shape. Shared by the
// chart (chart.hpp) and the marks that draw it (chart_marks.hpp).
#pragma once

namespace gf::render {

/// How a series is drawn.
enum class SeriesStyle {
  kLine,            ///< segments between consecutive points
  kMarkers,         ///< a filled circle at each point
  kLineAndMarkers,  ///< both
};

/// How a series' line is stroked. Solid lines are drawn first, then dashed, dash-dotted and
/// dotted ones over them, so a broken curve lying on a solid one leaves both visible.
enum class LineDash { kSolid, kDashed, kDashDot, kDotted };

/// The shape of a series' markers (and of its legend swatch's).
enum class MarkerShape { kCircle, kSquare, kTriangle, kDiamond };

}  // namespace gf::render

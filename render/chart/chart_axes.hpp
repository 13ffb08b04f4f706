// A chart's axes (render/chart/chart.cpp): the ranges fitted to the data, where a value lands in
// pixels, the ticks and their text. Internal to the chart code; pure functions, any thread.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "render/chart/chart.hpp"

namespace gf::render::chart_axes {

/// A log axis is padded by this share of its span (decades) on each side.
inline constexpr double kLogPad = 0.04;

/// A span of data values.
struct Range {
  double lo = 0.0, hi = 1.0;
};

/// Whether `v` can be drawn on a linear (log = false) or log axis.
inline bool onAxis(double v, bool log) {
  return std::isfinite(v) && (!log || v > 0.0);
}

/// One axis: its data range, its scale and the pixels of its two ends.
struct Axis {
  Range range;
  bool log = false;
  float px_lo = 0.0f, px_hi = 1.0f;  // pixels of range.lo and range.hi

  double coord(double v) const { return log ? std::log10(v) : v; }
  float pixel(double v) const {
    const double t = (coord(v) - coord(range.lo)) / (coord(range.hi) - coord(range.lo));
    return px_lo + static_cast<float>(t) * (px_hi - px_lo);
  }
  float decadePx() const {
    return std::abs(px_hi - px_lo) / static_cast<float>(std::log10(range.hi / range.lo));
  }
};

/// A tick: a grid line, labelled or not; minor lines are fainter.
struct Tick {
  double value;
  bool labelled, major;
};

/// The coordinates of the points drawable on both axes.
struct DrawnValues {
  std::vector<double> x, y;
};

/// The coordinates of `chart`'s points drawable on both its axes.
DrawnValues drawnValues(const ChartSpec& chart);

/// A linear x axis: the data's full span ({0, 1} without data).
Range fitLinearX(const std::vector<double>& v);

/// A log axis: the positive data's span, snapped outward to decades when it is more than one
/// (at least one decade, centred on the data), padded by kLogPad of its span in decades.
Range fitLog(const std::vector<double>& v);

/// The y axis of `chart` for the values `v` (ChartSpec says how).
Range fitY(const ChartSpec& chart, const std::vector<double>& v);

/// The ticks of `axis`: about `linear_count` on a linear one; decades and minor lines on a log one.
std::vector<Tick> ticks(const Axis& axis, int linear_count);

/// A tick's text: "%g" with the exponent unpadded (1e-5, 1e6).
std::string tickText(double v);

}  // namespace gf::render::chart_axes

#include "render/chart/chart_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gf::render::chart_axes {

constexpr float kMinorDecadePx = 30.0f;  // minor log grid lines only on decades this wide
constexpr int kMaxDecadeLabels = 12;

namespace {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `span`.
double tickStep(double span, int count) {
  const double raw = span / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

}  // namespace


DrawnValues drawnValues(const ChartSpec& chart) {
  DrawnValues out;
  for (const ChartSeries& s : chart.series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!onAxis(s.x[i], chart.log_x) || !onAxis(s.y[i], chart.log_y)) continue;
      out.x.push_back(s.x[i]);
      out.y.push_back(s.y[i]);
    }
  }
  return out;
}

// Linear x: the data's full span.
Range fitLinearX(const std::vector<double>& v) {
  if (v.empty()) return {0.0, 1.0};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi > *lo ? Range{*lo, *hi} : Range{0.0, 1.0};
}

namespace {

// Linear y: every value, padded by 5 %; or, when that span is more than kClipRatio times the
// 0.2 % to 99.8 % quantiles' (single-step impacts that would flatten every curve), the
// quantiles padded by 5 %, and `clipped` set so the values beyond are marked. Or the chart's
// fixed range (values beyond it marked too).
constexpr double kClipRatio = 4.0;

Range fitLinearY(std::vector<double> v, const ChartSpec& chart) {
  if (chart.y_max > chart.y_min) return {chart.y_min, chart.y_max};
  Range y{0.0, 0.0};
  if (!v.empty()) {
    std::sort(v.begin(), v.end());
    const Range all{v.front(), v.back()};
    // Outward-rounded indices: a series of fewer than 500 values keeps its extremes.
    const Range middle{v[static_cast<std::size_t>(std::floor(0.002 * static_cast<double>(v.size() - 1)))],
                       v[static_cast<std::size_t>(std::ceil(0.998 * static_cast<double>(v.size() - 1)))]};
    y = all.hi - all.lo > kClipRatio * (middle.hi - middle.lo) && middle.hi > middle.lo ? middle : all;
  }
  if (!(y.hi > y.lo)) {  // one value: a span around it that its magnitude can show
    const double half = y.lo != 0.0 ? 0.05 * std::abs(y.lo) : 1.0;
    y = {y.lo - half, y.lo + half};
  }
  const double pad = 0.05 * (y.hi - y.lo);
  return {y.lo - pad, y.hi + pad};
}

}  // namespace

// Log axis: the positive data's full span, snapped outward to decades when it is more than
// one decade (at least one decade, centred on the data, so a tick is always labelled), then
// padded by kLogPad of its span in decades.
Range fitLog(const std::vector<double>& v) {
  if (v.empty()) return {1.0, 10.0};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  double a = std::log10(*lo), b = std::log10(*hi);
  if (b - a > 1.0) {
    a = std::floor(a + 1e-9);
    b = std::ceil(b - 1e-9);
  }
  if (b - a < 1.0) {
    const double middle = 0.5 * (a + b);
    a = middle - 0.5;
    b = middle + 0.5;
  }
  const double pad = kLogPad * (b - a);
  return {std::pow(10.0, a - pad), std::pow(10.0, b + pad)};
}

Range fitY(const ChartSpec& chart, const std::vector<double>& v) {
  if (!chart.log_y) return fitLinearY(v, chart);
  if (chart.y_max > chart.y_min && chart.y_min > 0.0) return {chart.y_min, chart.y_max};
  return fitLog(v);
}

namespace {

std::vector<Tick> linearTicks(Range r, int count) {
  std::vector<Tick> out;
  const double step = tickStep(r.hi - r.lo, count);
  for (double v = std::ceil(r.lo / step) * step; v <= r.hi + 1e-9; v += step) {
    out.push_back({std::abs(v) < 1e-12 ? 0.0 : v, true, true});
  }
  return out;
}

// Decades (labelled; at most kMaxDecadeLabels of them), minor lines at 2..9 times a decade
// (with `minor`; 2 and 5 labelled when the axis spans less than a decade) and, when fewer than
// two ticks would be labelled, labels on every tick.
std::vector<Tick> logTicks(const Axis& axis) {
  const double a = std::log10(axis.range.lo), b = std::log10(axis.range.hi), eps = 1e-9;
  const bool minor = axis.decadePx() >= kMinorDecadePx, sub_decade = b - a < 1.0;
  const int k0 = static_cast<int>(std::floor(a)), k1 = static_cast<int>(std::ceil(b));
  const int every = std::max(1, (k1 - k0 + kMaxDecadeLabels - 1) / kMaxDecadeLabels);
  std::vector<Tick> out;
  int labelled = 0;
  for (int k = k0; k <= k1; ++k) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, k), t = std::log10(v);
      if (t < a - eps || t > b + eps) continue;
      const bool label =
          m == 1 ? (k % every + every) % every == 0 : sub_decade && (m == 2 || m == 5);
      if (m == 1 || minor) out.push_back({v, label, m == 1});
      labelled += label;
    }
  }
  if (labelled < 2) {
    for (Tick& tick : out) tick.labelled = true;
  }
  return out;
}

}  // namespace

std::vector<Tick> ticks(const Axis& axis, int linear_count) {
  return axis.log ? logTicks(axis) : linearTicks(axis.range, linear_count);
}

// "%g", with the exponent unpadded: 1e-05 -> 1e-5, 1e+06 -> 1e6.
std::string tickText(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  std::string text = buffer;
  std::size_t i = text.find('e');
  if (i == std::string::npos) return text;
  ++i;
  if (text[i] == '+') text.erase(i, 1);
  if (text[i] == '-') ++i;
  while (i + 1 < text.size() && text[i] == '0') text.erase(i, 1);
  return text;
}

}  // namespace gf::render::chart_axes

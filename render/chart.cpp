#include "render/chart.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/context.hpp"
#include "render/imgui_layer.hpp"

namespace gf::render {
namespace {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `span`.
double tickStep(double span, int count) {
  const double raw = span / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

struct Range {
  double lo = 0.0, hi = 1.0;
};

void fit(const ChartSpec& chart, Range& x, Range& y) {
  x = {HUGE_VAL, -HUGE_VAL};
  y = {HUGE_VAL, -HUGE_VAL};
  // y from the 0.2 % and 99.8 % quantiles: single-step impacts do not flatten the curves.
  std::vector<double> ys;
  for (const ChartSeries& s : chart.series) {
    for (double v : s.x) x = {std::min(x.lo, v), std::max(x.hi, v)};
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  if (!ys.empty()) {
    std::sort(ys.begin(), ys.end());
    y = {ys[static_cast<std::size_t>(0.002 * (ys.size() - 1))], ys[static_cast<std::size_t>(0.998 * (ys.size() - 1))]};
  }
  if (!(x.hi > x.lo)) x = {0.0, 1.0};
  if (chart.y_max > chart.y_min) y = {chart.y_min, chart.y_max};
  if (!(y.hi > y.lo)) y = {y.lo - 1.0, y.lo + 1.0};
  const double pad = 0.05 * (y.hi - y.lo);
  if (!(chart.y_max > chart.y_min)) y = {y.lo - pad, y.hi + pad};
}

}  // namespace

void drawChart(ImGuiLayer& layer, const ChartSpec& chart) {
  GF_ASSERT_GL_THREAD();
  layer.beginFrame(1.0 / 60.0, {});
  const float w = static_cast<float>(chart.width), h = static_cast<float>(chart.height);
  ImDrawList* d = ImGui::GetForegroundDrawList();
  const float font = ImGui::GetFontSize();
  const ImVec2 lo(5.5f * font, 2.5f * font), hi(w - 1.5f * font, h - 3.5f * font);
  const ImU32 ink = IM_COL32(30, 30, 30, 255), faint = IM_COL32(220, 220, 220, 255);
  d->AddRectFilled(ImVec2(0, 0), ImVec2(w, h), IM_COL32(255, 255, 255, 255));
  Range xr, yr;
  fit(chart, xr, yr);
  const auto px = [&](double x) { return lo.x + static_cast<float>((x - xr.lo) / (xr.hi - xr.lo)) * (hi.x - lo.x); };
  const auto py = [&](double y) { return hi.y - static_cast<float>((y - yr.lo) / (yr.hi - yr.lo)) * (hi.y - lo.y); };
  char text[64];
  // Grid and tick labels.
  const double xs = tickStep(xr.hi - xr.lo, 10), ys = tickStep(yr.hi - yr.lo, 6);
  for (double x = std::ceil(xr.lo / xs) * xs; x <= xr.hi + 1e-9; x += xs) {
    d->AddLine(ImVec2(px(x), lo.y), ImVec2(px(x), hi.y), faint);
    std::snprintf(text, sizeof text, "%g", std::abs(x) < 1e-12 ? 0.0 : x);
    d->AddText(ImVec2(px(x) - ImGui::CalcTextSize(text).x / 2, hi.y + 0.3f * font), ink, text);
  }
  for (double y = std::ceil(yr.lo / ys) * ys; y <= yr.hi + 1e-9; y += ys) {
    d->AddLine(ImVec2(lo.x, py(y)), ImVec2(hi.x, py(y)), faint);
    std::snprintf(text, sizeof text, "%g", std::abs(y) < 1e-12 ? 0.0 : y);
    d->AddText(ImVec2(lo.x - ImGui::CalcTextSize(text).x - 0.4f * font, py(y) - font / 2), ink, text);
  }
  d->AddRect(lo, hi, ink);
  // Curves, clipped to the plot.
  d->PushClipRect(lo, hi, true);
  for (const ChartSeries& s : chart.series) {
    for (std::size_t i = 1; i < s.x.size() && i < s.y.size(); ++i) {
      d->AddLine(ImVec2(px(s.x[i - 1]), py(s.y[i - 1])), ImVec2(px(s.x[i]), py(s.y[i])), imguiColour(s.colour), 1.6f);
    }
  }
  d->PopClipRect();
  // Title, axis labels, legend.
  d->AddText(ImVec2(lo.x, 0.6f * font), ink, chart.title.c_str());
  d->AddText(ImVec2((lo.x + hi.x - ImGui::CalcTextSize(chart.x_label.c_str()).x) / 2, h - 1.6f * font), ink,
             chart.x_label.c_str());
  d->AddText(ImVec2(0.4f * font, lo.y - 1.6f * font), ink, chart.y_label.c_str());
  float legend_y = lo.y + 0.6f * font;
  for (const ChartSeries& s : chart.series) {
    const float x = hi.x - 18.0f * font;
    d->AddLine(ImVec2(x, legend_y + font / 2), ImVec2(x + 2.0f * font, legend_y + font / 2), imguiColour(s.colour), 3.0f);
    d->AddText(ImVec2(x + 2.5f * font, legend_y), ink, s.label.c_str());
    legend_y += 1.3f * font;
  }
  layer.render();
}

}  // namespace gf::render

// Line charts drawn with ImGui's draw lists into a PNG: the Fig. 8 force curve.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace gf::render {

/// One curve.
struct ChartSeries {
  std::string label;
  Eigen::Vector3f colour = Eigen::Vector3f(0.1f, 0.3f, 0.9f);  ///< linear RGB
  std::vector<double> x, y;
};

/// A chart: axes fitted to the data (y range can be fixed), ticks, labels and a legend.
struct ChartSpec {
  std::string title, x_label, y_label;
  std::vector<ChartSeries> series;
  double y_min = 0.0, y_max = 0.0;  ///< equal: fitted to the data
  int width = 1200, height = 600;   ///< pixels
};

class ImGuiLayer;

/// Builds the chart as an ImGui frame in `layer` (whose size must match) and renders it over
/// the bound framebuffer. Render thread only.
void drawChart(ImGuiLayer& layer, const ChartSpec& chart);

}  // namespace gf::render

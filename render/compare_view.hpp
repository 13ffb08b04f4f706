// Frames of a side-by-side comparison (`godfinger compare`): one panel per contact model, each a
// frame of that model's run seen from the same camera and labelled with the model, its settings
// and its step time, above one chart of a trace quantity for every model with a cursor at the
// frame's time.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "render/chart.hpp"
#include "render/image.hpp"

namespace gf::render {

/// The label of one panel.
struct ComparePanel {
  std::string title;   ///< the model ("god-finger")
  std::string detail;  ///< its settings
  std::string timing;  ///< its step time; empty: not shown
  Eigen::Vector3f colour = Eigen::Vector3f(0.1f, 0.35f, 0.95f);  ///< its chart series' (linear RGB)
};

/// Where the parts of a width x height comparison frame go (pixels, origin top left).
struct CompareLayout {
  int panel_width = 0, panel_height = 0;  ///< each panel, at the frame's aspect ratio
  int panels_left = 0;                    ///< left edge of the first panel (the row is centred)
  int chart_top = 0, chart_height = 0;    ///< the chart: the full width under the panels
};

/// The layout of `panels` (1..4) side by side over a chart: panels at the frame's aspect ratio,
/// as large as leaves the chart at least 30 % of the height. Each panel is at least 16 x 16.
CompareLayout compareLayout(int width, int height, int panels);

/// Draws comparison frames. Needs a current GL context (render thread); construction makes the
/// framebuffer, the panel textures and the ImGui layer (allocates, throws GlError).
class CompareCompositor {
 public:
  /// `chart`: the series of every model over the whole run; its size is set from the layout.
  CompareCompositor(int width, int height, std::vector<ComparePanel> panels, ChartSpec chart);
  ~CompareCompositor();
  CompareCompositor(const CompareCompositor&) = delete;
  CompareCompositor& operator=(const CompareCompositor&) = delete;

  const CompareLayout& layout() const;
  /// Draws one frame into `out`: `images[i]` (a frame of model i's run, any size: scaled to its
  /// panel) in panel i with its label, the chart with its cursor at `time_s`.
  void compose(const std::vector<const Image*>& images, double time_s, Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

// Frames of a side-by-side comparison (`godfinger compare`): one panel per contact model, each a
// frame of that model's run seen from the same camera and labelled with the model, its settings
// and its step time, above one chart of a trace quantity for every model with a cursor at the
// frame's time, the time written beside it.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "render/chart/chart.hpp"
#include "render/frames/image.hpp"

namespace gf::render {

/// The label of one panel.
struct ComparePanel {
  std::string title;   ///< the model ("god-finger")
  std::string detail;  ///< its settings
  std::string timing;  ///< its step time; empty: not shown
  Eigen::Vector3f colour = Eigen::Vector3f(0.1f, 0.35f, 0.95f);  ///< its chart series' (linear RGB)
};

/// Where the parts of a comparison frame go (pixels, origin top left).
struct CompareLayout {
  int width = 0, height = 0;              ///< the comparison frame
  int panel_width = 0, panel_height = 0;  ///< each panel, at the scene frame's aspect ratio
  std::vector<Eigen::Vector2i> panels;    ///< each panel's top-left corner
  /// Three panels: the empty cell of the grid (right of the third panel), which holds the key to
  /// the pictures' marks; x < 0: none.
  Eigen::Vector2i key = Eigen::Vector2i(-1, -1);
  int chart_top = 0, chart_height = 0;    ///< the chart: the full width under the panels
};

/// The layout of `panels` (1..4) for a scene framed width x height (pixels). One or two panels
/// side by side over the chart, at the scene's aspect ratio, as large as leaves the chart at
/// least 30 % of the height, in a width x height frame. Three or four in a 2 x 2 grid of
/// half-size panels (beside a third, the key to the marks) over a chart of half the scene's
/// height (at least 220 pixels), in a frame about half again as tall as the scene's (a third of
/// it the chart; 1280 x 720: four 640 x 360 panels over a 1280 x 360 chart in a 1280 x 1080
/// frame), so that no panel is smaller than two models' are. Each panel is at least 16 x 16;
/// the frame's height is even. The chart's text is 17 px in a 1280-pixel-wide frame, in
/// proportion below, never under 11 px.
CompareLayout compareLayout(int width, int height, int panels);

/// Draws comparison frames. Needs a current GL context (render thread); construction makes the
/// framebuffer, the panel textures and the ImGui layer (allocates, throws GlError).
class CompareCompositor {
 public:
  /// `width` x `height`: the scene's frame (compareLayout gives the comparison's). `chart`: the
  /// series of every model over the whole run; its size is set from the layout.
  CompareCompositor(int width, int height, std::vector<ComparePanel> panels, ChartSpec chart);
  ~CompareCompositor();
  CompareCompositor(const CompareCompositor&) = delete;
  CompareCompositor& operator=(const CompareCompositor&) = delete;

  const CompareLayout& layout() const;
  /// Draws one frame into `out`: `images[i]` (a frame of model i's run, any size: scaled to its
  /// panel) in panel i with its label, in the grid's empty cell the key to the marks, the chart with its cursor at `time_s` and that time
  /// written beside it; `out` is layout().width x layout().height.
  void compose(const std::vector<const Image*>& images, double time_s, Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

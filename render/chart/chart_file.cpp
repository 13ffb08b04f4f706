#include "render/chart/chart_file.hpp"

#include <cstdint>
#include <vector>

#include "render/chart/chart_pen.hpp"
#include "render/frames/image.hpp"
#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/imgui_layer.hpp"

namespace gf::render {
namespace {

// The SVG beside a chart's PNG: the same name, .svg for .png (appended to another name).
std::string svgPathOf(const std::string& png_path) {
  const bool png = png_path.size() > 4 && png_path.compare(png_path.size() - 4, 4, ".png") == 0;
  return (png ? png_path.substr(0, png_path.size() - 4) : png_path) + ".svg";
}

}  // namespace

void drawChartFile(const ChartSpec& chart, const std::string& path) {
  Framebuffer frame(chart.width, chart.height, view::Antialiasing::kNone);  // ImGui smooths its own edges
  ImGuiLayer layer(chart.width, chart.height, 17.0f);
  frame.bind();
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  SvgText svg;
  drawChart(layer, chart, &svg);
  Image image;
  frame.read(image);
  writePng(path, image);
  const std::string text = svgDocument(svg, chart.width, chart.height);
  writeFileAtomically(svgPathOf(path), std::vector<std::uint8_t>(text.begin(), text.end()));
}

void writeChartPng(const ChartSpec& chart, const std::string& path) {
  GlContext context;
  drawChartFile(chart, path);
}

}  // namespace gf::render

// What makes a chart readable without colour and in print: Okabe–Ito's colours with a marker and
// a dash per series, point labels in their series' colour, the "N of M runs" stamp, the SVG
// written beside every PNG, and axis labels with their units that OCR (tesseract) reads back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "render/chart/chart.hpp"
#include "render/frames/image.hpp"
#include "render/render_thread.hpp"
#include "tests/scratch.hpp"

namespace gf::render {
namespace {

namespace fs = std::filesystem;

fs::path lookPng(const std::string& name) { return gf::test::scratchRoot() / ("gf_chart_look_" + name + ".png"); }

std::string lookText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Luma (Rec. 601) of a colour as shown, 0..255: what a grey-scale print keeps of it.
double printGrey(Srgb8 c) { return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b; }

// Three labelled line series with markers along them, one with point labels, on axes with units.
ChartSpec threeSeries() {
  ChartSpec chart;
  chart.title = "look";
  chart.x_label = "time, s";
  chart.y_label = "force, N";
  chart.width = 900;
  chart.height = 450;
  for (std::size_t i = 0; i < 3; ++i) {
    const SeriesLook look = seriesLook(i);
    ChartSeries s{"series " + std::to_string(i), look.colour, {0.0, 1.0, 2.0, 3.0},
                  {1.0 + i, 2.0 + i, 1.5 + i, 3.0 + i}, SeriesStyle::kLineAndMarkers};
    s.marker = look.marker;
    s.dash = look.dash;
    if (i == 1) s.point_labels = {"", "n8", "", ""};
    chart.series.push_back(s);
  }
  return chart;
}

// The first seven series differ in colour and in marker; the first 28 in marker and dash
// together; the colours are Okabe and Ito's published ones (yellow left out).
TEST(ChartLook, SeriesDifferInMarkerAndDashNotOnlyInColour) {
  for (std::size_t i = 0; i < 7; ++i) {
    for (std::size_t j = i + 1; j < 7; ++j) {
      EXPECT_NE(seriesLook(i).marker, seriesLook(j).marker) << i << " " << j;
      EXPECT_FALSE(seriesLook(i).colour.isApprox(seriesLook(j).colour)) << i << " " << j;
    }
  }
  std::set<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < 28; ++i) {
    pairs.insert({static_cast<int>(seriesLook(i).marker), static_cast<int>(seriesLook(i).dash)});
  }
  EXPECT_EQ(pairs.size(), 28u);
  EXPECT_EQ(kOkabeIto[0].r, 0);
  EXPECT_EQ(kOkabeIto[0].g, 114);
  EXPECT_EQ(kOkabeIto[0].b, 178);
  EXPECT_EQ(kOkabeIto[1].r, 213);
  EXPECT_EQ(kOkabeIto[4].g, 159);
  // Shown through the display gamma 2, the linear value gives back the published colour.
  EXPECT_NEAR(std::sqrt(linearFromSrgb(kOkabeIto[0]).y()) * 255.0, 114.0, 1e-3);
  // forces.png's pair (blue, orange) differs in grey by far more than its old red and blue.
  EXPECT_GT(printGrey(kOkabeIto[4]) - printGrey(kOkabeIto[0]), 60.0);
}

// Writing a chart's PNG writes the SVG beside it: one document, every element closed, the axis
// labels as text, a polyline per series (the dashed ones with their dash array), markers of
// several shapes, the point label in its series' colour (darkened), the plot clipped.
TEST(ChartSvg, IsWrittenBesideThePngAndIsWellFormed) {
  const fs::path png = lookPng("svg");
  fs::remove(fs::path(png).replace_extension(".svg"));
  writeChartPng(threeSeries(), png.string());
  const fs::path svg_path = fs::path(png).replace_extension(".svg");
  ASSERT_TRUE(fs::exists(svg_path));
  const std::string svg = lookText(svg_path);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"900\" height=\"450\""), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  // Every tag opened is closed, in order (self-closed ones aside).
  std::vector<std::string> open;
  for (std::size_t at = svg.find('<'); at != std::string::npos; at = svg.find('<', at + 1)) {
    const std::size_t end = svg.find('>', at);
    ASSERT_NE(end, std::string::npos);
    const std::string tag = svg.substr(at + 1, end - at - 1);
    if (tag.front() == '?' || tag.back() == '/') continue;
    const std::string name = tag.substr(tag.front() == '/' ? 1 : 0, tag.find(' ') == std::string::npos ? std::string::npos : tag.find(' ') - (tag.front() == '/' ? 1 : 0));
    if (tag.front() != '/') {
      open.push_back(name);
    } else {
      ASSERT_FALSE(open.empty()) << tag;
      EXPECT_EQ(open.back(), name);
      open.pop_back();
    }
  }
  EXPECT_TRUE(open.empty());
  EXPECT_NE(svg.find(">time, s</text>"), std::string::npos);
  EXPECT_NE(svg.find(">force, N</text>"), std::string::npos);
  EXPECT_NE(svg.find("<clipPath"), std::string::npos);
  EXPECT_GE(std::count(svg.begin(), svg.end(), '\n'), 40);
  int polylines = 0, dashed = 0;
  for (std::size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) {
    ++polylines;
    dashed += svg.substr(at, svg.find('>', at) - at).find("stroke-dasharray") != std::string::npos;
  }
  EXPECT_GE(polylines, 6);  // three series, three legend swatches
  EXPECT_GE(dashed, 4);     // the dashed and the dotted series, and their swatches
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_NE(svg.find("<polygon"), std::string::npos);  // the third series' triangles
  // The label "n8": series 1's vermillion (213, 94, 0), darkened to sqrt(0.45) of it.
  const std::size_t label = svg.find(">n8</text>");
  ASSERT_NE(label, std::string::npos);
  const std::string element = svg.substr(svg.rfind("<text", label), label - svg.rfind("<text", label));
  EXPECT_NE(element.find("fill=\"#8f3f00\""), std::string::npos) << element;
}

// A stamp's box (pale orange, 255 244 214) is drawn at the top right when the chart has one.
TEST(ChartStamp, IsDrawnAtTheTopRightOnlyWhenGiven) {
  const auto stampPixels = [](const ChartSpec& chart) {
    const fs::path png = lookPng(chart.stamp.empty() ? "unstamped" : "stamped");
    writeChartPng(chart, png.string());
    const Image image = readPng(png.string());
    int count = 0;
    for (int y = 0; y < image.height / 4; ++y) {
      for (int x = image.width / 2; x < image.width; ++x) {
        const std::uint8_t* p = &image.rgb[static_cast<std::size_t>(3 * (y * image.width + x))];
        count += p[0] == 255 && p[1] == 244 && p[2] == 214;
      }
    }
    return count;
  };
  ChartSpec chart = threeSeries();
  EXPECT_EQ(stampPixels(chart), 0);
  chart.stamp = "88 of 104 runs measured";
  EXPECT_GT(stampPixels(chart), 500);
}

// OCR (tesseract, sparse text) reads the axis labels' units back from the PNG as drawn: "time, s"
// and "force, N". (Enlarged three times without smoothing, the chart font's "s" reads as "5".)
TEST(ChartOcr, AxisUnitsReadBack) {
  ASSERT_EQ(std::system("command -v tesseract > /dev/null"), 0) << "tesseract is needed (scripts/test installs it)";
  const fs::path png = lookPng("ocr"), text = gf::test::scratchRoot() / "gf_chart_look_ocr";
  writeChartPng(threeSeries(), png.string());
  const std::string cmd = "tesseract " + png.string() + " " + text.string() + " --psm 11 > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string read = lookText(fs::path(text.string() + ".txt"));
  EXPECT_NE(read.find("time, s"), std::string::npos) << read;
  EXPECT_NE(read.find("force, N"), std::string::npos) << read;
}

}  // namespace
}  // namespace gf::render

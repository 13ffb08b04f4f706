// Charts drawn to PNG through writeChartPng: where points land on fitted log axes, what is not
// drawn (values a log axis cannot show, unlabelled series in the legend, labels off the plot),
// fixed y ranges, coinciding curves, the cursor's label, bands and notes. Positions are found from the plot's frame in the image.
#include "render/chart/chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "render/frames/image.hpp"
#include "render/render_thread.hpp"
#include "tests/scratch.hpp"

namespace gf::render {
namespace {

namespace fs = std::filesystem;

const Eigen::Vector3f kRed(1.0f, 0.0f, 0.0f), kBlue(0.0f, 0.0f, 1.0f), kGreen(0.0f, 1.0f, 0.0f);
constexpr double kLogPad = 0.04;  // ChartSpec: a log axis is padded by 4 % of its decades

// Draws `chart` through writeChartPng into a file of the running test's own, and reads it back.
Image drawChart(const ChartSpec& chart) {
  const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path path = gf::test::scratchRoot() / ("gf_chart_" + name + ".png");
  writeChartPng(chart, path.string());
  return readPng(path.string());
}

const std::uint8_t* pixel(const Image& image, int x, int y) {
  return &image.rgb[3 * (y * image.width + x)];
}

// Pure colours only: imguiColour keeps 0 and 1 as they are.
bool hasColour(const Image& image, int x, int y, const Eigen::Vector3f& colour) {
  const std::uint8_t* p = pixel(image, x, y);
  for (int c = 0; c < 3; ++c) {
    if (std::abs(p[c] - 255 * colour[c]) > 60) return false;
  }
  return true;
}

// Pixels of `colour` in the rectangle [x0, x1) x [y0, y1), clamped to the image.
int countColour(const Image& image, const Eigen::Vector3f& colour, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y) {
    for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x)
      count += hasColour(image, x, y, colour);
  }
  return count;
}

bool isWhite(const Image& image, int x, int y) {
  const std::uint8_t* p = pixel(image, x, y);
  return p[0] > 250 && p[1] > 250 && p[2] > 250;
}

// The plot's frame: the rows and columns that are mostly dark grey.
struct Plot {
  int left = -1, top = -1, right = -1, bottom = -1;
  int width() const { return right - left; }
  int height() const { return bottom - top; }
};

bool isFrameGrey(const Image& image, int x, int y) {
  const std::uint8_t* p = pixel(image, x, y);
  return p[0] < 170 && std::abs(p[0] - p[1]) < 8 && std::abs(p[1] - p[2]) < 8;
}

Plot findPlot(const Image& image) {
  Plot plot;
  for (int y = 0; y < image.height; ++y) {
    int grey = 0;
    for (int x = 0; x < image.width; ++x) grey += isFrameGrey(image, x, y);
    if (grey < 0.6 * image.width) continue;
    if (plot.top < 0) plot.top = y;
    plot.bottom = y;
  }
  for (int x = 0; x < image.width; ++x) {
    int grey = 0;
    for (int y = 0; y < image.height; ++y) grey += isFrameGrey(image, x, y);
    if (grey < 0.6 * image.height) continue;
    if (plot.left < 0) plot.left = x;
    plot.right = x;
  }
  return plot;
}

// Pixel of a value on a log axis spanning the decades [k_lo, k_hi] before padding.
double logPixel(double v, double k_lo, double k_hi, double px_lo, double px_hi) {
  const double pad = kLogPad * (k_hi - k_lo),
               t = (std::log10(v) - k_lo + pad) / (k_hi - k_lo + 2 * pad);
  return px_lo + t * (px_hi - px_lo);
}

// Two marker-and-line series on log-log axes, one with values the log y axis cannot show, and
// an unlabelled marker series. Drawn points fit x to the decades [1e-3, 0.1], y to [0.01, 100].
ChartSpec workPrecision() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ChartSpec chart;
  chart.title = "work-precision";
  chart.x_label = "step time (s)";
  chart.y_label = "|error| vs (2/3) mu F r";
  chart.log_x = chart.log_y = true;
  chart.width = 960;
  chart.height = 540;
  chart.series = {
      {"a",
       kRed,
       {1e-3, 1e-2, 1e-1},
       {100.0, 10.0, 1.0},
       SeriesStyle::kLineAndMarkers,
       {"3", "4", "8"}},
      {"b",
       kBlue,
       {2e-3, 2e-2, 5e-2, 7e-2, 9e-2},
       {0.5, 0.05, 0.0, -1.0, nan},
       SeriesStyle::kLineAndMarkers,
       {"3", "4", "8", "16", "32"}},
      {"", kGreen, {1.5e-3}, {0.02}, SeriesStyle::kMarkers},
  };
  return chart;
}

class WorkPrecisionChart : public ::testing::Test {
 protected:
  WorkPrecisionChart() : image_(drawChart(workPrecision())), plot_(findPlot(image_)) {}

  // Pixels of `colour` within 3 px of where (x, y) must be drawn (a marker: 7 x 7 = 49 px).
  int near(double x, double y, const Eigen::Vector3f& colour) const {
    const int px = static_cast<int>(std::lround(logPixel(x, -3, -1, plot_.left, plot_.right)));
    const int py = static_cast<int>(std::lround(logPixel(y, -2, 2, plot_.bottom, plot_.top)));
    return countColour(image_, colour, px - 3, py - 3, px + 4, py + 4);
  }

  Image image_;
  Plot plot_;
};

TEST_F(WorkPrecisionChart, HasTheRequestedSizeAndAPlotFrame) {
  EXPECT_EQ(image_.width, 960);
  EXPECT_EQ(image_.height, 540);
  EXPECT_GT(plot_.width(), 0.8 * 960);
  EXPECT_GT(plot_.height(), 0.7 * 540);
}

// Markers sit where the fitted decades put them (within 3 px): the point at the data's least
// x and greatest y in the plot's top-left corner, the others along the decades.
TEST_F(WorkPrecisionChart, MarkersLandWhereTheFittedDecadesPutThem) {
  EXPECT_GE(near(1e-3, 100.0, kRed), 30);
  EXPECT_GE(near(1e-2, 10.0, kRed), 30);
  EXPECT_GE(near(1e-1, 1.0, kRed), 30);
  EXPECT_GE(near(2e-3, 0.5, kBlue), 30);
  EXPECT_GE(near(2e-2, 0.05, kBlue), 30);
  EXPECT_GE(near(1.5e-3, 0.02, kGreen), 30);
  // The line between two markers passes through their midpoint (a straight line in log-log).
  EXPECT_GE(near(std::sqrt(2e-3 * 2e-2), std::sqrt(0.5 * 0.05), kBlue), 3);
}

// Values <= 0 or NaN on a log axis are not drawn, nor are the segments that reach them: no blue
// right of x = 0.03 in the lower three quarters of the plot (the legend sits above).
TEST_F(WorkPrecisionChart, ValuesALogAxisCannotShowAreNotDrawn) {
  const int x0 = static_cast<int>(logPixel(0.03, -3, -1, plot_.left, plot_.right));
  EXPECT_EQ(
      countColour(image_, kBlue, x0, plot_.top + plot_.height() / 4, plot_.right, plot_.bottom), 0);
}

// The legend, above the plot on the right (off the data), lists "a" and "b" but not the
// unlabelled green series (whose point is drawn: see above).
TEST_F(WorkPrecisionChart, LegendListsLabelledSeriesOnly) {
  const int x0 = plot_.left + plot_.width() / 2;
  EXPECT_GE(countColour(image_, kRed, x0, 0, plot_.right, plot_.top), 20);
  EXPECT_GE(countColour(image_, kBlue, x0, 0, plot_.right, plot_.top), 20);
  EXPECT_EQ(countColour(image_, kGreen, 0, 0, image_.width, plot_.top), 0);
}

// Point labels at the plot's corners are moved inside it: outside the frame, only the tick
// labels below and left of the plot are drawn (no title, axis labels or legend here).
TEST(Chart, PointLabelsStayInsideThePlot) {
  ChartSpec chart;
  chart.log_x = chart.log_y = true;
  chart.width = 640;
  chart.height = 360;
  chart.series = {{"",
                   kRed,
                   {1.0, 1000.0},
                   {1.0, 1000.0},
                   SeriesStyle::kMarkers,
                   {"a long label at a corner", "a long label at a corner"}}};
  const Image image = drawChart(chart);
  const Plot plot = findPlot(image);
  ASSERT_GT(plot.width(), 0);
  int ink_outside = 0;
  for (int y = 0; y < plot.bottom - 1; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool above = y<plot.top - 1, right = x> plot.right + 1;
      ink_outside += (above || right) && !isWhite(image, x, y);
    }
  }
  EXPECT_EQ(ink_outside, 0);
}

// A fixed y range is used as given (no padding): a constant at its middle is drawn on the
// plot's middle row, on a linear axis (0..10, y = 5) and a log axis (1..100, y = 10).
TEST(Chart, FixedYRangePutsItsMiddleOnTheMiddleRow) {
  for (const bool log : {false, true}) {
    ChartSpec chart;
    chart.width = 640;
    chart.height = 360;
    chart.log_y = log;
    chart.y_min = log ? 1.0 : 0.0;
    chart.y_max = log ? 100.0 : 10.0;
    const double y = log ? 10.0 : 5.0;
    chart.series = {{"", kBlue, {0.0, 10.0}, {y, y}}};
    const Image image = drawChart(chart);
    const Plot plot = findPlot(image);
    const int x = (plot.left + plot.right) / 2, middle = (plot.top + plot.bottom) / 2;
    double rows = 0.0;
    int count = 0;
    for (int r = plot.top + 2; r < plot.bottom - 1; ++r) {
      if (!hasColour(image, x, r, kBlue)) continue;
      rows += r;
      ++count;
    }
    ASSERT_GT(count, 0) << (log ? "log" : "linear");
    EXPECT_NEAR(rows / count, middle, 1.5) << (log ? "log" : "linear");
  }
}

// Nothing drawable on a log axis (zero, negative, NaN): the chart is still written, with the
// series in the legend only.
TEST(Chart, NothingDrawableStillWritesTheChart) {
  ChartSpec chart;
  chart.log_y = true;
  chart.width = 640;
  chart.height = 360;
  chart.series = {{"none",
                   kRed,
                   {1.0, 2.0, 3.0},
                   {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()},
                   SeriesStyle::kLineAndMarkers,
                   {"1", "2", "3"}}};
  const Image image = drawChart(chart);
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 360);
  const Plot plot = findPlot(image);
  EXPECT_EQ(
      countColour(image, kRed, plot.left, plot.top + plot.height() / 4, plot.right, plot.bottom),
      0);
  EXPECT_GT(countColour(image, kRed, plot.left, 0, plot.right, plot.top), 0);  // the legend
}

// A line chart fits all its curves: the highest and lowest values of both series are drawn
// inside the frame, within 2 px of where the 5 % padding puts them, and none on its edge.
TEST(Chart, LinesFitAllTheirCurves) {
  ChartSpec chart;
  chart.width = 800;
  chart.height = 400;
  std::vector<double> t, a, b;
  for (int i = 0; i <= 400; ++i) {
    t.push_back(i / 400.0);
    a.push_back(std::sin(20.0 * t.back()));              // -1 .. 1
    b.push_back(0.5 * std::sin(10.0 * t.back()) - 1.2);  // -1.7 .. -0.7
  }
  chart.series = {{"a", kRed, t, a}, {"b", kBlue, t, b}};
  const Image image = drawChart(chart);
  const Plot plot = findPlot(image);
  const double top = 1.0 + 0.05 * 2.7, bottom = -1.7 - 0.05 * 2.7;
  const auto row = [&](double v) {
    return static_cast<int>(std::lround(plot.bottom + (v - bottom) / (top - bottom) * (plot.top - plot.bottom)));
  };
  EXPECT_GT(row(1.0), plot.top + 5);
  EXPECT_LT(row(-1.7), plot.bottom - 5);
  EXPECT_GT(countColour(image, kRed, plot.left, row(1.0) - 2, plot.right, row(1.0) + 3), 0) << "a's maximum";
  EXPECT_EQ(countColour(image, kRed, plot.left, plot.top, plot.right, row(1.0) - 3), 0) << "nothing above it";
  EXPECT_GT(countColour(image, kBlue, plot.left, row(-1.7) - 2, plot.right, row(-1.7) + 3), 0) << "b's minimum";
  EXPECT_EQ(countColour(image, kBlue, plot.left, row(-1.7) + 4, plot.right, plot.bottom), 0) << "nothing below it";
}

// One impact a hundred times the curve's size would flatten it: the axis keeps to the curve and
// the impact is marked by a triangle at the top edge where it happens, in its series' colour.
TEST(Chart, AnOutlierBeyondTheFitIsMarkedAtTheEdge) {
  ChartSpec chart;
  chart.width = 800;
  chart.height = 400;
  std::vector<double> t, y;
  for (int i = 0; i <= 1000; ++i) {
    t.push_back(i / 1000.0);
    y.push_back(i == 500 ? 100.0 : std::sin(20.0 * t.back()));
  }
  chart.series = {{"a", kRed, t, y}};
  const Image image = drawChart(chart);
  const Plot plot = findPlot(image);
  const int middle = (plot.left + plot.right) / 2;
  // The curve fills the plot's height (its +-1 within the 5 % padding), not a flat line.
  EXPECT_GT(countColour(image, kRed, plot.left, plot.top + 5, plot.right, plot.top + plot.height() / 8), 0);
  EXPECT_GT(countColour(image, kRed, plot.left, plot.bottom - plot.height() / 8, plot.right, plot.bottom - 3), 0);
  // The triangle under the top edge at t = 0.5: a few pixels wide and tall.
  EXPECT_GE(countColour(image, kRed, middle - 6, plot.top + 1, middle + 7, plot.top + 6), 12);
}


bool isDark(const Image& image, int x, int y) {
  const std::uint8_t* p = pixel(image, x, y);
  return p[0] < 90 && p[1] < 90 && p[2] < 90;
}

int countDark(const Image& image, int x0, int y0, int x1, int y1) {
  int count = 0;
  for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y) {
    for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) count += isDark(image, x, y);
  }
  return count;
}

// Two curves on one another: the dashed one is listed first, yet the solid one is drawn under
// it, so both colours show along the curve; their markers (every 60 px, shifted by half of that)
// stand off the line, and the legend draws each line with its marker.
TEST(Chart, CoincidingCurvesBothStayVisible) {
  ChartSpec chart;
  chart.width = 800;
  chart.height = 400;
  const std::vector<double> t = {0.0, 1.0}, y = {0.0, 1.0};
  chart.series = {{"dashed", kBlue, t, y}, {"solid", kRed, t, y}};
  chart.series[0].dash = LineDash::kDashed;
  chart.series[0].marker = MarkerShape::kSquare;
  for (std::size_t k = 0; k < 2; ++k) {
    chart.series[k].marker_spacing_px = 60.0f;
    chart.series[k].marker_phase = 0.5f * static_cast<float>(k);
  }
  const Image image = drawChart(chart);
  const Plot plot = findPlot(image);
  const int red = countColour(image, kRed, plot.left + 2, plot.top + 2, plot.right - 1, plot.bottom - 1);
  const int blue = countColour(image, kBlue, plot.left + 2, plot.top + 2, plot.right - 1, plot.bottom - 1);
  RecordProperty("red_px", red);
  RecordProperty("blue_px", blue);
  // The diagonal is about 900 px long: each colour shows along a good part of it.
  EXPECT_GT(red, 300);
  EXPECT_GT(blue, 300);
  // The line is under 3 px thick, a marker 9 px across: columns where a colour lies 3 px
  // from the line's centre (the middle of the coloured pixels in the column) hold its markers.
  const auto blobs = [&](const Eigen::Vector3f& colour) {
    int n = 0;
    for (int x = plot.left + 10; x < plot.right - 10; ++x) {
      std::vector<int> rows;
      for (int row = plot.top + 1; row < plot.bottom; ++row) {
        if (hasColour(image, x, row, kRed) || hasColour(image, x, row, kBlue)) rows.push_back(row);
      }
      if (rows.empty()) continue;
      const int centre = rows[rows.size() / 2];
      for (int row : {centre - 3, centre + 3}) n += hasColour(image, x, row, colour);
    }
    return n;
  };
  EXPECT_GT(blobs(kRed), 0) << "red markers";
  EXPECT_GT(blobs(kBlue), 0) << "blue markers";
  // The legend, above the plot: both colours.
  EXPECT_GT(countColour(image, kRed, plot.left, 0, plot.right, plot.top), 20);
  EXPECT_GT(countColour(image, kBlue, plot.left, 0, plot.right, plot.top), 20);
}

// The cursor's label sits at the plot's top beside the line: right of it, or left of it near the
// plot's right edge; without a label nothing dark is there.
TEST(Chart, TheCursorsLabelSitsBesideIt) {
  ChartSpec chart;
  chart.width = 800;
  chart.height = 400;
  chart.series = {{"a", kRed, {0.0, 1.0}, {0.0, 0.0}}};
  const auto inkRightAndLeft = [&](double at, const std::string& label) {
    chart.cursor_x = at;
    chart.cursor_label = label;
    const Image image = drawChart(chart);
    const Plot plot = findPlot(image);
    const int x = plot.left + static_cast<int>(std::lround(at * plot.width()));
    return std::pair{countDark(image, x + 3, plot.top + 2, x + 120, plot.top + 24),
                     countDark(image, x - 120, plot.top + 2, x - 3, plot.top + 24)};
  };
  const auto [right, left] = inkRightAndLeft(0.5, "t = 0.50 s");
  EXPECT_GT(right, 30);
  EXPECT_EQ(left, 0);
  const auto [right_edge, left_edge] = inkRightAndLeft(0.98, "t = 0.98 s");
  EXPECT_EQ(right_edge, 0);
  EXPECT_GT(left_edge, 30);
  const auto [none_right, none_left] = inkRightAndLeft(0.5, "");
  EXPECT_EQ(none_right + none_left, 0);
}

// A band from the plot's bottom to 1e-4 under data at 0.01 to 1: the log axis reaches down to
// show it, the plot is shaded up to its top and white above; notes under the x label take rows
// from the plot's height and are written there.
TEST(Chart, ABandIsShadedAndTheAxisShowsItAndNotesGoUnderTheAxis) {
  ChartSpec chart;
  chart.width = 800;
  chart.height = 400;
  chart.log_x = chart.log_y = true;
  chart.series = {{"a", kRed, {1.0, 10.0}, {1.0, 0.01}, SeriesStyle::kMarkers}};
  const Plot plain = findPlot(drawChart(chart));
  chart.bands = {{0.0, 1e-4, "", kBlue}};
  chart.notes = {"first note", "second note"};
  const Image image = drawChart(chart);
  const Plot plot = findPlot(image);
  EXPECT_LT(plot.height(), plain.height() - 20) << "two note rows";
  EXPECT_GT(countDark(image, 0, plot.bottom + 40, 200, image.height), 20) << "the notes";
  // The y axis spans 1e-4 .. 1 padded: the band's top at 4 of 4 decades plus padding.
  const double decades = 4.0, pad = kLogPad * decades;
  const int band_top = static_cast<int>(std::lround(plot.bottom - pad / (decades + 2 * pad) * plot.height()));
  const int x = (plot.left + 2 * plot.right) / 3;  // away from the data's markers
  const std::uint8_t* inside = pixel(image, x, (band_top + plot.bottom) / 2);
  EXPECT_LT(inside[0], 245) << "shaded";
  EXPECT_GT(inside[2], inside[0]) << "in the band's colour";
  EXPECT_TRUE(isWhite(image, x, band_top - 8)) << "white above the band";
}

}  // namespace
}  // namespace gf::render

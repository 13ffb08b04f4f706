#include "app/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "app/scene_file.hpp"
#include "render/chart.hpp"
#include "render/render_thread.hpp"

namespace gf::app {
namespace {

// Colours of successive curves (linear RGB): distinct on white and for the common colour
// blindnesses (Okabe and Ito's qualitative set).
const Eigen::Vector3f kCurveColours[] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f},
                                         {0.80f, 0.47f, 0.65f}, {0.34f, 0.71f, 0.91f}, {0.90f, 0.62f, 0.00f},
                                         {0.20f, 0.20f, 0.20f}};

std::vector<std::string> splitRow(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t a = 0;
  for (;;) {
    const std::size_t b = line.find(',', a);
    cells.push_back(line.substr(a, b == std::string::npos ? std::string::npos : b - a));
    if (b == std::string::npos) break;
    a = b + 1;
  }
  if (!cells.empty() && !cells.back().empty() && cells.back().back() == '\r') cells.back().pop_back();
  return cells;
}

}  // namespace

std::string writePlot(const PlotOptions& o) {
  if (std::filesystem::is_directory(o.csv)) throw InputError(o.csv, 0, 0, "file", "is a folder; give a CSV file");
  std::ifstream in(o.csv);
  if (!in) throw InputError(o.csv, 0, 0, "file", "cannot read");
  std::string line;
  if (!std::getline(in, line)) throw InputError(o.csv, 1, 0, "header", "empty file: expected a header row");
  const std::vector<std::string> header = splitRow(line);
  const auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    std::string names;
    for (const std::string& h : header) names.append(names.empty() ? "" : ", ").append(h);
    throw InputError(o.csv, 1, 0, name, "no such column (the file has: " + names + ")");
  };
  const std::size_t xc = column(o.x);
  std::vector<std::size_t> yc;
  for (const std::string& y : o.y) yc.push_back(column(y));
  std::vector<double> xs;
  std::vector<std::vector<double>> ys(yc.size());
  const auto number = [&](const std::vector<std::string>& cells, std::size_t c, int row) {
    if (c >= cells.size() || cells[c].empty()) return std::numeric_limits<double>::quiet_NaN();  // a gap
    char* end = nullptr;
    const double v = std::strtod(cells[c].c_str(), &end);
    if (end == cells[c].c_str() || *end != '\0') {
      throw InputError(o.csv, row, static_cast<int>(c) + 1, header[c], "expected a number, got '" + cells[c] + "'");
    }
    return v;
  };
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitRow(line);
    xs.push_back(number(cells, xc, row));
    for (std::size_t k = 0; k < yc.size(); ++k) ys[k].push_back(number(cells, yc[k], row));
  }
  render::ChartSpec chart;
  chart.width = o.width;
  chart.height = o.height;
  chart.x_label = o.x == "t" ? "time (s)" : o.x;
  chart.y_label = o.y.size() == 1 ? o.y.front() : "";
  std::string joined;
  for (const std::string& y : o.y) joined.append(joined.empty() ? "" : ", ").append(y);
  chart.title = o.title.empty() ? std::filesystem::path(o.csv).filename().string() + ": " + joined : o.title;
  for (std::size_t k = 0; k < yc.size(); ++k) {
    chart.series.push_back({o.y[k], kCurveColours[k % std::size(kCurveColours)], xs, ys[k]});
  }
  const std::string out =
      o.out.empty() ? (std::filesystem::path(o.csv).parent_path() / "plot.png").string() : o.out;
  const std::filesystem::path folder = std::filesystem::path(out).parent_path();
  std::error_code ec;
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);
  if (ec) throw std::runtime_error(folder.string() + ": cannot create folder: " + ec.message());
  render::writeChartPng(chart, out);
  return out;
}

}  // namespace gf::app

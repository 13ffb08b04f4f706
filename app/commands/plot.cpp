#include "app/commands/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "app/scene/scene_file.hpp"
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

std::vector<std::vector<double>> readCsvColumns(const std::string& path, const std::vector<std::string>& names) {
  if (std::filesystem::is_directory(path)) throw InputError(path, 0, 0, "file", "is a folder; give a CSV file");
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, 0, "file", "cannot read");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path, 1, 0, "header", "empty file: expected a header row");
  const std::vector<std::string> header = splitRow(line);
  const auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return i;
    }
    std::string known;
    for (const std::string& h : header) known.append(known.empty() ? "" : ", ").append(h);
    throw InputError(path, 1, 0, name, "no such column (the file has: " + known + ")");
  };
  std::vector<std::size_t> columns;
  for (const std::string& n : names) columns.push_back(column(n));
  std::vector<std::vector<double>> out(columns.size());
  const auto number = [&](const std::vector<std::string>& cells, std::size_t c, int row) {
    if (c >= cells.size() || cells[c].empty()) return std::numeric_limits<double>::quiet_NaN();  // a gap
    char* end = nullptr;
    const double v = std::strtod(cells[c].c_str(), &end);
    if (end == cells[c].c_str() || *end != '\0') {
      throw InputError(path, row, static_cast<int>(c) + 1, header[c], "expected a number, got '" + cells[c] + "'");
    }
    return v;
  };
  for (int row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = splitRow(line);
    for (std::size_t k = 0; k < columns.size(); ++k) out[k].push_back(number(cells, columns[k], row));
  }
  return out;
}

std::string writePlot(const PlotOptions& o) {
  std::vector<std::string> names = {o.x};
  names.insert(names.end(), o.y.begin(), o.y.end());
  std::vector<std::vector<double>> columns = readCsvColumns(o.csv, names);
  const std::vector<double>& xs = columns.front();
  const std::vector<std::vector<double>> ys(columns.begin() + 1, columns.end());
  render::ChartSpec chart;
  chart.width = o.width;
  chart.height = o.height;
  chart.x_label = o.x == "t" ? "time (s)" : o.x;
  chart.y_label = o.y.size() == 1 ? o.y.front() : "";
  std::string joined;
  for (const std::string& y : o.y) joined.append(joined.empty() ? "" : ", ").append(y);
  chart.title = o.title.empty() ? std::filesystem::path(o.csv).filename().string() + ": " + joined : o.title;
  for (std::size_t k = 0; k < ys.size(); ++k) {
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

#include "app/commands/plot.hpp"

#include <cstdio>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "app/commands/commands.hpp"
#include "app/runs/run_reader.hpp"
#include "render/chart/chart.hpp"
#include "render/render_thread.hpp"

namespace gf::app {
namespace {

// Colours of successive curves (linear RGB): distinct on white and for the common colour
// blindnesses (Okabe and Ito's qualitative set).
const Eigen::Vector3f kCurveColours[] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f},
                                         {0.80f, 0.47f, 0.65f}, {0.34f, 0.71f, 0.91f}, {0.90f, 0.62f, 0.00f},
                                         {0.20f, 0.20f, 0.20f}};

}  // namespace

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

namespace {

class PlotCommand final : public Command {
 public:
  CLI::App* add(CLI::App& app) override {
    PlotOptions& o = options_;
    CLI::App* p = app.add_subcommand("plot", "Draw columns of a CSV (trace.csv, forces.csv) against time as a PNG");
    p->add_option("csv", o.csv, "The CSV file (a header row, then numbers)")->required();
    p->add_option("--y", o.y, "A column to draw (repeat for more curves)")->required();
    p->add_option("--x", o.x, "The column along the x axis (default: t)");
    p->add_option("--out", o.out, "PNG file (default: plot.png beside the CSV)");
    p->add_option("--title", o.title, "Chart title (default: the file and the columns)");
    p->add_option("--width", o.width, "Pixels (default 1200)")->check(CLI::Range(200, 4000));
    p->add_option("--height", o.height, "Pixels (default 600)")->check(CLI::Range(150, 4000));
    return p;
  }

  int run() override {
    std::printf("wrote %s\n", writePlot(options_).c_str());
    return 0;
  }

 private:
  PlotOptions options_;
};

}  // namespace

std::unique_ptr<Command> makePlotCommand(const std::vector<std::string>&) { return std::make_unique<PlotCommand>(); }

}  // namespace gf::app

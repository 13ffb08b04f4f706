#include "app/commands/plot.hpp"

#include <cstdio>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>

#include "app/commands/commands.hpp"
#include "app/runs/run_reader.hpp"
#include "render/chart/chart.hpp"
#include "render/render_thread.hpp"

namespace gf::app {
namespace {

constexpr float kMarkerSpacingPx = 90.0f;  // markers along each curve, this far apart in x

// The unit of a trace.csv or forces.csv column, from its name's suffix (TraceWriter's columns);
// "" when the name does not tell.
std::string columnUnit(const std::string& name) {
  if (name == "t") return "s";
  const std::string suffix = name.substr(name.rfind('.') == std::string::npos ? name.size() : name.rfind('.') + 1);
  if (suffix.ends_with("overlap_mm2")) return "mm^2";
  if (suffix == "port_energy") return "J";
  if (suffix == "n_sgo") return "SGOs";
  if (suffix == "r" || (suffix.size() == 2 && (suffix[0] == 'p' || suffix[0] == 'd') && suffix[1] >= 'x' && suffix[1] <= 'z')) {
    return "m";
  }
  if ((suffix.size() == 2 && suffix[0] == 'q') || (suffix.size() == 3 && suffix.starts_with("dq"))) {
    return "dimensionless";  // a quaternion's component
  }
  if (suffix == "fx" || suffix == "fy" || suffix == "fz" || suffix.starts_with("sent_f")) return "N";
  if (suffix == "vx" || suffix == "vy" || suffix == "vz") return "m/s";
  if (suffix == "wx" || suffix == "wy" || suffix == "wz") return "rad/s";
  return "";
}

// An axis label for columns: "index.fx, index.fy, N" when they share a unit; else each with its
// own ("index.fx, N; ball.px, m").
std::string columnsLabel(const std::vector<std::string>& names) {
  std::string joined, each;
  bool same = true;
  for (const std::string& n : names) {
    same = same && columnUnit(n) == columnUnit(names.front());
    joined.append(joined.empty() ? "" : ", ").append(n);
    each.append(each.empty() ? "" : "; ").append(n).append(columnUnit(n).empty() ? "" : ", " + columnUnit(n));
  }
  if (!same) return each;
  return columnUnit(names.front()).empty() ? joined : joined + ", " + columnUnit(names.front());
}

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
  chart.x_label = o.x == "t" ? "time, s" : columnsLabel({o.x});
  chart.y_label = columnsLabel(o.y);
  std::string joined;
  for (const std::string& y : o.y) joined.append(joined.empty() ? "" : ", ").append(y);
  chart.title = o.title.empty() ? std::filesystem::path(o.csv).filename().string() + ": " + joined : o.title;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const render::SeriesLook look = render::seriesLook(k);
    render::ChartSeries s{o.y[k], look.colour, xs, ys[k]};
    s.dash = look.dash;
    s.marker = look.marker;
    if (ys.size() > 1) {  // markers along each curve tell them apart where they cross
      s.marker_spacing_px = kMarkerSpacingPx;
      s.marker_phase = static_cast<float>(k) / static_cast<float>(ys.size());
    }
    chart.series.push_back(std::move(s));
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

// `godfinger plot`: trace columns against time (or any column), with the project's chart code.
#pragma once

#include <string>
#include <vector>

namespace gf::app {

struct PlotOptions {
  std::string csv;             ///< a trace.csv, forces.csv or results.csv: a header row, then numbers
  std::vector<std::string> y;  ///< columns to draw, one curve each
  std::string x = "t";         ///< the column along the x axis
  std::string out;             ///< PNG path (default: the CSV's folder / plot.png)
  std::string title;           ///< default: the CSV's name and the columns
  int width = 1200, height = 600;
};

/// Reads the columns from the CSV and writes the chart. Throws InputError naming the file, line
/// and column for a missing column or a cell that is not a number (empty cells are gaps), and
/// std::runtime_error when the PNG cannot be written. Returns the PNG's path.
std::string writePlot(const PlotOptions& options);

}  // namespace gf::app

// The work-precision chart of a study's collected results (study_run.cpp collects them): |error|
// against cost per series, labels on each series' best points, notes saying what the labels and
// series names abbreviate, and the reference run's own noise as a shaded band where it is known.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "app/study/study.hpp"
#include "app/study/study_measure.hpp"
#include "render/chart/chart.hpp"

namespace gf::app {

/// One row of results.csv: a run, its configuration as it ran, its measures and its cost.
struct StudyRow {
  const StudyRun* run = nullptr;
  std::string series, model, patch, solver = "points";
  int n_sgo = 0, rings = 0, iterations = 0, walk_resolution = 0;
  double rate = 0.0;
  std::vector<MeasureResult> measures;
  double step_median = NAN, step_p99 = NAN, patch_mean = NAN;
  std::string status = "ok";
  double cost(CostKind k) const { return k == CostKind::kStep ? step_median : patch_mean; }
  double error() const { return measures.empty() ? NAN : measures.front().error; }
};

/// The unit an absolute error of `m` is in (" deg", " N", ...; "" for a relative one).
const char* errorUnit(const StudyMeasure& m);

/// The unit of a measure of `kind`, with a leading space (" N m"; "" for a ratio).
const char* measureUnit(MeasureKind kind);

/// How a reference is named in reports and legends ("(2/3) mu F r", "the reference run").
std::string referenceName(ReferenceKind k);

/// The charts' colour for series `i` (linear RGB: Okabe–Ito's, render::seriesLook()).
Eigen::Vector3f seriesColour(std::size_t i);

/// The cost: "median step time" or "mean patch time per call" (in us).
std::string costName(CostKind k);

/// The cost axis' label, with its unit ("median step time, us").
std::string costLabel(CostKind k);

/// A study axis' label on a chart, with its unit where its name tells it: "pad angle, deg" for
/// pad_angle_deg, "haptic rate, Hz", "n_SGO, SGOs per patch"; else the name.
std::string axisLabel(const std::string& axis);

/// The press behind the first row's analytic reference of measure `k`, as a sentence ("The press:
/// F = 4.42 N (...), r = 7.49 mm (...), mu = 1."), ranges where runs differ; "" when none.
std::string pressText(const std::vector<StudyRow>& rows, std::size_t k);

/// How many rows have a value of measure `k` (status ok, finite): a chart's "N of M runs".
int measuredRuns(const std::vector<StudyRow>& rows, std::size_t k = 0);

/// The stamp of a chart of `rows` when some lack measure `k`: "88 of 104 runs measured (16
/// missing, failed or without a value: see report.md)"; "" when none lacks it.
std::string runsStamp(const std::vector<StudyRow>& rows, std::size_t k = 0);

/// The study's chart (a scored study asking the cost question): a marker series per study series (its best points, each 1 % better than
/// any cheaper one, labelled with every axis that varies within it, e.g. "n8 it20 2kHz") and a
/// line through its best points, notes
/// for the abbreviations used, and a band up to the reference run's own value where the
/// measure is one a perfect run makes zero (swing, force s.d.) and its reference is a run. A
/// relative error (or a trajectory's deviation) is drawn in percent. Each series has its own
/// colour, marker and dash (render::seriesLook()); point labels are in its colour.
render::ChartSpec workPrecisionChart(const StudyPlan& plan, const std::vector<StudyRow>& rows);

/// A chart of a measure's value against a study axis (StudyDesc::chart_axes) and where it goes.
struct AxisChart {
  std::string file;  ///< "MEASURE-vs-AXIS.png"
  render::ChartSpec chart;
};

/// For each charted axis and each measure of the first series: the measure's value against the
/// axis' value, a line with markers per series (and per combination of the other axes that vary
/// within it), and the first series' reference as a dotted grey line (named a comparison, with
/// the press it was formed from in a note, when the study is not scored). A trajectory's chart
/// shows its deviation in percent on a log axis, without a reference line. The x axis is
/// logarithmic when its values are positive and span a factor 8 or more (haptic rates). Rows
/// without the measure are left out, and the chart's stamp says so.
std::vector<AxisChart> axisCharts(const StudyPlan& plan, const std::vector<StudyRow>& rows);

}  // namespace gf::app

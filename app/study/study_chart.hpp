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

/// The charts' colour for series `i` (linear RGB; twelve, then again).
Eigen::Vector3f seriesColour(std::size_t i);

/// The cost axis' label.
std::string costLabel(CostKind k);

/// The study's chart: a marker series per study series (its best points, each 1 % better than
/// any cheaper one, labelled with every axis that varies within it, e.g. "n8 it20 2kHz") and a
/// line through its best points, notes
/// for the abbreviations used, and a band up to the reference run's own value where the
/// measure is one a perfect run makes zero (swing, force s.d.) and its reference is a run.
render::ChartSpec workPrecisionChart(const StudyPlan& plan, const std::vector<StudyRow>& rows);

/// A chart of a measure's value against a study axis (StudyDesc::chart_axes) and where it goes.
struct AxisChart {
  std::string file;  ///< "MEASURE-vs-AXIS.png"
  render::ChartSpec chart;
};

/// For each charted axis and each measure of the first series: the measure's value against the
/// axis' value, a line with markers per series (and per combination of the other axes that vary
/// within it), and the first series' reference as a dotted grey line. Rows without the measure
/// are left out.
std::vector<AxisChart> axisCharts(const StudyPlan& plan, const std::vector<StudyRow>& rows);

}  // namespace gf::app

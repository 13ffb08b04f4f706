#include "app/study/study_chart.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <utility>

namespace gf::app {
namespace {

using Row = StudyRow;

// The unit of a measure's value, with a leading space ("" for a ratio).
const char* valueUnit(MeasureKind kind) {
  switch (kind) {
    case MeasureKind::kSwing: return " deg";
    case MeasureKind::kForceSd:
    case MeasureKind::kFrictionForce: return " N";
    case MeasureKind::kTipMoment:
    case MeasureKind::kFrictionTorque: return " N m";
    case MeasureKind::kGeodesicRadius:
    case MeasureKind::kTrajectory: return " m";
    case MeasureKind::kRollRatio: return "";
  }
  return "";
}

}  // namespace

const char* errorUnit(const StudyMeasure& m) { return m.error != ErrorKind::kAbsolute ? "" : valueUnit(m.kind); }

const char* measureUnit(MeasureKind kind) { return valueUnit(kind); }

namespace {

constexpr double kFrontGain = 0.99;  // a best point lowers the series' best |error| so far by 1 % or more

// Rows of one series on the chart's cost axis, cheapest first.
std::vector<const Row*> chartable(const std::vector<Row>& rows, const std::string& series, CostKind cost) {
  std::vector<const Row*> out;
  for (const Row& r : rows) {
    if (r.series == series && r.status == "ok" && r.cost(cost) > 0.0 && std::isfinite(r.error())) out.push_back(&r);
  }
  std::sort(out.begin(), out.end(), [&](const Row* a, const Row* b) { return a->cost(cost) < b->cost(cost); });
  return out;
}

// The axes whose value differs between the runs of `series`: what tells its points apart.
std::vector<std::string> varyingAxes(const std::vector<Row>& rows, const std::string& series) {
  std::map<std::string, std::set<std::string>> values;
  std::vector<std::string> order;
  for (const Row& r : rows) {
    if (r.series != series) continue;
    for (const auto& [field, value] : r.run->axis_values) {
      if (values[field].empty()) order.push_back(field);
      values[field].insert(value);
    }
  }
  std::vector<std::string> out;
  for (const std::string& f : order) {
    if (values[f].size() > 1) out.push_back(f);
  }
  return out;
}

// One axis value in a point's label: "n8" for n_SGO 8, "it10" for 10 solver iterations, "2kHz"
// for a haptic rate of 2000 Hz, "res4" for walk resolution 4, "45deg" for an angle (a name ending
// in _deg, e.g. pad_angle_deg); else the field's last name = value.
std::string labelToken(const std::string& field, const std::string& value) {
  const std::string name = field.substr(field.rfind('.') + 1);
  if (name == "n_sgo") return "n" + value;
  if (name == "solver_iterations") return "it" + value;
  if (name == "walk_resolution") return "res" + value;
  if (name.size() > 4 && name.ends_with("_deg")) return value + "deg";
  if (name == "haptic_rate") {
    const double hz = std::atof(value.c_str());
    if (hz >= 1000.0 && std::fmod(hz, 1000.0) == 0.0) return std::to_string(std::lround(hz / 1000.0)) + "kHz";
    return value + "Hz";
  }
  return name + "=" + value;
}

// A chart point's label: every axis that varies within its series (two runs of a series never
// share a label), e.g. "n8 it20 2kHz".
std::string pointLabel(const Row& r, const std::vector<std::string>& varying) {
  std::string out;
  for (const auto& [field, value] : r.run->axis_values) {
    if (std::find(varying.begin(), varying.end(), field) == varying.end()) continue;
    out.append(out.empty() ? "" : " ").append(labelToken(field, value));
  }
  return out;
}

// Whether a point label of `chart` holds a token that starts with `prefix` and then a digit
// ("n8"), or (digit_first) a number and then `prefix` ("2kHz").
bool labelsUse(const render::ChartSpec& chart, const std::string& prefix, bool digit_first) {
  for (const render::ChartSeries& s : chart.series) {
    for (const std::string& label : s.point_labels) {
      for (std::size_t a = 0; a < label.size();) {
        const std::size_t b = std::min(label.find(' ', a), label.size());
        const std::string token = label.substr(a, b - a);
        a = b + 1;
        if (token.size() <= prefix.size()) continue;
        const bool hit = digit_first ? token.compare(token.size() - prefix.size(), prefix.size(), prefix) == 0 &&
                                           std::isdigit(static_cast<unsigned char>(token.front()))
                                     : token.rfind(prefix, 0) == 0 &&
                                           std::isdigit(static_cast<unsigned char>(token[prefix.size()]));
        if (hit) return true;
      }
    }
  }
  return false;
}

// What the chart's labels and series names abbreviate, as notes under it: only what it shows.
std::vector<std::string> labelNotes(const render::ChartSpec& chart) {
  std::string keys;
  const auto key = [&](bool used, const char* meaning) {
    if (used) keys.append(keys.empty() ? "" : "; ").append(meaning);
  };
  key(labelsUse(chart, "n", false), "n = n_SGO, SGOs per patch");
  key(labelsUse(chart, "it", false), "it = solver iterations");
  key(labelsUse(chart, "kHz", true) || labelsUse(chart, "Hz", true), "kHz = haptic rate");
  key(labelsUse(chart, "res", false), "res = walk resolution");
  std::vector<std::string> notes;
  if (!keys.empty()) {
    notes.push_back("Point labels (" + keys + ") on each series' best points, the ones its line joins, each 1 % "
                    "better than any cheaper; every point is in report.md and results.csv.");
  }
  for (const render::ChartSeries& s : chart.series) {
    if (s.label.find("aggregate") == std::string::npos) continue;
    notes.push_back("\"aggregate\": the patch's SGOs solved as one block per contact (world.contact_solver = "
                    "aggregate); the others solve each SGO as a point of its own.");
    break;
  }
  return notes;
}

// The reference run's own noise, where the study knows it: a swing or force s.d. is zero for a
// perfectly held body, so the converged reference's own value is what is left of its
// discretisation, and an absolute error below it is within the reference's own error. Returns
// the largest such value over the reference runs (NaN when there is none: an analytic
// reference, or another measure).
double referenceNoise(const StudyMeasure& m, const std::vector<Row>& rows) {
  const bool zero_ideal = m.kind == MeasureKind::kSwing || m.kind == MeasureKind::kForceSd;
  if (!zero_ideal || m.reference != ReferenceKind::kRun || m.error != ErrorKind::kAbsolute) return NAN;
  double noise = NAN;
  for (const Row& r : rows) {
    if (r.run->series >= 0 || r.status != "ok" || r.measures.empty()) continue;
    const double x = std::abs(r.measures.front().measure);
    if (std::isfinite(x) && !(x <= noise)) noise = x;
  }
  return noise;
}

// "4.42" or "4.41 to 4.43" (of `scale` times the values), "" without values.
std::string spanText(std::vector<double> v, double scale) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return "";
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  char a[32], b[32];
  std::snprintf(a, sizeof a, "%.3g", scale * *lo);
  std::snprintf(b, sizeof b, "%.3g", scale * *hi);
  return std::string(a) == b ? a : std::string(a) + " to " + b;
}

}  // namespace

Eigen::Vector3f seriesColour(std::size_t i) { return render::seriesLook(i).colour; }

std::string costName(CostKind k) { return k == CostKind::kStep ? "median step time" : "mean patch time per call"; }

std::string costLabel(CostKind k) { return costName(k) + ", us"; }

std::string axisLabel(const std::string& axis) {
  const std::string name = axis.substr(axis.rfind('.') + 1);
  const auto words = [](std::string t) {
    std::replace(t.begin(), t.end(), '_', ' ');
    return t;
  };
  if (name.size() > 4 && name.ends_with("_deg")) return words(name.substr(0, name.size() - 4)) + ", deg";
  if (name == "haptic_rate" || name == "haptic_rate_hz") return "haptic rate, Hz";
  if (name == "n_sgo") return "n_SGO, SGOs per patch";
  if (name == "solver_iterations") return "solver iterations, per step";
  if (name == "walk_resolution") return "walk resolution, subdivisions";
  for (const auto& [suffix, unit] : {std::pair{"_mm", "mm"}, {"_m", "m"}, {"_s", "s"}, {"_n", "N"}, {"_hz", "Hz"}}) {
    const std::string tail = suffix;
    if (name.size() > tail.size() && name.ends_with(tail)) return words(name.substr(0, name.size() - tail.size())) + ", " + unit;
  }
  return words(name);
}

int measuredRuns(const std::vector<Row>& rows, std::size_t k) {
  return static_cast<int>(std::count_if(rows.begin(), rows.end(), [&](const Row& r) {
    return r.status == "ok" && r.measures.size() > k && std::isfinite(r.measures[k].measure);
  }));
}

std::string pressText(const std::vector<Row>& rows, std::size_t k) {
  std::vector<double> f, r, mu;
  for (const Row& row : rows) {
    if (row.status != "ok" || row.measures.size() <= k) continue;
    f.push_back(row.measures[k].press_force_n);
    r.push_back(row.measures[k].press_radius_m);
    mu.push_back(row.measures[k].friction);
  }
  const std::string force = spanText(f, 1.0), radius = spanText(r, 1000.0), friction = spanText(mu, 1.0);
  if (force.empty()) return "";
  std::string out = "The press the comparison values are formed from: F = " + force +
                    " N (the finger's measured press)";
  if (!radius.empty()) out += ", r = " + radius + " mm (the Eq. 1 radius of that press; a soft pad's own)";
  if (!friction.empty()) out += ", mu = " + friction + " (the pad's friction)";
  return out + "; over the runs measured.\n";
}

std::string runsStamp(const std::vector<Row>& rows, std::size_t k) {
  const int n = measuredRuns(rows, k), m = static_cast<int>(rows.size());
  if (n == m) return "";
  return std::to_string(n) + " of " + std::to_string(m) + " runs measured (" + std::to_string(m - n) +
         " missing, failed or without a value: see report.md)";
}

// A relative error or a deviation is drawn in percent; an absolute one in its measure's unit.
double errorScale(const StudyMeasure& m) { return m.error == ErrorKind::kAbsolute ? 1.0 : 100.0; }

// The work-precision chart's y label: the error as formed, with its unit.
std::string errorLabel(const StudyPlan& plan) {
  const StudyMeasure& m = plan.study.series.front().measures.front();
  for (const StudySeries& s : plan.study.series) {
    if (s.measures.front().error != m.error || s.measures.front().kind != m.kind) {
      return "|error|, each series in its own measure's unit (see report.md)";
    }
  }
  if (m.error == ErrorKind::kRelative) return "|error| = |" + m.name + " / reference - 1|, %";
  if (m.error == ErrorKind::kDeviation) return "RMS deviation from the reference path, % of its RMS displacement";
  const char* unit = errorUnit(m);
  return "|error| = |" + m.name + " - reference|, " + (*unit ? std::string(unit + 1) : std::string("dimensionless"));
}

render::ChartSpec workPrecisionChart(const StudyPlan& plan, const std::vector<Row>& rows) {
  const StudyMeasure& m = plan.study.series.front().measures.front();
  const double scale = errorScale(m);
  render::ChartSpec chart;
  chart.title = plan.study.name + ": error against cost (one line per series through its best points)";
  chart.x_label = costLabel(plan.study.cost);
  chart.y_label = errorLabel(plan);
  chart.stamp = runsStamp(rows);
  chart.log_x = chart.log_y = true;
  chart.width = 1280;
  chart.height = 720;

  std::size_t colour = 0;
  for (const StudySeries& s : plan.study.series) {
    const std::vector<const Row*> points = chartable(rows, s.name, plan.study.cost);
    if (points.empty()) continue;
    const render::SeriesLook look = render::seriesLook(colour++);
    render::ChartSeries markers{s.name, look.colour, {}, {}};
    markers.style = render::SeriesStyle::kMarkers;
    markers.marker = look.marker;
    markers.dash = look.dash;  // the legend shows the front's line too
    markers.legend_line = true;
    render::ChartSeries front{"", look.colour, {}, {}};
    front.dash = look.dash;
    const std::vector<std::string> varying = varyingAxes(rows, s.name);
    double best = HUGE_VAL;
    for (const Row* r : points) {
      markers.x.push_back(r->cost(plan.study.cost));
      markers.y.push_back(scale * std::abs(r->error()));
      // The best error at this cost or less, by a margin: a point 0.01 % better than a cheaper one
      // is the same accuracy, and labelling it would crowd the labels that matter.
      const bool on_front = std::abs(r->error()) < kFrontGain * best;
      markers.point_labels.push_back(on_front ? pointLabel(*r, varying) : "");
      if (on_front) {
        best = std::abs(r->error());
        front.x.push_back(r->cost(plan.study.cost));
        front.y.push_back(scale * best);
      }
    }
    // |error| 0 has no place on a log axis: say how many points that leaves out.
    int zeros = 0;
    for (const Row* r : points) zeros += r->error() == 0.0;
    if (zeros > 0) markers.label += " (" + std::to_string(zeros) + " at error 0, not drawn)";
    chart.series.push_back(std::move(front));
    chart.series.push_back(std::move(markers));
  }
  chart.notes = labelNotes(chart);
  const double noise = referenceNoise(m, rows);
  if (std::isfinite(noise) && noise > 0.0) {
    char b[200];
    std::snprintf(b, sizeof b, "the reference run's own %s, %.2g%s: an error below it is within the reference's noise",
                  m.name.c_str(), noise, errorUnit(m));
    chart.bands.push_back({0.0, noise, b, Eigen::Vector3f(0.55f, 0.55f, 0.6f)});
  }
  return chart;
}

namespace {

const char* referenceText(ReferenceKind k) {
  switch (k) {
    case ReferenceKind::kRun: return "the reference run";
    case ReferenceKind::kTwoThirdsMuFR: return "(2/3) mu F r";
    case ReferenceKind::kMuFR: return "mu F r";
    case ReferenceKind::kHertzMuFR: return "(3 pi / 16) mu F r";
    case ReferenceKind::kThinLayerMuFR: return "(8 / 15) mu F r";
    case ReferenceKind::kMuF: return "mu F";
    case ReferenceKind::kRollingPrediction: return "the rolling prediction";
    case ReferenceKind::kPatchRadius: return "the Eq. 1 radius";
    case ReferenceKind::kFR: return "F r";
    case ReferenceKind::kValue: return "the given value";
  }
  return "";
}

// Puts a line's points in the order of their x.
void sortByX(render::ChartSeries& line) {
  std::vector<std::size_t> order(line.x.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return line.x[a] < line.x[b]; });
  const std::vector<double> x = line.x, y = line.y;
  for (std::size_t i = 0; i < order.size(); ++i) {
    line.x[i] = x[order[i]];
    line.y[i] = y[order[i]];
  }
}

// The line key of a row on a chart against `axis`: its series and the other axes varying in it.
std::string lineKey(const Row& r, const std::vector<std::string>& varying, const std::string& axis) {
  std::vector<std::string> others;
  for (const std::string& f : varying) {
    if (f != axis) others.push_back(f);
  }
  const std::string label = pointLabel(r, others);
  return label.empty() ? r.series : r.series + " " + label;
}

double axisNumber(const Row& r, const std::string& axis) {
  for (const auto& [field, value] : r.run->axis_values) {
    if (field == axis) return std::strtod(value.c_str(), nullptr);
  }
  return NAN;
}

// The value a chart against an axis draws of a row's measure: a trajectory's deviation in
// percent of the reference path's displacement, else the measure in its unit.
double chartedValue(const StudyMeasure& m, const MeasureResult& x) {
  return m.kind == MeasureKind::kTrajectory ? 100.0 * x.error : x.measure;
}

// The first series' reference against the axis, dotted grey: "reference: ..." for a scored
// study, "comparison: ..." for one that is not. None for a trajectory (its value is a distance
// from its reference).
void addReferenceLine(render::ChartSpec& chart, const StudyPlan& plan, const std::vector<Row>& rows, std::size_t k,
                      const std::string& axis) {
  const StudyMeasure& m = plan.study.series.front().measures[k];
  if (m.kind == MeasureKind::kTrajectory) return;
  const std::string first = plan.study.series.front().name;
  render::ChartSeries reference{std::string(plan.study.scored ? "reference: " : "comparison, a flat pad: ") +
                                    referenceName(m.reference) + " (" + first + "'s runs)",
                                Eigen::Vector3f(0.3f, 0.3f, 0.3f), {}, {}};
  reference.dash = render::LineDash::kDotted;
  for (const Row& r : rows) {
    if (r.series != first || r.measures.size() <= k || !std::isfinite(r.measures[k].reference)) continue;
    reference.x.push_back(axisNumber(r, axis));
    reference.y.push_back(r.measures[k].reference);
  }
  if (!reference.x.empty()) chart.series.push_back(std::move(reference));
}

// Log axes where the values call for them: x when its values are positive and span a factor 8
// or more (rates that double), y for a trajectory's deviation (decades apart).
void chooseScales(render::ChartSpec& chart, const StudyMeasure& m) {
  double lo = HUGE_VAL, hi = 0.0;
  for (const render::ChartSeries& s : chart.series) {
    for (double x : s.x) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  chart.log_x = lo > 0.0 && hi >= 8.0 * lo;
  chart.log_y = m.kind == MeasureKind::kTrajectory;
}

render::ChartSpec measureAgainstAxis(const StudyPlan& plan, const std::vector<Row>& rows, std::size_t k,
                                     const std::string& axis) {
  const StudyMeasure& m = plan.study.series.front().measures[k];
  render::ChartSpec chart;
  chart.title = plan.study.name + ": " + m.name + " against " + axis;
  chart.x_label = axisLabel(axis);
  chart.y_label = m.kind == MeasureKind::kTrajectory
                      ? m.name + ": RMS deviation from the reference path, % of its RMS displacement"
                      : m.name + ", " + (*valueUnit(m.kind) ? std::string(valueUnit(m.kind) + 1) : "dimensionless");
  chart.stamp = runsStamp(rows, k);
  chart.width = 1280;
  chart.height = 720;
  std::map<std::string, std::size_t> line_of;
  for (const StudySeries& s : plan.study.series) {
    const std::vector<std::string> varying = varyingAxes(rows, s.name);
    for (const Row& r : rows) {
      if (r.series != s.name || r.measures.size() <= k || !std::isfinite(r.measures[k].measure)) continue;
      const std::string key = lineKey(r, varying, axis);
      if (!line_of.count(key)) {
        const std::size_t i = chart.series.size();
        line_of[key] = i;
        const render::SeriesLook look = render::seriesLook(i);
        render::ChartSeries line{key, look.colour, {}, {}};
        line.style = render::SeriesStyle::kLineAndMarkers;
        line.marker = look.marker;
        line.dash = look.dash;
        chart.series.push_back(std::move(line));
      }
      render::ChartSeries& line = chart.series[line_of[key]];
      line.x.push_back(axisNumber(r, axis));
      line.y.push_back(chartedValue(m, r.measures[k]));
    }
  }
  addReferenceLine(chart, plan, rows, k, axis);
  for (render::ChartSeries& line : chart.series) sortByX(line);
  chooseScales(chart, m);
  if (const std::string press = pressText(rows, k); !press.empty()) chart.notes.push_back(press);
  return chart;
}

}  // namespace

std::string referenceName(ReferenceKind k) { return referenceText(k); }

std::vector<AxisChart> axisCharts(const StudyPlan& plan, const std::vector<Row>& rows) {
  std::vector<AxisChart> out;
  for (const std::string& axis : plan.study.chart_axes) {
    const std::vector<StudyMeasure>& measures = plan.study.series.front().measures;
    for (std::size_t k = 0; k < measures.size(); ++k) {
      out.push_back({measures[k].name + "-vs-" + axis + ".png", measureAgainstAxis(plan, rows, k, axis)});
    }
  }
  return out;
}

}  // namespace gf::app

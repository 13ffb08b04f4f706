#include "app/study/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gf::app {
namespace {

using Row = StudyRow;

std::string errorText(const StudyMeasure& m, double e) {
  char b[48];
  if (!std::isfinite(e)) return "n/a";
  if (m.error == ErrorKind::kAbsolute) std::snprintf(b, sizeof b, "%.3g%s", e, errorUnit(m));
  else std::snprintf(b, sizeof b, "%+.2f %%", 100.0 * e);
  return b;
}

std::string configurationText(const Row& r) {
  std::string s = r.series;
  for (const auto& [field, value] : r.run->axis_values) s += ", " + field.substr(field.rfind('.') + 1) + " " + value;
  return s;
}

// True when a further measure is not the first one's quantity against another reference
// (another kind, body, finger, axis or window): the report then shows its value too.
bool otherQuantity(const StudyMeasure& a, const StudyMeasure& b) {
  return a.kind != b.kind || a.body != b.body || a.finger != b.finger || a.axis != b.axis || a.from != b.from ||
         a.to != b.to;
}

// Why some measures have no value (a roll ratio of a body at rest), one line each.
std::string notesMd(const StudyPlan& plan, const std::vector<Row>& rows) {
  std::string out;
  for (const Row& r : rows) {
    const std::vector<StudyMeasure>& own = measuresOf(plan, *r.run);
    for (std::size_t k = 0; k < r.measures.size() && k < own.size(); ++k) {
      if (r.measures[k].note.empty()) continue;
      out += "- " + configurationText(r) + ", `" + own[k].name + "`: " + r.measures[k].note + "\n";
    }
  }
  return out.empty() ? out : "\nNo value:\n\n" + out;
}

// The opening: summary, study file, runs (and how many were measured), how times were taken.
std::string headMd(const StudyPlan& plan, const std::vector<Row>& rows, bool parallel_times) {
  const StudyDesc& study = plan.study;
  std::string out = "# Study `" + study.name + "`\n\n" + study.summary + "\n\n";
  out += "Study file: `" + study.source + "`. " + std::to_string(rows.size()) + " runs" +
         (plan.quick ? " (the --quick grid)" : "") + ". ";
  const int measured = measuredRuns(rows);
  if (measured < static_cast<int>(rows.size())) {
    out += "**" + std::to_string(measured) + " of " + std::to_string(rows.size()) +
           " runs measured**: the others are marked by their status in the tables. ";
  }
  for (const std::string& e : plan.extra) out += "`--set " + e + "` ";
  out += parallel_times ? "Step times were taken with several runs at once on one machine (or a run does not say "
                          "when and where it ran): they include contention for the cores; use `--jobs 1` for "
                          "published figures.\n\n"
                        : "Step times were taken one run at a time on each machine.\n\n";
  return out;
}

// The runs' table of a scored study: each measure, its reference and its error.
std::string scoredTableMd(const StudyPlan& plan, const std::vector<Row>& rows) {
  const std::vector<StudyMeasure>& measures = plan.study.series.front().measures;
  const StudyMeasure& m = measures.front();
  std::string out = "Error: ";
  out += m.error == ErrorKind::kRelative    ? "measure / reference - 1.\n\n"
         : m.error == ErrorKind::kAbsolute  ? "measure - reference, in the measure's unit.\n\n"
                                            : "RMS deviation from the reference path / its RMS displacement.\n\n";
  bool same_measure = true;
  for (const StudySeries& s : plan.study.series) same_measure = same_measure && s.measures.front().name == m.name;
  out += "| configuration | " + (same_measure ? m.name : std::string("measure (its series')")) + " | reference | error |";
  for (std::size_t k = 1; k < measures.size(); ++k) {
    out += (otherQuantity(measures[k], m) ? " " + measures[k].name + " |" : "") + " " + measures[k].name + " error |";
  }
  out += " step us (median) | step us (p99) | patch us |\n|---|---|---|---|";
  for (std::size_t k = 1; k < measures.size(); ++k) out += otherQuantity(measures[k], m) ? "---|---|" : "---|";
  out += "---|---|---|\n";
  char b[160];
  for (const Row& r : rows) {
    const MeasureResult x = r.measures.empty() ? MeasureResult{} : r.measures.front();
    const std::vector<StudyMeasure>& own = measuresOf(plan, *r.run);  // a series may measure otherwise
    std::snprintf(b, sizeof b, " | %.5g | %.5g | %s |", x.measure, x.reference, errorText(own.front(), x.error).c_str());
    out.append("| ").append(configurationText(r));
    if (r.status != "ok") out.append(" (").append(r.status).append(")");
    out += b;
    for (std::size_t k = 1; k < measures.size(); ++k) {
      const StudyMeasure& mk = k < own.size() ? own[k] : measures[k];
      const MeasureResult xk = k < r.measures.size() ? r.measures[k] : MeasureResult{};
      if (otherQuantity(measures[k], m)) {
        std::snprintf(b, sizeof b, " %.5g |", xk.measure);
        out += b;
      }
      out.append(1, ' ').append(errorText(mk, xk.error)).append(" |");
    }
    std::snprintf(b, sizeof b, " %.1f | %.1f | %.2f |\n", r.step_median, r.step_p99, r.patch_mean);
    out += b;
  }
  return out;
}

// The most accurate run within each budget: the answer to a cost question.
std::string budgetMd(const StudyPlan& plan, const std::vector<Row>& rows) {
  const StudyDesc& study = plan.study;
  const StudyMeasure& m = study.series.front().measures.front();
  std::string out = "\n## The most accurate configuration per budget\n\n";
  out += "Budget on the " + costLabel(study.cost) + "; reference runs left out, and runs measured otherwise than " +
         "the first series (`" + m.name + "`).\n\n| budget (us) | configuration | error | cost (us) |\n|---|---|---|---|\n";
  char b[200];
  for (double budget : {10.0, 20.0, 50.0, 100.0}) {
    const Row* best = nullptr;
    for (const Row& r : rows) {
      if (r.run->series < 0 || r.status != "ok" || !std::isfinite(r.error()) || !(r.cost(study.cost) <= budget)) continue;
      const StudyMeasure& own = measuresOf(plan, *r.run).front();
      if (own.kind != m.kind || own.error != m.error || own.reference != m.reference) continue;  // not comparable
      if (!best || std::abs(r.error()) < std::abs(best->error())) best = &r;
    }
    if (best) {
      std::snprintf(b, sizeof b, "| %.0f | %s | %s | %.1f |\n", budget, configurationText(*best).c_str(),
                    errorText(m, best->error()).c_str(), best->cost(study.cost));
    } else {
      std::snprintf(b, sizeof b, "| %.0f | none fits | | |\n", budget);
    }
    out += b;
  }
  return out;
}

std::string axisValueOf(const Row& r, const std::string& axis) {
  for (const auto& [field, value] : r.run->axis_values) {
    if (field == axis) return value;
  }
  return "";
}

// "0.02229", or "0.02229 / 0.0223" when runs of one cell differ in other axes; "n/a" for none.
std::string cellText(const std::vector<double>& values) {
  if (values.empty()) return "n/a";
  std::string out;
  char b[32];
  for (double v : values) {
    std::snprintf(b, sizeof b, "%.4g", v);
    out.append(out.empty() ? "" : " / ").append(std::isfinite(v) ? b : "n/a");
  }
  return out;
}

// Measure k of an unscored study against `axis`: a row per axis value, a column per series, and
// the comparison value (of the first series' runs) last.
std::string effectTableMd(const StudyPlan& plan, const std::vector<Row>& rows, std::size_t k, const std::string& axis) {
  const StudyMeasure& m = plan.study.series.front().measures[k];
  const std::string unit = measureUnit(m.kind);
  std::string out = "\n## " + m.name + (unit.empty() ? "" : "," + unit) + ", against " + axis + "\n\n| " + axis + " |";
  for (const StudySeries& s : plan.study.series) out += " " + s.name + " |";
  out += " " + referenceName(m.reference) + " (" + plan.study.series.front().name + ") |\n|---|";
  for (std::size_t i = 0; i <= plan.study.series.size(); ++i) out += "---|";
  out += "\n";
  std::vector<std::string> values;  // the axis' values in the order the runs have them
  for (const Row& r : rows) {
    const std::string v = axisValueOf(r, axis);
    if (!v.empty() && std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
  }
  for (const std::string& v : values) {
    out += "| " + v + " |";
    std::vector<double> comparison;
    for (const StudySeries& s : plan.study.series) {
      std::vector<double> cell;
      for (const Row& r : rows) {
        if (r.series != s.name || axisValueOf(r, axis) != v || r.status != "ok" || r.measures.size() <= k) continue;
        cell.push_back(r.measures[k].measure);
        if (&s == &plan.study.series.front()) comparison.push_back(r.measures[k].reference);
      }
      out += " " + cellText(cell) + " |";
    }
    out += " " + cellText(comparison) + " |\n";
  }
  return out + "\n" + pressText(rows, k) + "\n";
}

// The runs' table of an unscored study: each measure's value, no reference, no error.
std::string valuesTableMd(const StudyPlan& plan, const std::vector<Row>& rows) {
  const std::vector<StudyMeasure>& measures = plan.study.series.front().measures;
  std::string out = "\n## Every run\n\n| configuration |";
  for (const StudyMeasure& m : measures) out += " " + m.name + (*measureUnit(m.kind) ? "," : "") + measureUnit(m.kind) + " |";
  out += " step us (median) | step us (p99) | patch us |\n|---|";
  for (std::size_t k = 0; k < measures.size(); ++k) out += "---|";
  out += "---|---|---|\n";
  char b[96];
  for (const Row& r : rows) {
    out += "| " + configurationText(r) + (r.status != "ok" ? " (" + r.status + ")" : "") + " |";
    for (std::size_t k = 0; k < measures.size(); ++k) {
      std::snprintf(b, sizeof b, " %.5g |", k < r.measures.size() ? r.measures[k].measure : NAN);
      out += b;
    }
    std::snprintf(b, sizeof b, " %.1f | %.1f | %.2f |\n", r.step_median, r.step_p99, r.patch_mean);
    out += b;
  }
  return out;
}

// What an unscored study's references are, and the tables against each charted axis.
std::string unscoredMd(const StudyPlan& plan, const std::vector<Row>& rows) {
  std::string out =
      "The study is not scored (`scored = false`): its references are comparison values, the limits of a flat "
      "pad pressed as each run pressed, which the configurations may differ from by design. The tables give "
      "each measure's value.\n";
  const std::vector<StudyMeasure>& measures = plan.study.series.front().measures;
  for (const std::string& axis : plan.study.chart_axes) {
    for (std::size_t k = 0; k < measures.size(); ++k) out += effectTableMd(plan, rows, k, axis);
  }
  return out + valuesTableMd(plan, rows);
}

// The charts an effect question is answered by.
std::string effectChartsMd(const StudyPlan& plan) {
  std::string out = "\nThe study asks how its measures change along ";
  std::string files;
  for (const std::string& axis : plan.study.chart_axes) {
    out += (&axis == &plan.study.chart_axes.front() ? "`" : ", `") + axis + "`";
    for (const StudyMeasure& m : plan.study.series.front().measures) files += " `" + m.name + "-vs-" + axis + ".png`";
  }
  return out + " (`question = \"effect\"`): see" + files + ".\n";
}

}  // namespace

const std::vector<StudyMeasure>& measuresOf(const StudyPlan& plan, const StudyRun& run) {
  return plan.study.series[static_cast<std::size_t>(run.measured_as)].measures;
}

std::string reportMd(const StudyPlan& plan, const std::vector<Row>& rows, bool parallel_times) {
  const StudyDesc& study = plan.study;
  std::string out = headMd(plan, rows, parallel_times);
  out += study.scored ? scoredTableMd(plan, rows) : unscoredMd(plan, rows);
  out += notesMd(plan, rows);
  if (study.question == StudyQuestion::kEffect) out += effectChartsMd(plan);
  if (study.scored && study.question == StudyQuestion::kCost) out += budgetMd(plan, rows);
  return out;
}

}  // namespace gf::app

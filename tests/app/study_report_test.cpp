// What a study says follows its question: `scored` and `question` in the study file (checked
// where they stand), the report's wording (no "error" nor "budget" for an unscored study, the
// press stated), the charts' units, the haptic rate on the timestep study's x axis, and the
// "N of M runs" stamp when runs are missing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/scene/input_error.hpp"
#include "app/study/study.hpp"
#include "app/study/study_chart.hpp"
#include "app/study/study_report.hpp"
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

fs::path studyFileIn(const std::string& name, const std::string& text) {
  const fs::path dir = gf::test::scratchRoot() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path p = dir / "study.toml";
  std::ofstream(p) << "scene = \"" << GF_SOURCE_DIR << "/assets/scenes/pressed-puck.toml\"\n" << text;
  return p;
}

// A charted pad angle (0 and 30 deg), a torsion limit against (2/3) mu F r, two series.
const std::string kTiltedStudy = R"(
[[axes]]
field = "fingers.index.device.tilt_deg"
name = "pad_angle_deg"
chart = true
values = [0, 30]
[[measures]]
name = "torsion_limit"
kind = "friction_torque"
body = "puck"
window = [0.7, 1.0]
reference = "two_thirds_mu_f_r"
[[series]]
name = "a"
[[series]]
name = "b"
)";

// Rows of `plan`: torsion 0.02 - 1e-4 angle (b 0.001 less), pressed with 4.4 N over 7.5 mm at
// mu 1; the last row missing when `missing`.
std::vector<StudyRow> tiltedRows(const StudyPlan& plan, bool missing) {
  std::vector<StudyRow> rows(plan.runs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].run = &plan.runs[i];
    rows[i].series = plan.study.series[static_cast<std::size_t>(plan.runs[i].series)].name;
    const double angle = std::atof(plan.runs[i].axis_values.at(0).second.c_str());
    MeasureResult x{0.02 - 1e-4 * angle - (rows[i].series == "b" ? 0.001 : 0.0), 0.022, 0.0, ""};
    x.error = x.measure / x.reference - 1.0;
    x.press_force_n = 4.4;
    x.press_radius_m = 0.0075;
    x.friction = 1.0;
    rows[i].measures = {x};
    rows[i].step_median = 10.0 + static_cast<double>(i);
  }
  if (missing) {
    rows.back().status = "missing";
    rows.back().measures.clear();
  }
  return rows;
}

StudyPlan tiltedPlan(const std::string& name, const std::string& head) {
  return expandStudy(loadStudyFile(studyFileIn(name, head + kTiltedStudy).string()), false, {});
}

// Wrong `scored` and `question` values, and ones that do not fit together or with the study, are
// refused with file, line, column and field.
TEST(StudyFile, ScoredAndQuestionAreCheckedWhereTheyStand) {
  struct Case {
    std::string head, expected;
  };
  const Case cases[] = {
      {"scored = \"no\"\n", ":2:10: scored: expected true or false, got a string"},
      {"question = \"why\"\n", ":2:12: question: "},
      {"scored = false\n", ":2:10: scored: a cost question ranks runs by their error"},
      {"scored = false\nquestion = \"cost\"\n", ":3:12: question: a cost question ranks runs by their error"},
  };
  for (const Case& c : cases) {
    const fs::path study = studyFileIn("gf_study_question_bad", c.head + kTiltedStudy);
    try {
      loadStudyFile(study.string());
      ADD_FAILURE() << "accepted:\n" << c.head;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(study.string() + c.expected, 0), 0u) << e.what();
    }
  }
  // An effect is shown against a charted axis.
  const fs::path no_axis = studyFileIn("gf_study_question_bad",
                                      "question = \"effect\"\n[[measures]]\nkind = \"friction_torque\"\nbody = \"puck\"\n"
                                      "reference = \"mu_f_r\"\n[[series]]\nname = \"a\"\n");
  EXPECT_THROW(
      {
        try {
          loadStudyFile(no_axis.string());
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find(":2:12: question: \"effect\" is shown against an axis"), std::string::npos)
              << e.what();
          throw;
        }
      },
      InputError);
  // The bundled studies say what they ask.
  const StudyDesc orientation = loadStudyFile("orientation"), timestep = loadStudyFile("timestep");
  EXPECT_FALSE(orientation.scored);
  EXPECT_EQ(orientation.question, StudyQuestion::kEffect);
  EXPECT_TRUE(timestep.scored);
  EXPECT_EQ(timestep.question, StudyQuestion::kEffect);
  EXPECT_EQ(timestep.chart_axes, std::vector<std::string>{"haptic_rate"});
  EXPECT_EQ(loadStudyFile("torsion").question, StudyQuestion::kCost);
}

// An unscored study's report gives each limit against the pad angle beside the comparison value
// and the press it was formed from; it never speaks of an error or a budget. A scored cost study's
// report keeps both.
TEST(StudyReport, AnUnscoredStudyShowsValuesAndThePressNotErrors) {
  const StudyPlan plan = tiltedPlan("gf_study_unscored", "scored = false\nquestion = \"effect\"\n");
  const std::string md = reportMd(plan, tiltedRows(plan, false), false);
  std::string lower = md;
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  EXPECT_EQ(lower.find("error"), std::string::npos) << md;
  EXPECT_EQ(lower.find("budget"), std::string::npos) << md;
  EXPECT_NE(md.find("## torsion_limit, N m, against pad_angle_deg"), std::string::npos) << md;
  EXPECT_NE(md.find("| pad_angle_deg | a | b | (2/3) mu F r (a) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 30 | 0.017 | 0.016 | 0.022 |"), std::string::npos) << md;
  EXPECT_NE(md.find("F = 4.4 N"), std::string::npos) << md;
  EXPECT_NE(md.find("r = 7.5 mm"), std::string::npos) << md;
  EXPECT_NE(md.find("mu = 1 "), std::string::npos) << md;
  EXPECT_NE(md.find("torsion_limit-vs-pad_angle_deg.png"), std::string::npos) << md;

  const StudyPlan scored = tiltedPlan("gf_study_scored", "");
  const std::string cost = reportMd(scored, tiltedRows(scored, false), false);
  EXPECT_NE(cost.find("| error |"), std::string::npos) << cost;
  EXPECT_NE(cost.find("most accurate configuration per budget"), std::string::npos) << cost;
  const StudyPlan effect = tiltedPlan("gf_study_scored_effect", "question = \"effect\"\n");
  const std::string effect_md = reportMd(effect, tiltedRows(effect, false), false);
  EXPECT_NE(effect_md.find("| error |"), std::string::npos) << effect_md;
  EXPECT_EQ(effect_md.find("budget"), std::string::npos) << effect_md;
}

// Every chart of a study with a missing run says "N of M runs"; the report too. The charts'
// axes carry units: the cost in us, a relative error in percent (its values too), the pad angle
// in degrees, the limit in N m; an unscored study's reference line is a comparison, its press in
// a note.
TEST(StudyChart, MissingRunsAreStampedAndEveryAxisHasItsUnit) {
  const StudyPlan plan = tiltedPlan("gf_study_stamp", "");
  const std::vector<StudyRow> whole = tiltedRows(plan, false), missing = tiltedRows(plan, true);
  EXPECT_EQ(workPrecisionChart(plan, whole).stamp, "");
  const render::ChartSpec wp = workPrecisionChart(plan, missing);
  EXPECT_EQ(wp.stamp.rfind("3 of 4 runs measured (1 missing", 0), 0u) << wp.stamp;
  EXPECT_EQ(wp.x_label, "median step time, us");
  EXPECT_EQ(wp.y_label, "|error| = |torsion_limit / reference - 1|, %");
  ASSERT_FALSE(wp.series.empty());
  EXPECT_NEAR(wp.series[1].y.front(), 100.0 * std::abs(0.02 / 0.022 - 1.0), 1e-9);  // a's cheapest
  EXPECT_NE(reportMd(plan, missing, false).find("**3 of 4 runs measured**"), std::string::npos);

  const std::vector<AxisChart> charts = axisCharts(plan, missing);
  ASSERT_EQ(charts.size(), 1u);
  EXPECT_EQ(charts[0].chart.stamp.rfind("3 of 4 runs measured", 0), 0u);
  EXPECT_EQ(charts[0].chart.x_label, "pad angle, deg");
  EXPECT_EQ(charts[0].chart.y_label, "torsion_limit, N m");
  EXPECT_FALSE(charts[0].chart.log_x) << "0 and 30 deg: a linear axis";

  const StudyPlan unscored = tiltedPlan("gf_study_stamp_unscored", "scored = false\nquestion = \"effect\"\n");
  const render::ChartSpec against = axisCharts(unscored, tiltedRows(unscored, false))[0].chart;
  EXPECT_EQ(against.series.back().label, "comparison, a flat pad: (2/3) mu F r (a's runs)");
  ASSERT_EQ(against.notes.size(), 1u);
  EXPECT_NE(against.notes[0].find("F = 4.4 N"), std::string::npos) << against.notes[0];
}

// The timestep study's error is charted against the haptic rate, on log axes (the rates double),
// without a reference line (a trajectory's value is its distance from the reference run).
TEST(StudyChart, TheTimestepStudyChartsItsErrorAgainstTheHapticRate) {
  const StudyPlan plan = expandStudy(loadStudyFile("timestep"), false, {});
  std::vector<StudyRow> rows(plan.runs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const StudyRun& run = plan.runs[i];
    rows[i].run = &run;
    rows[i].series = run.series < 0 ? "reference" : plan.study.series[static_cast<std::size_t>(run.series)].name;
    const double rate = run.axis_values.empty() ? 10000.0 : std::atof(run.axis_values[0].second.c_str());
    rows[i].measures = {{1e-3 * 250.0 / rate, 1e-2, 0.1 * 250.0 / rate, ""}};
  }
  const std::vector<AxisChart> charts = axisCharts(plan, rows);
  ASSERT_EQ(charts.size(), 1u);
  const render::ChartSpec& chart = charts[0].chart;
  EXPECT_EQ(charts[0].file, "path_rms_m-vs-haptic_rate.png");
  EXPECT_EQ(chart.x_label, "haptic rate, Hz");
  EXPECT_TRUE(chart.log_x);
  EXPECT_TRUE(chart.log_y);
  ASSERT_EQ(chart.series.size(), 2u) << "a line per series, no reference line";
  EXPECT_EQ(chart.series[0].x, (std::vector<double>{250.0, 500.0, 1000.0, 2000.0}));
  EXPECT_NEAR(chart.series[0].y[0], 10.0, 1e-9);  // 0.1 of the displacement: 10 %
  EXPECT_NE(chart.y_label.find("%"), std::string::npos) << chart.y_label;
}

}  // namespace
}  // namespace gf::app

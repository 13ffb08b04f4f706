// Accuracy studies: the bundled studies' quick grids, the measures and references on hand-made
// run folders, the emit / GNU parallel / collect path, and malformed study files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <tuple>

#include "app/runs/run_reader.hpp"
#include "app/scene/scene_file.hpp"
#include "app/study/study.hpp"
#include "app/study/study_chart.hpp"
#include "app/study/study_measure.hpp"
#include "sim/patch/god_finger.hpp"
#include "tests/app/run_helpers.hpp"
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

using gf::app::test::readFile;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.push_back(cell), cell.clear();
    else cell += c;
  }
  out.push_back(cell);
  return out;
}

// results.csv as rows of named cells.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i) {
      if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
  }
};

Csv readCsv(const fs::path& p) {
  Csv csv;
  std::istringstream in(readFile(p));
  std::string line;
  std::getline(in, line);
  csv.header = split(line);
  while (std::getline(in, line)) csv.rows.push_back(split(line));
  return csv;
}

fs::path freshDir(const std::string& name) {
  const fs::path d = gf::test::scratchRoot() / name;
  fs::remove_all(d);
  return d;
}

std::string binary() { return std::string(GF_BINARY_DIR) + "/godfinger"; }

StudyOptions options(const fs::path& out, int jobs) {
  StudyOptions o;
  o.out = out.string();
  o.jobs = jobs;
  o.progress = false;
  o.godfinger = binary();
  return o;
}

class BundledStudy : public testing::TestWithParam<const char*> {};

// Every bundled study's quick grid runs, and results.csv has the issue's columns, one row per
// run, each measured with a finite error; the chart and the report are written.
TEST_P(BundledStudy, QuickGridRunsWithEveryColumnAndAFiniteError) {
  const fs::path out = freshDir(std::string("gf_study_quick_") + GetParam());
  const StudyPlan plan = expandStudy(loadStudyFile(GetParam()), true, {});
  ASSERT_EQ(runStudy(plan, options(out, 2)), 0);
  const Csv csv = readCsv(out / "results.csv");
  for (const char* c : {"study", "model", "patch", "n_sgo", "rings", "contact_solver", "solver_iterations", "haptic_rate_hz",
                        "walk_resolution", "measure", "reference", "error", "step_us_median", "step_us_p99"}) {
    EXPECT_GE(csv.column(c), 0) << "no column " << c;
  }
  ASSERT_EQ(csv.rows.size(), plan.runs.size());
  for (const std::vector<std::string>& row : csv.rows) {
    ASSERT_EQ(row.size(), csv.header.size());
    EXPECT_EQ(row[static_cast<std::size_t>(csv.column("status"))], "ok") << row.back();
    EXPECT_TRUE(std::isfinite(std::stod(row[static_cast<std::size_t>(csv.column("error"))]))) << row.back();
    EXPECT_GT(std::stod(row[static_cast<std::size_t>(csv.column("step_us_median"))]), 0.0) << row.back();
  }
  // A cost question: the work-precision chart (PNG and SVG) and the best run per budget; an effect:
  // a chart against each charted axis, no budget.
  const bool cost = plan.study.question == StudyQuestion::kCost;
  const std::string chart = cost ? "work-precision" : plan.study.series.front().measures.front().name + "-vs-" +
                                                          plan.study.chart_axes.front();
  EXPECT_GT(fs::file_size(out / (chart + ".png")), 1000u);
  EXPECT_NE(readFile(out / (chart + ".svg")).find("</svg>"), std::string::npos);
  EXPECT_EQ(readFile(out / "report.md").find("most accurate configuration per budget") != std::string::npos, cost);
}

INSTANTIATE_TEST_SUITE_P(Study, BundledStudy,
                         testing::Values("torsion", "sliding", "rolling", "pinch", "geodesic", "timestep", "effects", "soft-hand"),
                         [](const testing::TestParamInfo<const char*>& i) {
                           std::string name = i.param;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

// A hand-made run folder: a pressed puck (the pressed-puck scene) spinning up at a known angular
// acceleration while the finger presses with a known force, its proxy resting on the top face's
// centre (y = 0.048) until the puck slides away under it.
struct HandMadeRun {
  long steps = 1000;        // the scene's 1 s at 1 kHz: a complete run
  double inertia = 8e-4;    // kg m^2 about y
  double alpha = 25.0;      // rad/s^2 from the load's start (0.6 s)
  double press = 4.0;       // N
  double radius = 0.0075;   // m, the finger's patch
  double swing_deg = 0.0;   // rotation about x, growing linearly to this by 1 s
  double slide = 0.0;       // m/s^2: the puck's acceleration along x from 0.6 s
};

void writeRun(const fs::path& dir, const HandMadeRun& h) {
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << R"({"step_time_us": {"median": 10.0, "p99": 20.0}, "counters": {"steps": )"
                                      << h.steps << "}, "
                                      << R"("patch_time_us": {"mean": 1.0, "calls": 1}, )"
                                      << R"("bodies": [{"name": "puck", "mass_kg": 1.0, "inertia_kg_m2": [0.0005, )"
                                      << h.inertia << ", 0.0005]}]}\n";
  std::ofstream t(dir / "trace.csv");
  t << "t,puck.px,puck.py,puck.pz,puck.qx,puck.qy,puck.qz,puck.qw,index.fx,index.fy,index.fz,index.n_sgo,index.r,"
       "index.px,index.py,index.pz,index.dx,index.dy,index.dz,puck.vx,puck.vy,puck.vz,puck.wx,puck.wy,puck.wz\n";
  t.precision(17);
  for (int i = 0; i <= 1000; ++i) {
    const double time = i * 1e-3, after = std::max(0.0, time - 0.6), w = h.alpha * after;
    const double half = 0.5 * h.swing_deg * std::numbers::pi / 180.0 * time;
    t << time << "," << 0.5 * h.slide * after * after << ",0.02,0," << std::sin(half) << ",0,0," << std::cos(half)
      << ",0," << -h.press << ",0,8," << h.radius << ",0,0.048,0,0,0.04225,0," << h.slide * after << ",0,0,0," << w
      << ",0\n";
  }
}

fs::path writeStudy(const fs::path& dir, const std::string& text) {
  fs::create_directories(dir);
  const fs::path p = dir / "study.toml";
  std::ofstream(p) << "scene = \"" << GF_SOURCE_DIR << "/assets/scenes/pressed-puck.toml\"\n" << text;
  return p;
}

// The friction torque is the applied torque minus I alpha; the analytic references use the
// measured press F and the Eq. 1 radius of the press depth F / k; the error is measure /
// reference - 1.
TEST(StudyMeasure, FrictionTorqueAndItsAnalyticReferences) {
  const fs::path dir = freshDir("gf_study_measure");
  const fs::path study = writeStudy(dir, R"(
[[measures]]
kind = "friction_torque"
body = "puck"
window = [0.7, 1.0]
reference = "two_thirds_mu_f_r"
[[measures]]
name = "hertz"
kind = "friction_torque"
body = "puck"
window = [0.7, 1.0]
reference = "hertz_mu_f_r"
[[series]]
name = "only"
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.runs.size(), 1u);
  HandMadeRun h;
  writeRun(dir / "runs" / plan.runs[0].id, h);
  const RunOutputs run = readRunOutputs((dir / "runs" / plan.runs[0].id).string(), loadSceneFile(plan.runs[0].scene));
  const double measured = 0.04 - h.inertia * h.alpha;  // the scene's 0.04 N m from 0.6 s
  const double r = sim::contactRadius(h.press / 800.0, 0.010, 0.004);  // the scene's finger: k 800 N/m, defaults
  const MeasureResult a = evaluateMeasure(plan.study.series[0].measures[0], run, nullptr);
  EXPECT_NEAR(a.measure, measured, 1e-9);
  EXPECT_NEAR(a.reference, 2.0 / 3.0 * 1.0 * h.press * r, 1e-12);
  EXPECT_NEAR(a.error, measured / a.reference - 1.0, 1e-9);
  const MeasureResult b = evaluateMeasure(plan.study.series[0].measures[1], run, nullptr);
  EXPECT_NEAR(b.reference, 3.0 * std::numbers::pi / 16.0 * h.press * r, 1e-12);
  EXPECT_NEAR(measureError(ErrorKind::kAbsolute, 3.0, 1.0), 2.0, 0.0);
  EXPECT_NEAR(measureError(ErrorKind::kDeviation, 3.0, 1.5), 2.0, 0.0);
}

// A friction measure whose window runs on after the finger's contact has left the face it
// presses fails, naming the run, the measure and the time. The puck slides 0.5 a s^2 along x
// (s from 0.6 s) under a finger resting over its centre, unstretched (the device straight
// below the proxy): a patch of radius r reaches the edge (R = 0.04 m) when that is R - r, a
// point contact when it is R. A window that ends before is measured: the force is m a.
TEST(StudyMeasure, FrictionWindowPastTheContactLeavingTheFaceFails) {
  const fs::path dir = freshDir("gf_study_leaves");
  const fs::path study = writeStudy(dir, R"(
[[measures]]
name = "slip_force"
kind = "friction_force"
body = "puck"
window = [0.65, 0.9]
reference = "mu_f"
[[measures]]
name = "slip_torque"
kind = "friction_torque"
body = "puck"
window = [0.65, 0.9]
reference = "two_thirds_mu_f_r"
[[measures]]
name = "before"
kind = "friction_force"
body = "puck"
window = [0.65, 0.75]
reference = "mu_f"
[[series]]
name = "only"
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.runs.size(), 1u);
  const std::vector<StudyMeasure>& m = plan.study.series[0].measures;
  const fs::path run_dir = dir / "runs" / plan.runs[0].id;
  HandMadeRun h;
  h.slide = 2.5;  // m/s^2, m 1 kg
  // r 7.5 mm: 1.25 s^2 = 0.0325 at s = 0.16125 (row 0.762); a point: 0.04 at s = 0.17889 (row 0.779).
  for (const auto& [radius, time] : {std::pair{0.0075, "0.7620"}, std::pair{0.0, "0.7790"}}) {
    h.radius = radius;
    writeRun(run_dir, h);
    const RunOutputs run = readRunOutputs(run_dir.string(), loadSceneFile(plan.runs[0].scene));
    for (std::size_t k : {0u, 1u}) {
      try {
        evaluateMeasure(m[k], run, nullptr);
        ADD_FAILURE() << m[k].name << " measured past the edge, r = " << radius;
      } catch (const std::runtime_error& e) {
        const std::string expected = run_dir.string() + ": " + m[k].name +
                                     ": the finger's contact leaves the puck's face at t = " + time +
                                     " s, inside the window [0.65, 0.9]; end the window before it";
        EXPECT_EQ(e.what(), expected);
      }
    }
    EXPECT_NEAR(evaluateMeasure(m[2], run, nullptr).measure, 2.5, 1e-6) << "r = " << radius;
  }
  // Collected, the run is unmeasured and the study not whole.
  EXPECT_NE(collectStudy(plan, dir.string(), dir.string(), false), 0);
  const Csv csv = readCsv(dir / "results.csv");
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.rows[0][static_cast<std::size_t>(csv.column("status"))], "unmeasured");
}

// A hand-made Fig. 5 run (3 s): the ball goes `speed` along x from 0.5 s, turning about z as far
// as `roll` times rolling would.
void writeBallRun(const fs::path& dir, double speed, double roll) {
  fs::create_directories(dir);
  std::ofstream(dir / "summary.json") << R"({"step_time_us": {"median": 10.0, "p99": 20.0}, "counters": {"steps": 3000}, )"
                                      << R"("patch_time_us": {"mean": 1.0, "calls": 1}})" << "\n";
  std::ofstream t(dir / "trace.csv");
  t << "t,ball.px,ball.py,ball.pz,ball.qx,ball.qy,ball.qz,ball.qw\n";
  t.precision(17);
  for (int i = 0; i <= 1000; ++i) {
    const double time = i * 1e-3, x = speed * std::max(0.0, time - 0.5), half = -0.5 * roll * x / 0.03;
    t << time << "," << x << ",0.03,0,0,0," << std::sin(half) << "," << std::cos(half) << "\n";
  }
}

// A number is a reference of its own: the roll ratio after a push against 1. A ball that went
// less than 1 % of its radius has no roll ratio: NaN, with a note the report lists, and the run
// still counts as measured.
TEST(StudyMeasure, ANumberIsAReferenceAndABallAtRestHasNoRollRatio) {
  const fs::path dir = freshDir("gf_study_free_roll");
  const fs::path study = writeStudy(dir, R"(
[[measures]]
name = "free_roll_ratio"
kind = "roll_ratio"
body = "ball"
window = [0.5, 1.0]
reference = 1.0
[[series]]
name = "only"
scene = "fig5-push-ball"
axes = [{ field = "fingers.index.friction", values = [0.3, 1.1] }]
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.runs.size(), 2u);
  const StudyMeasure& m = plan.study.series[0].measures[0];
  EXPECT_EQ(m.reference, ReferenceKind::kValue);
  EXPECT_EQ(m.error, ErrorKind::kAbsolute) << "a roll ratio's error is absolute";
  writeBallRun(dir / "runs" / plan.runs[0].id, 0.05, 0.98);
  writeBallRun(dir / "runs" / plan.runs[1].id, 0.0002, 1.0);  // 0.1 mm in 0.5 s: at rest
  ASSERT_EQ(collectStudy(plan, dir.string(), dir.string(), false), 0);
  const Csv csv = readCsv(dir / "results.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  const auto cell = [&](std::size_t row, const char* c) {
    return csv.rows[row][static_cast<std::size_t>(csv.column(c))];
  };
  EXPECT_NEAR(std::stod(cell(0, "measure")), 0.98, 1e-9);
  EXPECT_EQ(std::stod(cell(0, "reference")), 1.0);
  EXPECT_NEAR(std::stod(cell(0, "error")), -0.02, 1e-9);
  EXPECT_EQ(cell(1, "measure"), "nan");
  EXPECT_EQ(cell(1, "status"), "ok");
  EXPECT_NE(readFile(dir / "report.md").find("- only, friction 1.1, `free_roll_ratio`: no roll ratio: the ball went 0.1 mm "
                                             "in the window [0.5, 1], less than 1 % of its radius (it rests)"),
            std::string::npos)
      << readFile(dir / "report.md");
}

// A measure against the reference run is looked up in the reference run's folder: collecting
// hand-made folders gives error = swing - reference swing (absolute, deg) for each run.
TEST(StudyMeasure, ReferenceRunIsLookedUpWhenCollecting) {
  const fs::path dir = freshDir("gf_study_collect");
  const fs::path study = writeStudy(dir, R"(
[[measures]]
name = "swing_deg"
kind = "swing"
body = "puck"
axis = [1.0, 0.0, 0.0]
[reference_run]
set = ["world.solver_iterations=50"]
[[series]]
name = "ring"
axes = [{ field = "fingers.index.n_sgo", values = [4, 8] }]
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.runs.size(), 3u);
  ASSERT_EQ(plan.runs[0].series, -1) << "the reference run comes first";
  const double swings[] = {1.0, 4.0, 2.5};
  for (std::size_t i = 0; i < 3; ++i) {
    HandMadeRun h;
    h.swing_deg = swings[i];
    writeRun(dir / "runs" / plan.runs[i].id, h);
  }
  ASSERT_EQ(collectStudy(plan, dir.string(), dir.string(), false), 0);
  const Csv csv = readCsv(dir / "results.csv");
  ASSERT_EQ(csv.rows.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto cell = [&](const char* c) { return std::stod(csv.rows[i][static_cast<std::size_t>(csv.column(c))]); };
    EXPECT_NEAR(cell("measure"), swings[i], 1e-9);
    EXPECT_NEAR(cell("reference"), swings[0], 1e-9);
    EXPECT_NEAR(cell("error"), swings[i] - swings[0], 1e-9);
  }
  EXPECT_EQ(csv.rows[1][static_cast<std::size_t>(csv.column("fingers.index.n_sgo"))], "4");
  EXPECT_EQ(csv.rows[2][static_cast<std::size_t>(csv.column("n_sgo"))], "8");
}

// A run that stopped early (its summary counts fewer steps than the scene's duration asks) is
// marked incomplete and not measured, and the collection says the study is not whole.
TEST(StudyMeasure, RunStoppedEarlyIsIncompleteNotMeasured) {
  const fs::path dir = freshDir("gf_study_incomplete");
  const fs::path study = writeStudy(dir, R"(
[[measures]]
kind = "friction_torque"
body = "puck"
window = [0.7, 1.0]
reference = "two_thirds_mu_f_r"
[[series]]
name = "only"
axes = [{ field = "fingers.index.n_sgo", values = [4, 8] }]
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.runs.size(), 2u);
  HandMadeRun h;
  writeRun(dir / "runs" / plan.runs[0].id, h);
  h.steps = 800;  // stopped at 0.8 s
  writeRun(dir / "runs" / plan.runs[1].id, h);
  EXPECT_NE(collectStudy(plan, dir.string(), dir.string(), false), 0);
  const Csv csv = readCsv(dir / "results.csv");
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0][static_cast<std::size_t>(csv.column("status"))], "ok");
  EXPECT_EQ(csv.rows[1][static_cast<std::size_t>(csv.column("status"))], "incomplete");
  EXPECT_EQ(csv.rows[1][static_cast<std::size_t>(csv.column("error"))], "nan");
}

// Emitting the command lines, running them with GNU parallel from another folder and collecting
// gives the same results as a direct run (all but the step and patch times).
// The pinch study's god-object runs differ in solver iterations and haptic rate: the chart
// labels each best point with both (two runs at 10 iterations are not both "it10"), leaves the
// other points unlabelled (report.md lists them), explains the abbreviations and "aggregate"
// under the chart, and shades the reference run's own swing as its noise floor.
TEST(StudyChart, LabelsTellPointsApartAndTheReferenceNoiseIsShaded) {
  StudyPlan plan;
  plan.study.name = "pinch";
  StudyMeasure swing;
  swing.name = "swing_deg";
  swing.kind = MeasureKind::kSwing;
  swing.reference = ReferenceKind::kRun;
  swing.error = ErrorKind::kAbsolute;
  for (const char* name : {"god_object", "god_finger ring aggregate"}) {
    StudySeries series;
    series.name = name;
    series.measures = {swing};
    series.has_reference_run = true;
    plan.study.series.push_back(series);
  }
  const double reference = 1.4e-5;  // deg: the converged run's own swing
  plan.runs.push_back({"000-reference", -1, "", {}, {}, -1, 0});
  // (iterations, rate, step us, swing deg): the cheapest is not the most accurate.
  const std::vector<std::tuple<const char*, const char*, double, double>> runs = {
      {"10", "1000", 7.0, 180.0}, {"20", "1000", 9.0, 170.0}, {"10", "2000", 11.0, 100.0}, {"20", "2000", 13.0, 175.0}};
  for (const auto& [it, rate, cost, value] : runs) {
    plan.runs.push_back({"god_object", 0, "", {}, {{"world.solver_iterations", it}, {"haptic_rate", rate}}, 0, 0});
  }
  plan.runs.push_back({"aggregate", 1, "", {}, {{"fingers.left.n_sgo", "8"}}, 0, 1});
  std::vector<StudyRow> rows(plan.runs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].run = &plan.runs[i];
    rows[i].series = i == 0 ? "reference" : i + 1 == rows.size() ? "god_finger ring aggregate" : "god_object";
    const double value = i == 0 ? reference : i + 1 == rows.size() ? 3e-4 : std::get<3>(runs[i - 1]);
    rows[i].step_median = i == 0 ? 90.0 : i + 1 == rows.size() ? 12.0 : std::get<2>(runs[i - 1]);
    rows[i].measures = {{value, reference, value - reference, ""}};
  }
  const render::ChartSpec chart = workPrecisionChart(plan, rows);
  std::vector<std::string> labels;
  for (const render::ChartSeries& s : chart.series) {
    if (s.label == "god_object") labels = s.point_labels;
  }
  // Cheapest first: 7, 9, 11, 13 us; the best so far at 7 (180), 9 (170) and 11 (100) us.
  EXPECT_EQ(labels, (std::vector<std::string>{"it10 1kHz", "it20 1kHz", "it10 2kHz", ""}));
  std::string notes;
  for (const std::string& n : chart.notes) notes += n + "\n";
  EXPECT_NE(notes.find("it = solver iterations"), std::string::npos) << notes;
  EXPECT_NE(notes.find("kHz = haptic rate"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("n = n_SGO"), std::string::npos) << "no label uses n: " << notes;
  EXPECT_NE(notes.find("aggregate"), std::string::npos) << notes;
  ASSERT_EQ(chart.bands.size(), 1u);
  EXPECT_DOUBLE_EQ(chart.bands[0].y_hi, reference);
  EXPECT_NE(chart.bands[0].label.find("1.4e-05 deg"), std::string::npos) << chart.bands[0].label;
  // An analytic reference has no run whose noise could be known: no band.
  for (StudySeries& s : plan.study.series) s.measures.front().reference = ReferenceKind::kTwoThirdsMuFR;
  EXPECT_TRUE(workPrecisionChart(plan, rows).bands.empty());
}

// An axis with `chart = true` charts every measure against its values: a line per series in the
// order of the axis (whatever order the runs came in), the first series' reference dotted.
TEST(StudyChart, AChartedAxisGivesEachMeasureAgainstIt) {
  const fs::path dir = freshDir("gf_study_axis_chart");
  const fs::path study = writeStudy(dir, R"(
[[axes]]
field = "fingers.index.device.tilt_deg"
name = "pad_angle_deg"
chart = true
values = [30, 0]
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
)");
  const StudyPlan plan = expandStudy(loadStudyFile(study.string()), false, {});
  ASSERT_EQ(plan.study.chart_axes, std::vector<std::string>{"pad_angle_deg"});
  ASSERT_EQ(plan.runs.size(), 4u);
  std::vector<StudyRow> rows(plan.runs.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].run = &plan.runs[i];
    rows[i].series = plan.study.series[static_cast<std::size_t>(plan.runs[i].series)].name;
    const double angle = std::atof(plan.runs[i].axis_values.at(0).second.c_str());
    rows[i].measures = {{0.02 - 1e-4 * angle - (rows[i].series == "b" ? 0.001 : 0.0), 0.022, 0.0, ""}};
  }
  const std::vector<AxisChart> charts = axisCharts(plan, rows);
  ASSERT_EQ(charts.size(), 1u);
  EXPECT_EQ(charts[0].file, "torsion_limit-vs-pad_angle_deg.png");
  EXPECT_EQ(charts[0].chart.x_label, "pad angle, deg");
  EXPECT_EQ(charts[0].chart.y_label, "torsion_limit, N m");
  ASSERT_EQ(charts[0].chart.series.size(), 3u);
  EXPECT_EQ(charts[0].chart.series[0].label, "a");
  EXPECT_EQ(charts[0].chart.series[0].x, (std::vector<double>{0.0, 30.0}));
  EXPECT_DOUBLE_EQ(charts[0].chart.series[0].y[1], 0.017);
  EXPECT_DOUBLE_EQ(charts[0].chart.series[1].y[0], 0.019);
  EXPECT_EQ(charts[0].chart.series[2].dash, render::LineDash::kDotted);
  EXPECT_EQ(charts[0].chart.series[2].y, (std::vector<double>{0.022, 0.022}));
}

TEST(StudyJobs, EmitParallelCollectMatchesADirectRun) {
  ASSERT_EQ(std::system("command -v parallel > /dev/null"), 0) << "GNU parallel is needed (scripts/test installs it)";
  const fs::path direct = freshDir("gf_study_direct"), emitted = freshDir("gf_study_emitted");
  const StudyPlan plan = expandStudy(loadStudyFile("torsion"), true, {});
  ASSERT_EQ(runStudy(plan, options(direct, 1)), 0);
  EXPECT_NE(readFile(direct / "report.md").find("taken one run at a time"), std::string::npos)
      << "runs one after another do not overlap";
  fs::create_directories(emitted);
  const fs::path jobs = emitted / "jobs.txt";
  emitStudyJobs(plan, options(emitted, 1), jobs.string());
  const std::string cmd = "cd / && parallel --will-cite -j 2 < " + jobs.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  ASSERT_EQ(collectStudy(plan, emitted.string(), emitted.string(), true), 0);
  const Csv a = readCsv(direct / "results.csv"), b = readCsv(emitted / "results.csv");
  ASSERT_EQ(a.header, b.header);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t r = 0; r < a.rows.size(); ++r) {
    for (std::size_t c = 0; c < a.header.size(); ++c) {
      if (a.header[c] == "step_us_median" || a.header[c] == "step_us_p99" || a.header[c] == "patch_us_mean") continue;
      EXPECT_EQ(a.rows[r][c], b.rows[r][c]) << a.header[c] << " of " << a.rows[r].back();
    }
  }
}

// A malformed study file is rejected with FILE:LINE:COLUMN: FIELD: reason before anything runs.
TEST(StudyFile, MalformedStudiesNameFileLineColumnAndField) {
  const fs::path dir = freshDir("gf_study_bad");
  const std::string measure = "[[measures]]\nkind = \"friction_torque\"\nbody = \"puck\"\nreference = \"mu_f_r\"\n";
  struct Case {
    std::string text, expected;
  };
  const Case cases[] = {
      {measure + "[[series]]\nname = \"a\"\naxes = [{ field = \"fingers.index.nsgo\", values = [4] }]\n",
       ":8:19: series.0.axes.0.field: 'fingers.index.nsgo=4': fingers.index.nsgo: unknown field"},
      {measure + "[[series]]\nname = \"a\"\naxes = [{ field = \"fingers.index.n_sgo\", values = [] }]\n",
       ":8:51: series.0.axes.0.values: empty"},
      {"[[measures]]\nkind = \"torque\"\nbody = \"puck\"\n[[series]]\nname = \"a\"\n",
       ":3:8: measures.0.kind: unknown value 'torque'"},
      {measure + "[[series]]\nname = \"a\"\naxes = [{ field = \"fingers.index.n_sgo\", values = [4, 99] }]\n",
       ":8:55: series.0.axes.0.values.1: 'fingers.index.n_sgo=99': fingers.index.n_sgo: must be"},
      {"[[measures]]\nkind = \"swing\"\nbody = \"puck\"\n[[series]]\nname = \"a\"\n",
       ":2:1: measures.0.reference: 'run' needs a [reference_run]"},
      {"[[measures]]\nkind = \"friction_force\"\nbody = \"ball\"\nreference = \"mu_f\"\n[[series]]\nname = \"a\"\n"
       "scene = \"fig5-push-ball\"\n",
       ":2:1: measures.0.body: must be a box or a cylinder"},
      {"[[measures]]\nkind = \"trajectory\"\nbody = \"puck\"\nreference = 0.5\n[[series]]\nname = \"a\"\n",
       ":5:13: measures.0.reference: a number is not a reference of trajectory"},
      {"[[axes]]\nfield = \"fingers.index.patch\"\nchart = true\nvalues = [\"ring\", \"filled\"]\n[[measures]]\n"
       "kind = \"friction_torque\"\nbody = \"puck\"\n[[series]]\nname = \"a\"\n",
       ":4:9: axes.0.chart: a charted axis needs numbers as values, got 'ring'"},
      {"[[measures]]\nkind = \"friction_torque\"\nbody = \"puck\"\n[[series]]\nname = \"a\"\n"
       "axes = [{ field = \"fingers.index.n_sgo\", values = [4], chart = true }]\n",
       ":7:8: series.0.axes: chart: only an axis of the whole study ([[axes]]) is charted"},
  };
  for (const Case& c : cases) {
    const fs::path study = writeStudy(dir, c.text);
    try {
      expandStudy(loadStudyFile(study.string()), false, {});
      ADD_FAILURE() << "accepted:\n" << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(study.string() + c.expected, 0), 0u) << e.what();
    }
  }
  // From the command line: a non-zero exit and no output folder.
  const fs::path out = dir / "out";
  const std::string cmd = binary() + " study " + (dir / "study.toml").string() + " --out " + out.string() + " 2>/dev/null";
  EXPECT_NE(std::system(cmd.c_str()), 0);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace gf::app

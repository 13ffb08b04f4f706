// Running a study's configurations as `godfinger run` processes, and collecting their folders
// into results.csv, work-precision.png and report.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>

#include "app/runs/files.hpp"
#include "app/runs/jobs.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/scene_file.hpp"
#include "app/study/study.hpp"
#include "app/study/study_chart.hpp"
#include "app/study/study_measure.hpp"
#include "app/study/study_report.hpp"
#include "app/study/study_resume.hpp"
#include "render/render_thread.hpp"
#include "sim/scene/effective_settings.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using Row = StudyRow;

std::string number(double x) {
  if (!std::isfinite(x)) return "nan";
  std::string s;
  appendNumber(s, x);
  return s;
}

std::string csvCell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

const sim::Setting<sim::FingerDesc>& fingerSetting(std::string_view name) {
  return *sim::findSetting(sim::fingerSettings(), name);
}

// The configuration's columns from its scene, as it ran.
void describe(const StudyPlan& plan, const StudyRun& run, const SessionDesc& s, Row& row) {
  const StudyMeasure& m = plan.study.series[static_cast<std::size_t>(run.measured_as)].measures.front();
  const sim::SceneDesc& scene = s.scene;
  row.run = &run;
  row.series = run.series < 0 ? "reference" : plan.study.series[static_cast<std::size_t>(run.series)].name;
  if (run.series < 0) {  // whose reference: one series', or the n-th of several shared ones
    int references = 0, index = 0;
    for (const StudyRun& other : plan.runs) {
      if (other.series < 0) ++references;
      if (&other == &run) index = references;
    }
    const std::set<int> series_using = [&] {
      std::set<int> out;
      for (const StudyRun& other : plan.runs) {
        if (other.series >= 0 && other.reference >= 0 && plan.runs[static_cast<std::size_t>(other.reference)].id == run.id) {
          out.insert(other.series);
        }
      }
      return out;
    }();
    if (series_using.size() == 1) {
      row.series.append(" (").append(plan.study.series[static_cast<std::size_t>(*series_using.begin())].name).append(")");
    } else if (references > 1) {
      row.series.append(" ").append(std::to_string(index));
    }
  }
  const sim::FingerDesc* f = nullptr;
  for (const sim::FingerDesc& x : scene.fingers) {
    if (!f && (m.finger.empty() || x.name == m.finger)) f = &x;
  }
  if (f) {
    // The model the World runs (sim::effectiveSettings: n_sgo 0 or the god_finger effect off make
    // a god-finger a god-object) and its solver.
    const sim::EffectiveSettings e = sim::effectiveSettings(f->patch, scene.effects, scene.world.contact_solver);
    sim::FingerDesc effective = *f;
    effective.patch = e.patch;
    row.model = sim::choiceName(fingerSetting("contact_model"), effective);
    row.patch = row.model == "god_finger" ? std::string(sim::choiceName(fingerSetting("patch"), *f)) : "";
    row.n_sgo = row.model == "god_finger" ? f->patch.n_sgo : 0;
    row.rings = row.patch == "filled" ? f->patch.rings : 0;
    // A god-object or soft finger is one point whatever the solver setting.
    if (row.model == "god_finger" && e.solver == sim::ContactSolver::kAggregate) row.solver = "aggregate";
  }
  row.iterations = scene.world.solver_iterations;
  row.rate = scene.world.haptic_rate_hz;
  for (const sim::BodyDesc& b : scene.bodies) {
    if (b.name != m.body) continue;
    row.walk_resolution = b.walk_resolution > 0 ? b.walk_resolution : sim::shapeInfo(b.shape).default_resolution;
  }
}

std::vector<std::string> axisFields(const StudyPlan& plan) {
  std::vector<std::string> out;
  for (const StudyRun& r : plan.runs) {
    for (const auto& [field, value] : r.axis_values) {
      if (std::find(out.begin(), out.end(), field) == out.end()) out.push_back(field);
    }
  }
  return out;
}

std::string axisValue(const StudyRun& run, const std::string& field) {
  for (const auto& [f, v] : run.axis_values) {
    if (f == field) return v;
  }
  return "";
}

std::string resultsCsv(const StudyPlan& plan, const std::vector<Row>& rows) {
  const std::vector<std::string> axes = axisFields(plan);
  const std::vector<StudyMeasure>& first = plan.study.series.front().measures;
  std::string out = "study,series,model,patch,n_sgo,rings,contact_solver,solver_iterations,haptic_rate_hz,walk_resolution";
  for (const std::string& a : axes) out += "," + csvCell(a);
  out += ",measure,reference,error";
  for (std::size_t k = 1; k < first.size(); ++k) {
    out += "," + first[k].name + "," + first[k].name + "_reference," + first[k].name + "_error";
  }
  out += ",step_us_median,step_us_p99,patch_us_mean,status,run\n";
  for (const Row& r : rows) {
    out += csvCell(plan.study.name) + "," + csvCell(r.series) + "," + r.model + "," + r.patch + "," +
           std::to_string(r.n_sgo) + "," + std::to_string(r.rings) + "," + r.solver + "," + std::to_string(r.iterations) + "," +
           number(r.rate) + "," + std::to_string(r.walk_resolution);
    for (const std::string& a : axes) out.append(1, ',').append(csvCell(axisValue(*r.run, a)));
    for (std::size_t k = 0; k < std::max<std::size_t>(first.size(), 1); ++k) {
      const MeasureResult m = k < r.measures.size() ? r.measures[k] : MeasureResult{};
      for (double x : {m.measure, m.reference, m.error}) out.append(1, ',').append(number(x));
    }
    out += "," + number(r.step_median) + "," + number(r.step_p99) + "," + number(r.patch_mean) + "," + r.status + "," +
           r.run->id + "\n";
  }
  return out;
}

// True when two runs' steps overlapped in time on one host, or when a run does not say when and
// where it ran (summary.json's finished_unix_s, wall_time_s and host).
bool ranAtOnce(const std::vector<std::optional<RunOutputs>>& outputs) {
  std::map<std::string, std::vector<std::pair<double, double>>> spans;  // host -> [start, end]
  for (const std::optional<RunOutputs>& o : outputs) {
    if (!o) continue;
    const nlohmann::json& s = o->summary;
    if (!s.contains("finished_unix_s") || !s.contains("wall_time_s") || !s.contains("host")) return true;
    const double end = s["finished_unix_s"].get<double>();
    spans[s["host"].get<std::string>()].emplace_back(end - s["wall_time_s"].get<double>(), end);
  }
  for (auto& [host, list] : spans) {
    std::sort(list.begin(), list.end());
    for (std::size_t i = 1; i < list.size(); ++i) {
      if (list[i].first < list[i - 1].second) return true;
    }
  }
  return false;
}

// Each chart as PNG and SVG into `out`; the work-precision chart answers a scored cost question
// only. Returns ", FILE.png" per chart.
std::string writeCharts(const StudyPlan& plan, const std::vector<Row>& rows, const std::string& out) {
  std::string charts;
  if (plan.study.scored && plan.study.question == StudyQuestion::kCost) {
    render::writeChartPng(workPrecisionChart(plan, rows), (fs::path(out) / "work-precision.png").string());
    charts += ", work-precision.png";
  }
  for (const AxisChart& c : axisCharts(plan, rows)) {
    render::writeChartPng(c.chart, (fs::path(out) / c.file).string());
    charts += ", " + c.file;
  }
  return charts;
}

}  // namespace

int collectStudy(const StudyPlan& plan, const std::string& runs_dir, const std::string& out, bool parallel_times) {
  std::vector<Row> rows(plan.runs.size());
  std::vector<std::optional<RunOutputs>> outputs(plan.runs.size());
  int missing = 0;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const StudyRun& run = plan.runs[i];
    std::vector<std::string> texts;
    for (const StudyOverride& o : run.overrides) texts.push_back(o.text);
    const SessionDesc session = loadSceneFile(run.scene, texts);
    describe(plan, run, session, rows[i]);
    const std::string dir = (fs::path(runs_dir) / "runs" / run.id).string();
    try {
      outputs[i] = readRunOutputs(dir, session);
      const nlohmann::json& summary = outputs[i]->summary;
      rows[i].step_median = summary.at("step_time_us").at("median").get<double>();
      rows[i].step_p99 = summary.at("step_time_us").at("p99").get<double>();
      rows[i].patch_mean = summary.at("patch_time_us").at("mean").get<double>();
      // A run stopped early (Ctrl-C) wrote valid files for the time it reached: not measured.
      const sim::SceneDesc& scene = session.scene;
      const long expected = std::lround(scene.duration * scene.world.haptic_rate_hz);
      if (summary.at("counters").at("steps").get<long>() < expected) {
        std::fprintf(stderr, "godfinger study: %s: stopped after %ld of %ld steps\n", dir.c_str(),
                     summary.at("counters").at("steps").get<long>(), expected);
        rows[i].status = "incomplete";
        outputs[i].reset();
        ++missing;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "godfinger study: %s\n", e.what());
      rows[i].status = "missing";
      ++missing;
    }
  }
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const StudyRun& run = plan.runs[i];
    if (!outputs[i]) continue;
    const RunOutputs* ref = run.reference >= 0 && outputs[static_cast<std::size_t>(run.reference)]
                                ? &*outputs[static_cast<std::size_t>(run.reference)]
                                : nullptr;
    if (run.series < 0) ref = &*outputs[i];  // a reference run against itself
    for (const StudyMeasure& m : measuresOf(plan, run)) {
      try {
        rows[i].measures.push_back(evaluateMeasure(m, *outputs[i], ref));
        const std::string& note = rows[i].measures.back().note;
        if (!note.empty()) {
          std::fprintf(stderr, "godfinger study: %s: %s: %s\n", outputs[i]->dir.c_str(), m.name.c_str(), note.c_str());
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "godfinger study: %s\n", e.what());
        rows[i].measures.push_back({});
        rows[i].status = "unmeasured";
      }
    }
  }
  parallel_times = parallel_times || ranAtOnce(outputs);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw std::runtime_error(out + ": cannot create folder: " + ec.message());
  writeFileAtomically((fs::path(out) / kResultsFile).string(), resultsCsv(plan, rows));
  writeFileAtomically((fs::path(out) / "report.md").string(), reportMd(plan, rows, parallel_times));
  const std::string charts = writeCharts(plan, rows, out);
  int unmeasured = 0, incomplete = 0, absent = 0;
  for (const Row& r : rows) {
    unmeasured += r.status == "unmeasured";
    incomplete += r.status == "incomplete";
    absent += r.status == "missing";
  }
  std::printf("%s: %zu runs (%d missing, %d incomplete, %d unmeasured); wrote %s/results.csv, report.md%s (and "
              "an SVG beside each PNG)\n",
              plan.study.name.c_str(), rows.size(), absent, incomplete, unmeasured, out.c_str(), charts.c_str());
  return missing + unmeasured == 0 ? 0 : 1;
}

void writeStudyGrid(const std::string& dir, const StudyGrid& grid) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create folder: " + ec.message());
  const nlohmann::json j = {{"study", grid.study}, {"quick", grid.quick}, {"set", grid.extra}};
  writeFileAtomically((fs::path(dir) / "grid.json").string(), j.dump(1) + "\n");
}

std::optional<StudyGrid> readStudyGrid(const std::string& dir) {
  const fs::path path = fs::path(dir) / "grid.json";
  if (!fs::exists(path)) return std::nullopt;
  std::ifstream in(path);
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    return StudyGrid{j.at("study").get<std::string>(), j.at("quick").get<bool>(),
                     j.at("set").get<std::vector<std::string>>()};
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string(), 0, 0, "", std::string("not a study grid record: ") + e.what());
  }
}

void emitStudyJobs(const StudyPlan& plan, const StudyOptions& options, const std::string& jobs_file) {
  std::string text;
  for (const StudyRun& r : plan.runs) text += runCommandLine(options.godfinger, options.out, r) + "\n";
  writeFileAtomically(jobs_file, text);
  writeStudyGrid(options.out, {plan.study.source, plan.quick, plan.extra});
  std::printf("%s: %zu command lines in %s; run them (e.g. parallel --will-cite < %s), then: godfinger study %s "
              "--collect %s (the grid is recorded in %s/grid.json)\n",
              plan.study.name.c_str(), plan.runs.size(), jobs_file.c_str(), jobs_file.c_str(), plan.study.source.c_str(),
              options.out.c_str(), options.out.c_str());
}

namespace {

// Says what a rerun keeps: "resuming: 42 of 104 runs kept, 62 to run", and why records were
// not kept.
void reportResume(const StudyPlan& plan, const StudyOptions& options, const StudyResume& resume) {
  const std::size_t total = plan.runs.size(), kept = static_cast<std::size_t>(resume.kept_count);
  if (kept > 0) {
    std::printf("resuming: %zu of %zu runs kept, %zu to run (--restart runs them all)\n", kept, total, total - kept);
  } else if (options.restart) {
    std::printf("restarting: all %zu runs to run\n", total);
  }
  if (resume.other_key > 0) {
    std::fprintf(stderr, "godfinger study: %d finished runs in %s were made with another executable, scene file or "
                 "settings: run again\n", resume.other_key, options.out.c_str());
  }
  if (resume.broken > 0) {
    std::fprintf(stderr, "godfinger study: %d finished runs in %s have missing, changed or unfinished files: run "
                 "again\n", resume.broken, options.out.c_str());
  }
  std::fflush(stdout);
}

}  // namespace

int runStudy(const StudyPlan& plan, const StudyOptions& options) {
  std::error_code ec;
  fs::create_directories(fs::path(options.out) / "runs", ec);
  if (ec) throw std::runtime_error(options.out + ": cannot create folder: " + ec.message());
  writeStudyGrid(options.out, {plan.study.source, plan.quick, plan.extra});
  const StudyResume resume = planResume(plan, options.out, options.godfinger, options.restart);
  reportResume(plan, options, resume);
  // The runs to run: each loses its record first, so one cut short is never kept.
  std::vector<std::size_t> todo;
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    if (resume.kept[i]) continue;
    const std::string dir = (fs::path(options.out) / "runs" / plan.runs[i].id).string();
    forgetFinishedRun(dir);
    todo.push_back(i);
    lines.push_back(runCommandLine(options.godfinger, options.out, plan.runs[i]));
  }
  const bool stopped = options.stop_after > 0 && lines.size() > static_cast<std::size_t>(options.stop_after);
  if (stopped) lines.resize(static_cast<std::size_t>(options.stop_after));
  const auto start = std::chrono::steady_clock::now();
  std::size_t finished = 0;
  int failed = 0;
  const bool interrupted = runJobs(lines, options.jobs, [&](std::size_t k, int code) {
    const StudyRun& run = plan.runs[todo[k]];
    const std::string dir = (fs::path(options.out) / "runs" / run.id).string();
    ++finished;
    if (code == 0) recordFinishedRun(dir, resume.keys[todo[k]]);
    if (code != 0) {
      ++failed;
      std::fprintf(stderr, "godfinger study: run %s failed (exit %d); see %s\n", run.id.c_str(), code,
                   (fs::path(dir) / kRunLogFile).c_str());
    }
    if (options.progress) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double eta = elapsed / static_cast<double>(finished) * static_cast<double>(lines.size() - finished);
      std::fprintf(stderr, "[study] %s: %zu / %zu runs, %s elapsed, ETA %s\n", plan.study.name.c_str(), finished,
                   lines.size(), formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
    }
  });
  if (interrupted) std::fprintf(stderr, "godfinger study: interrupted; collecting the runs that finished\n");
  if (stopped) {
    std::fprintf(stderr, "godfinger study: stopped after %d runs (--stop-after); run again to resume\n",
                 options.stop_after);
  }
  const int collected = collectStudy(plan, options.out, options.out, false);
  if (interrupted || stopped) return 130;
  return failed == 0 && collected == 0 ? 0 : 1;
}

}  // namespace gf::app

// An experiment's report from its folder: per task and within factor, each level's success rate
// and completion time (means over participants with 95 % confidence intervals), the tests, the
// table conditions.tsv and the charts.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "app/experiment/experiment.hpp"
#include "app/experiment/outcome.hpp"
#include "app/experiment/statistics.hpp"
#include "app/runs/files.hpp"
#include "app/runs/run_reader.hpp"
#include "app/scene/input_error.hpp"
#include "app/study/study_chart.hpp"
#include "render/render_thread.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

struct FactorInfo {
  std::string name;
  bool within = true;
  std::vector<std::string> levels;
  std::vector<double> noise;  // per level: the hand's noise it sets (NaN: none)
  bool setsNoise() const { return std::none_of(noise.begin(), noise.end(), [](double v) { return std::isnan(v); }); }
};

struct TestRow {  // one test trial
  int participant = 0;
  std::string task;
  std::map<std::string, std::string> level;  // factor -> level
  bool success = false;
  double completion = NAN;
};

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> cells;
  for (const std::string_view c : splitCells(line, '\t')) cells.emplace_back(c);
  return cells;
}

// A participant's table (header and rows, each row as many cells as the header; a row's line is
// its index + 2); nullopt when the file is not there (a participant not reached yet).
struct Tsv {
  std::string file;
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> rows;
  // The index of column `name`; throws InputError naming the file when it has none.
  std::size_t column(const std::string& name) const {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) throw InputError(file, 1, 0, name, "missing column");
    return static_cast<std::size_t>(at - names.begin());
  }
};

std::optional<Tsv> readTsv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  if (!in || !std::getline(in, line)) return std::nullopt;
  Tsv t;
  t.file = file.string();
  t.names = splitTabs(line);
  for (int number = 2; std::getline(in, line); ++number) {
    t.rows.push_back(splitTabs(line));
    if (t.rows.back().size() != t.names.size()) throw InputError(t.file, number, 0, "", "expected " + std::to_string(t.names.size()) + " cells");
  }
  return t;
}

std::vector<TestRow> readTrials(const fs::path& dir, const std::string& label, int participants,
                                const std::vector<FactorInfo>& factors, int& practice, int& failed_runs) {
  std::vector<TestRow> out;
  for (int p = 0; p < participants; ++p) {
    const std::optional<Tsv> table = readTsv(dir / participantId(p) / "beh" / (participantId(p) + "_task-" + label + "_beh.tsv"));
    if (!table) continue;
    const fs::path file = table->file;
    const auto column = [&](const std::string& name) { return table->column(name); };
    for (std::size_t row = 0; row < table->rows.size(); ++row) {
      const std::vector<std::string>& cells = table->rows[row];
      const int number = static_cast<int>(row) + 2;
      if (cells[column("practice")] == "1") {
        ++practice;
        continue;
      }
      const std::string& success = cells[column("success")];
      if (success == "n/a") {  // the run failed, not the participant
        ++failed_runs;
        continue;
      }
      if (success != "0" && success != "1") throw InputError(file.string(), number, 0, "success", "expected 0, 1 or n/a, got '" + success + "'");
      TestRow r;
      r.participant = p;
      r.task = cells[column("task")];
      for (const FactorInfo& f : factors) r.level[f.name] = cells[column(f.name)];
      r.success = success == "1";
      const std::string& time = cells[column("completion_time")];
      char* end = nullptr;
      r.completion = time == "n/a" ? NAN : std::strtod(time.c_str(), &end);
      if (time != "n/a" && (time.empty() || *end != '\0')) {
        throw InputError(file.string(), number, 0, "completion_time", "expected a number or n/a, got '" + time + "'");
      }
      out.push_back(r);
    }
  }
  return out;
}

// Per participant (rows) and level (columns) of `factor`, for `task`: the success rate and the
// mean completion time of the successes (NaN without one).
struct Cells {
  std::vector<std::vector<double>> rate, time;
};
Cells cellsOf(const std::vector<TestRow>& rows, int participants, const FactorInfo& factor, const std::string& task) {
  const std::size_t k = factor.levels.size();
  const auto rows_of = static_cast<std::size_t>(participants);
  std::vector<std::vector<double>> n(rows_of, std::vector<double>(k, 0.0)), ok = n, time_sum = n;
  for (const TestRow& r : rows) {
    if (r.task != task) continue;
    const std::size_t l = static_cast<std::size_t>(std::find(factor.levels.begin(), factor.levels.end(), r.level.at(factor.name)) - factor.levels.begin());
    if (l >= k) continue;
    const auto p = static_cast<std::size_t>(r.participant);
    n[p][l] += 1.0;
    if (r.success) {
      ok[p][l] += 1.0;
      time_sum[p][l] += r.completion;
    }
  }
  Cells c;
  c.rate = c.time = std::vector<std::vector<double>>(rows_of, std::vector<double>(k, NAN));
  for (std::size_t p = 0; p < rows_of; ++p) {
    for (std::size_t l = 0; l < k; ++l) {
      if (n[p][l] > 0.0) c.rate[p][l] = ok[p][l] / n[p][l];
      if (ok[p][l] > 0.0) c.time[p][l] = time_sum[p][l] / ok[p][l];
    }
  }
  return c;
}

std::vector<double> columnOf(const std::vector<std::vector<double>>& m, std::size_t l) {
  std::vector<double> out;
  for (const auto& row : m) out.push_back(row[l]);
  return out;
}

std::string pText(double p) {
  if (std::isnan(p)) return "n/a";
  char b[32];
  std::snprintf(b, sizeof b, p < 0.001 ? "%.1e" : "%.3f", p);
  return b;
}

// The ANOVA's sentence, "" when it cannot say anything (too few participants, nothing varies).
std::string anovaText(const std::vector<std::vector<double>>& m) {
  const stats::RmAnova r = stats::rmAnova(m);
  if (r.subjects < 2) return "too few participants with every level for an ANOVA; ";
  if (std::isnan(r.f)) return "every participant scored the same in every level; ";
  if (std::isinf(r.f)) return "every participant scored the same in each level and the levels differ (no error variance: F unbounded); ";
  char b[256];
  std::snprintf(b, sizeof b,
                "repeated-measures ANOVA F(%g, %g) = %s, p = %s (Greenhouse-Geisser ε = %.2f, p = %s), partial η² = %.2f (%d participants); ",
                r.df1, r.df2, shortText(r.f, 4).c_str(), pText(r.p).c_str(), r.gg_epsilon, pText(r.p_gg).c_str(), r.partial_eta_squared,
                r.subjects);
  return b;
}

// The test of one measure across the factor's levels, as a sentence.
std::string testText(const std::vector<std::vector<double>>& m, const FactorInfo& f) {
  const std::size_t k = f.levels.size();
  std::vector<std::string> pairs;
  std::vector<double> ps;
  std::vector<stats::Wilcoxon> tests;
  for (std::size_t a = 0; a < k; ++a) {
    for (std::size_t b = a + 1; b < k; ++b) {
      tests.push_back(stats::wilcoxon(columnOf(m, a), columnOf(m, b)));
      pairs.push_back(f.levels[a] + " vs " + f.levels[b]);
      ps.push_back(tests.back().p);
    }
  }
  std::string out = k > 2 ? anovaText(m) + "pairwise Wilcoxon signed-rank (Holm): " : "Wilcoxon signed-rank: ";
  const std::vector<double> adjusted = k > 2 ? stats::holm(ps) : ps;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    char b[200];
    std::snprintf(b, sizeof b, "%s%s: p = %s, r = %+.2f (%d pairs differ%s)", i ? "; " : "", pairs[i].c_str(), pText(adjusted[i]).c_str(),
                  tests[i].n > 0 ? tests[i].rank_biserial : 0.0, tests[i].n, tests[i].exact ? ", exact" : "");
    out += b;
  }
  return out;
}

// A rate's t interval can pass 0 or 1 with few participants: shown within them.
void clampToRates(stats::MeanCi& m) {
  m.lo = std::max(0.0, m.lo);
  m.hi = std::min(1.0, m.hi);
}

std::string ciText(const stats::MeanCi& m, int digits, double scale = 1.0) {
  if (m.n == 0) return "n/a";
  char b[96];
  std::snprintf(b, sizeof b, "%.*f [%.*f, %.*f]", digits, m.mean * scale, digits, m.lo * scale, digits, m.hi * scale);
  return b;
}

// success-rate.png and completion-time.png: per level of `f`, a line over the tasks.
void writeTaskCharts(const fs::path& dir, const std::vector<TestRow>& rows, int participants, const FactorInfo& f,
                     const std::vector<std::string>& tasks) {
  for (const bool rate : {true, false}) {
    render::ChartSpec chart;
    chart.title = std::string(rate ? "Success rate" : "Completion time of the successes (s)") + " by task and " + f.name +
                  ": means over participants, bars 95 % CI";
    chart.x_label = "task, numbered as in the note below";
    chart.y_label = rate ? "success rate, share of trials" : "completion time, s";
    if (rate) {
      chart.y_min = -0.05;
      chart.y_max = 1.05;
    }
    chart.x_min = 0.5;
    chart.x_max = static_cast<double>(tasks.size()) + 0.5;
    std::string names;
    for (std::size_t t = 0; t < tasks.size(); ++t) names += (t ? ", " : "") + std::to_string(t + 1) + " " + tasks[t];
    chart.notes.push_back("tasks: " + names);
    for (std::size_t l = 0; l < f.levels.size(); ++l) {
      // Tasks are categories: markers, no lines between them; the intervals as vertical strokes.
      render::ChartSeries mean{f.levels[l], seriesColour(l), {}, {}, render::SeriesStyle::kMarkers};
      mean.marker = render::seriesLook(l).marker;
      render::ChartSeries ci{"", seriesColour(l), {}, {}, render::SeriesStyle::kLine};
      for (std::size_t t = 0; t < tasks.size(); ++t) {
        const Cells c = cellsOf(rows, participants, f, tasks[t]);
        stats::MeanCi m = stats::meanCi(columnOf(rate ? c.rate : c.time, l));
        if (rate) clampToRates(m);
        const double x = static_cast<double>(t + 1) + 0.1 * (static_cast<double>(l) - 0.5 * static_cast<double>(f.levels.size() - 1));
        mean.x.push_back(x);
        mean.y.push_back(m.mean);
        // The interval as a vertical stroke: its two ends, then a gap (NaN) before the next.
        ci.x.insert(ci.x.end(), {x, x, x});
        ci.y.insert(ci.y.end(), {m.lo, m.hi, NAN});
      }
      chart.series.push_back(mean);
      chart.series.push_back(ci);
    }
    render::writeChartPng(chart, (dir / (rate ? "success-rate.png" : "completion-time.png")).string());
  }
}

// success-vs-noise.png: per level of `f`, the success rate (over every task) against the hand's
// noise, when a factor's levels set it; and the table of it per task.
std::string noiseSection(const fs::path& dir, const std::vector<TestRow>& rows, int participants, const FactorInfo& f,
                         const FactorInfo& noise, const std::vector<std::string>& tasks) {
  render::ChartSpec chart;
  chart.title = "Success rate against the simulated hand's noise, every task, by " + f.name + ": means over participants";
  chart.x_label = "noise, times a typical adult's hand";
  chart.y_label = "success rate, share of trials";
  chart.y_min = -0.05;
  chart.y_max = 1.05;
  std::string md = "\n## Success rate against the hand's noise\n\n| task | " + f.name + " |";
  for (std::size_t j = 0; j < noise.levels.size(); ++j) md += " noise " + shortText(noise.noise[j]) + " |";
  md += "\n|---|---|";
  for (std::size_t j = 0; j < noise.levels.size(); ++j) md += "---|";
  md += "\n";
  for (std::size_t l = 0; l < f.levels.size(); ++l) {
    render::ChartSeries line{f.levels[l], seriesColour(l), {}, {}, render::SeriesStyle::kLineAndMarkers};
    line.marker = render::seriesLook(l).marker;
    line.dash = render::seriesLook(l).dash;
    for (std::size_t j = 0; j < noise.levels.size(); ++j) {
      std::vector<TestRow> at;
      for (const TestRow& r : rows) {
        if (r.level.at(noise.name) == noise.levels[j]) at.push_back(r);
      }
      std::vector<double> per_participant;
      for (int p = 0; p < participants; ++p) {
        double n = 0.0, ok = 0.0;
        for (const TestRow& r : at) {
          if (r.participant == p && r.level.at(f.name) == f.levels[l]) {
            n += 1.0;
            ok += r.success;
          }
        }
        per_participant.push_back(n > 0.0 ? ok / n : NAN);
      }
      line.x.push_back(noise.noise[j]);
      line.y.push_back(stats::meanCi(per_participant).mean);
    }
    chart.series.push_back(line);
  }
  for (const std::string& task : tasks) {
    for (std::size_t l = 0; l < f.levels.size(); ++l) {
      md += "| " + task + " | " + f.levels[l] + " |";
      for (std::size_t j = 0; j < noise.levels.size(); ++j) {
        int n = 0, ok = 0;
        for (const TestRow& r : rows) {
          if (r.task == task && r.level.at(f.name) == f.levels[l] && r.level.at(noise.name) == noise.levels[j]) {
            ++n;
            ok += r.success;
          }
        }
        char cell[32];  // (formatted here: GCC 12 at -O3 warns wrongly of an overlapping copy in string sums)
        std::snprintf(cell, sizeof cell, " %d/%d |", ok, n);
        md += cell;
      }
      md += "\n";
    }
  }
  render::writeChartPng(chart, (dir / "success-vs-noise.png").string());
  return md + "\n![success against noise](success-vs-noise.png)\n";
}

// Per participant (rows) and level of the blocked factor (columns): the mean Raw TLX and realism
// of their answers (NaN where none), from sub-*/beh/*_questionnaire.tsv. Empty without a table.
struct Answers {
  std::vector<std::vector<double>> tlx, realism;
  int tables = 0;
};

Answers readAnswers(const fs::path& dir, const std::string& label, int participants, const FactorInfo& f) {
  Answers a;
  const std::size_t k = f.levels.size();
  std::vector<std::vector<double>> n(static_cast<std::size_t>(participants), std::vector<double>(k, 0.0)), tlx = n, realism = n;
  for (int p = 0; p < participants; ++p) {
    const std::optional<Tsv> table =
        readTsv(dir / participantId(p) / "beh" / (participantId(p) + "_task-" + label + "_questionnaire.tsv"));
    if (!table) continue;
    ++a.tables;
    const auto column = [&](const std::string& name) { return table->column(name); };
    for (std::size_t r = 0; r < table->rows.size(); ++r) {
      const std::vector<std::string>& cells = table->rows[r];
      const auto l = static_cast<std::size_t>(std::find(f.levels.begin(), f.levels.end(), cells[column(f.name)]) - f.levels.begin());
      if (l >= k) throw InputError(table->file, static_cast<int>(r) + 2, 0, f.name, "no level '" + cells[column(f.name)] + "'");
      const auto pi = static_cast<std::size_t>(p);
      n[pi][l] += 1.0;
      tlx[pi][l] += std::strtod(cells[column("raw_tlx")].c_str(), nullptr);
      realism[pi][l] += std::strtod(cells[column("realism")].c_str(), nullptr);
    }
  }
  a.tlx = a.realism = std::vector<std::vector<double>>(n.size(), std::vector<double>(k, NAN));
  for (std::size_t p = 0; p < n.size(); ++p) {
    for (std::size_t l = 0; l < k; ++l) {
      if (n[p][l] == 0.0) continue;
      a.tlx[p][l] = tlx[p][l] / n[p][l];
      a.realism[p][l] = realism[p][l] / n[p][l];
    }
  }
  return a;
}

// The questionnaires' section ("" without any): Raw TLX and realism per level of the blocked factor.
std::string answersSection(const fs::path& dir, const std::string& label, int participants, const FactorInfo& f) {
  const Answers a = readAnswers(dir, label, participants, f);
  if (a.tables == 0) return "";
  std::ostringstream md;
  md << "\n## Questionnaire\n\nAfter each block: Raw NASA-TLX (the mean of its six scales, 0 to 100, lower is easier) and "
        "realism (1 to 7), from sub-*/beh/*_questionnaire.tsv; means over participants with 95 % confidence intervals.\n\n| "
     << f.name << " | Raw TLX | realism | n |\n|---|---|---|---|\n";
  for (std::size_t l = 0; l < f.levels.size(); ++l) {
    const stats::MeanCi tlx = stats::meanCi(columnOf(a.tlx, l)), realism = stats::meanCi(columnOf(a.realism, l));
    md << "| " << f.levels[l] << " | " << ciText(tlx, 1) << " | " << ciText(realism, 2) << " | " << tlx.n << " |\n";
  }
  if (f.levels.size() > 1) md << "\nRaw TLX: " << testText(a.tlx, f) << ".\n\nRealism: " << testText(a.realism, f) << ".\n";
  return md.str();
}

}  // namespace

int reportExperiment(const std::string& folder) {
  const fs::path dir(folder);
  const fs::path record = dir / kExperimentRecord;
  if (!fs::is_regular_file(record)) throw InputError(record.string(), 0, 0, "", "no experiment here (did `godfinger experiment` write to this folder?)");
  const nlohmann::json e = readJsonFile(record);
  std::string name, label;
  int participants = 0;
  std::vector<FactorInfo> factors;
  std::vector<std::string> tasks;
  try {
    name = e.at("name");
    label = e.at("task_label");
    participants = e.at("participants");
    for (const auto& f : e.at("factors")) {
      FactorInfo info{f.at("name"), f.at("within"), {}, {}};
      for (const auto& l : f.at("levels")) {
        info.levels.push_back(l.at("name"));
        info.noise.push_back(l.contains("noise") ? l.at("noise").get<double>() : NAN);
      }
      factors.push_back(info);
    }
    tasks = e.at("tasks").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception& x) {
    throw InputError(record.string(), 0, 0, "", std::string("not what `godfinger experiment` writes: ") + x.what());
  }
  int practice = 0, failed_runs = 0;
  const std::vector<TestRow> rows = readTrials(dir, label, participants, factors, practice, failed_runs);
  std::set<int> seen;  // the participants with a trial in the tables
  for (const TestRow& r : rows) seen.insert(r.participant);
  std::ostringstream md;
  md << "# " << name << ": report\n\n" << e.value("summary", "") << "\n\n"
     << rows.size() << " test trials of " << seen.size() << " participants (" << practice
     << " practice trials left out" << (failed_runs ? ", and " + std::to_string(failed_runs) + " whose run failed" : std::string())
     << "), from sub-*/beh/*_beh.tsv. Per participant and condition, the success rate and the mean "
        "completion time of the successful trials; the means below are over participants, with 95 % confidence intervals (t). "
        "Tests are paired over participants: the Wilcoxon signed-rank test (r: the matched-pairs rank-biserial correlation, "
        "positive when the first level is higher) and, for more than two levels, a one-way repeated-measures ANOVA; a "
        "participant without a success in a condition has no completion time there and leaves that test. A success rate's "
        "interval is shown within 0 and 1. Between-participant "
        "factors are described, not tested. Computed by godfinger (app/experiment/statistics.hpp).\n";
  std::string table = "task\tfactor\tlevel\tparticipants\tsuccess_rate\tsuccess_rate_lo\tsuccess_rate_hi\tcompletion_time\tcompletion_time_lo\tcompletion_time_hi\tcompletion_time_n\n";
  for (const FactorInfo& f : factors) {
    md << "\n## " << f.name << (f.within ? "" : " (between participants)") << "\n";
    for (const std::string& task : tasks) {
      const Cells c = cellsOf(rows, participants, f, task);
      md << "\n### " << task << "\n\n| " << f.name << " | success rate | completion time (s) | n |\n|---|---|---|---|\n";
      for (std::size_t l = 0; l < f.levels.size(); ++l) {
        stats::MeanCi rate = stats::meanCi(columnOf(c.rate, l));
        const stats::MeanCi time = stats::meanCi(columnOf(c.time, l));
        clampToRates(rate);
        md << "| " << f.levels[l] << " | " << ciText(rate, 2) << " | " << ciText(time, 2) << " | " << time.n << " |\n";
        table += task + "\t" + f.name + "\t" + f.levels[l] + "\t" + std::to_string(rate.n) + "\t" + shortText(rate.mean) + "\t" +
                 shortText(rate.lo) + "\t" + shortText(rate.hi) + "\t" + shortText(time.mean) + "\t" + shortText(time.lo) + "\t" +
                 shortText(time.hi) + "\t" + std::to_string(time.n) + "\n";
      }
      if (f.within && f.levels.size() > 1) {
        md << "\nSuccess rate: " << testText(c.rate, f) << ".\n\nCompletion time: " << testText(c.time, f) << ".\n";
      }
    }
  }
  const std::string block_by = e.value("block_by", "");
  const auto blocked = std::find_if(factors.begin(), factors.end(), [&](const FactorInfo& f) { return f.name == block_by; });
  if (blocked != factors.end()) md << answersSection(dir, label, participants, *blocked);
  const auto main = std::find_if(factors.begin(), factors.end(), [](const FactorInfo& f) { return f.within && f.levels.size() > 1; });
  if (main != factors.end()) {
    writeTaskCharts(dir, rows, participants, *main, tasks);
    md << "\n## Charts\n\n![success rate](success-rate.png)\n\n![completion time](completion-time.png)\n";
    const auto noise = std::find_if(factors.begin(), factors.end(), [&](const FactorInfo& f) { return f.setsNoise() && f.name != main->name; });
    if (noise != factors.end()) md << noiseSection(dir, rows, participants, *main, *noise, tasks);
  }
  writeFileAtomically((dir / "conditions.tsv").string(), table);
  writeFileAtomically((dir / "report.md").string(), md.str());
  return 0;
}

}  // namespace gf::app

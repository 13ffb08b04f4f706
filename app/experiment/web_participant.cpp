// A person's session of an experiment in the browser: the phases of the page (ready, trial,
// questionnaire) on one port, the trials as realtime runs, the questionnaire table.
#include "app/experiment/web_participant.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <utility>

#include "app/experiment/trial_tables.hpp"
#include "app/process/interrupt.hpp"
#include "app/runs/files.hpp"
#include "app/runs/run_reader.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"
#include "app/serve/live_view.hpp"
#include "app/session/session.hpp"
#include "app/study/study_resume.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string questionnaireStem(const ExperimentDesc& e, int p) { return participantId(p) + "_task-" + e.task_label + "_questionnaire"; }

// The blocked factor's level in block `block` of `trials` ("" without a blocked factor).
std::string blockLevel(const ExperimentDesc& e, const std::vector<Trial>& trials, int block) {
  for (std::size_t f = 0; f < e.factors.size(); ++f) {
    if (e.factors[f].name != e.block_by) continue;
    for (const Trial& t : trials) {
      if (t.block == block) return e.factors[f].levels[static_cast<std::size_t>(t.levels[f])].name;
    }
  }
  return "";
}

// The answers an earlier session of this participant wrote (to resume after them). A row that
// does not read as answers is refused, naming its line: a person's answers are never dropped.
std::map<int, BlockAnswers> readAnswers(const fs::path& file) {
  std::map<int, BlockAnswers> out;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return out;
  int number = 1;
  std::vector<std::string> header;  // copied: the rows are read into `line`
  for (const std::string_view name : splitCells(line, '\t')) header.emplace_back(name);
  while (std::getline(in, line)) {
    const std::vector<std::string_view> cells = splitCells(line, '\t');
    std::string text = "answers";
    int block = 0;
    for (std::size_t c = 0; c < header.size() && c < cells.size(); ++c) {
      const bool scale = header[c] == "realism" || std::find(kTlxScales.begin(), kTlxScales.end(), header[c]) != kTlxScales.end();
      if (header[c] == "block") std::from_chars(cells[c].data(), cells[c].data() + cells[c].size(), block);
      else if (scale) text.append(" ").append(header[c]).append("=").append(cells[c]);
    }
    std::string why;
    const std::optional<BlockAnswers> a = parseAnswers(text, block, why);
    ++number;
    if (!a || block < 1) {
      throw InputError(file.string(), number, 0, "", (a ? std::string("no block number") : why) +
                                                        ": fix the row, or --restart to run the participant again");
    }
    out[block] = *a;
  }
  return out;
}

void writeAnswers(const ExperimentDesc& e, const std::string& out, int p, const std::vector<Trial>& trials,
                  const std::map<int, BlockAnswers>& answers) {
  if (answers.empty()) return;
  const fs::path beh = fs::path(out) / participantId(p) / "beh";
  std::string text = "block";
  if (!e.block_by.empty()) text += "\t" + e.block_by;
  for (const char* scale : kTlxScales) text.append("\t").append(scale);
  text += "\traw_tlx\trealism\n";
  for (const auto& [block, a] : answers) {
    text += std::to_string(block);
    if (!e.block_by.empty()) text += "\t" + tsvCell(blockLevel(e, trials, block));
    for (const int v : a.tlx) text.append("\t").append(std::to_string(v));
    text.append("\t").append(shortText(a.rawTlx(), 4)).append("\t").append(std::to_string(a.realism)).append("\n");
  }
  json columns = {{"block", {{"Description", "the block the answers are about (asked after its last trial)"}}},
                  {"raw_tlx", {{"Description", "Raw TLX: the mean of the six scales"}}},
                  {"realism", {{"Description", "\"How much did touching the objects feel like touching real objects?\""},
                               {"Levels", {{"1", "not at all"}, {"7", "just like real objects"}}}}}};
  static constexpr const char* kQuestions[] = {
      "How mentally demanding was the task?", "How physically demanding was the task?",
      "How hurried or rushed was the pace of the task?", "How successful were you in accomplishing what you were asked to do?",
      "How hard did you have to work to accomplish your level of performance?",
      "How insecure, discouraged, irritated, stressed and annoyed were you?"};
  for (std::size_t s = 0; s < kTlxScales.size(); ++s) {
    columns[kTlxScales[s]] = {{"Description", std::string("NASA-TLX: ") + kQuestions[s]},
                              {"Levels", s == 3 ? json{{"0", "perfect"}, {"100", "failure"}} : json{{"0", "very low"}, {"100", "very high"}}}};
  }
  if (!e.block_by.empty()) columns[e.block_by] = {{"Description", "the blocked factor's level in that block"}};
  writeFileAtomically((beh / (questionnaireStem(e, p) + ".tsv")).string(), text);
  writeFileAtomically((beh / (questionnaireStem(e, p) + ".json")).string(), columns.dump(2) + "\n");
}

// Serves the page in one phase between trials (`panel`), with `session` for its view, on the
// session's port until the page posts a line `check` accepts (returns "" for one; else why
// not, answered as an error). The first bind fixes the port and the token for the others.
// Returns the line, or nullopt on Ctrl-C or SIGTERM (the caller holds the InterruptScope; a
// signal just after a line was accepted is still there for it to see).
std::optional<std::string> waitForPage(const SessionDesc& session, ServeOptions& serve, bool& serve_announced, const json& panel,
                                       const std::function<std::string(const std::string&)>& check) {
  std::mutex mutex;
  std::condition_variable accepted_cv;
  std::optional<std::string> accepted;
  LiveView view(session, sessionCamera(session, ""), "participant", "", false);
  view.setParticipant(panel);
  WebServer server(serve, view, [&](const std::string& line) -> std::string {
    const std::string why = check(line);
    if (!why.empty()) return "error: " + why;
    {
      std::lock_guard lock(mutex);
      if (!accepted) accepted = line;
    }
    accepted_cv.notify_all();
    return "ok";
  });
  if (!std::exchange(serve_announced, true)) {  // the first phase: where the page is
    std::fprintf(stderr, "godfinger experiment: %s's page: serving %s%s\n", panel.value("participant", "").c_str(),
                 server.shownUrl().c_str(), server.loopback() ? "" : "  (beyond loopback: every request needs this token)");
  }
  serve.port = server.port();
  serve.token = server.token();
  std::unique_lock lock(mutex);
  while (!accepted && interruptSignal() == 0) accepted_cv.wait_for(lock, std::chrono::milliseconds(100));
  const std::optional<std::string> line = accepted;
  lock.unlock();
  // The page hears its "ok" before this phase's server goes: the answer is handed to the
  // connection after the command is counted answered, so a quarter of a second more for the
  // write (a second at most in all).
  for (int i = 0; line && i < 75 && server.statsJson().value("commands_running", 0L) > 0; ++i) {
    lock.lock();
    accepted_cv.wait_for(lock, std::chrono::milliseconds(10));
    lock.unlock();
  }
  if (line) {
    lock.lock();
    accepted_cv.wait_for(lock, std::chrono::milliseconds(250));
    lock.unlock();
  }
  server.stop();
  return line;
}

json outcomeJson(const TaskDesc& task, const TrialOutcome& o) {
  const std::string failure = o.ran ? o.failure : "the trial stopped short: a failure of the software, not yours";
  json j = {{"task", task.name}, {"ran", o.ran}, {"success", o.success}, {"failure", failure}};
  if (o.success) j["completion_s"] = o.completion_s;
  return j;
}

// This process's mark in the phases' ids: a resumed session's phases are new ones to a page left
// open, even those with the same trial number.
const std::string& sessionMark() {
  static const std::string mark = std::to_string(getpid()) + "." +
                                  std::to_string(std::chrono::steady_clock::now().time_since_epoch().count() % 1000000007);
  return mark;
}

// What the page's panel shows: never a condition's name.
json panelFor(const ExperimentDesc& e, const std::vector<Trial>& trials, std::size_t i, const std::string& phase,
              const json& previous) {
  const Trial& t = trials[i];
  const TaskDesc& task = e.tasks[static_cast<std::size_t>(t.task)];
  json grip = json::object();  // the wheel closes the grip along these (unit)
  for (const auto& [finger, direction] : task.grip) {
    const sim::Vec3 d = direction.normalized();
    grip[finger] = {d.x(), d.y(), d.z()};
  }
  return {{"id", phase + "-" + std::to_string(t.number) + "-" + sessionMark()},
          {"device", e.device},
          {"grip", grip},
          {"phase", phase},
          {"participant", participantId(t.participant)},
          {"task", task.name},
          {"instruction", task.instruction},
          {"trial", t.number},
          {"trials", trials.back().number},
          {"block", t.block},
          {"blocks", trials.back().block},
          {"practice", t.practice},
          {"time_limit_s", task.time_limit},
          {"previous", previous},
          {"last", i + 1 == trials.size()}};
}

// A trial's run: the fingers on the page's pointer, where their tracks start; the condition, the
// goal drawn, the time limit; its key (the run's, marked as a person's trial).
TrialRun prepareWebTrial(const ExperimentDesc& e, const Trial& t, const SessionDesc& scene, const std::string& out) {
  const TaskDesc& task = e.tasks[static_cast<std::size_t>(t.task)];
  TrialRun r;
  r.dir = (behDir(out, t) / "trials" / trialName(t)).string();
  for (std::size_t f = 0; f < scene.scene.fingers.size(); ++f) {
    r.fingers.push_back(scene.scene.fingers[f].name);
    r.run.overrides.push_back({participantDeviceOverride(e, scene.scene.fingers[f], static_cast<int>(f)), {}, {}});
  }
  for (const std::string& o : trialOverrides(e, t, r.fingers)) r.run.overrides.push_back({o, {}, {}});
  for (const std::string& o : goalTargetOverrides(task.goal)) r.run.overrides.push_back({o, {}, {}});
  r.run.overrides.push_back({"duration=" + sim::numberText(task.time_limit, 17), {}, {}});
  r.run.overrides.push_back({"record.trace_rate=" + sim::numberText(kTraceRateHz), {}, {}});
  r.run.scene = task.scene;
  // Not the binary's hash, unlike a simulated trial's: a person's trial is not run again because
  // godfinger was rebuilt.
  r.key = hex64(fnv1a64(kFnv1a64Basis, "godfinger experiment web trial 1 " + studyRunKey("", r.run)));
  return r;
}

// A trial's session as the participant sees it: the contacts' patches, the insets and the overlay
// off, since they show the model (a god-finger's patch and SGOs, a god-object's point).
// A UDP device's force fades out after the time limit, in a run longer by the fade (and a few
// steps): the run that ends leaves no device pushing, and the next trial's ramp starts from zero.
SessionDesc trialSession(const ExperimentDesc& e, const TrialRun& r) {
  SessionDesc s = loadSceneWithOverrides(e.source, r.run.scene, r.run.overrides);
  s.view.patch_highlight = false;
  s.view.patch_insets = false;
  s.view.overlay = false;
  s.view.actions.clear();
  double fade = 0.0;
  for (UdpDeviceDesc& d : s.udp_devices) {
    d.fade_out_at = s.scene.duration;
    fade = std::max(fade, d.force_ramp);
  }
  if (fade > 0.0) s.scene.duration += fade + 5.0 / s.scene.world.haptic_rate_hz;
  return s;
}

// Runs a trial in real time with the page in its "trial" phase. Returns its outcome, or nullopt
// when Ctrl-C or SIGTERM stopped it (it runs again on resume).
std::optional<TrialOutcome> runWebTrial(const TaskDesc& task, const TrialRun& r, const SessionDesc& session, ServeOptions serve,
                                        const json& panel) {
  SessionOptions o;
  o.out_dir = r.dir;
  o.realtime = true;
  o.progress = false;
  o.stop_on_held_interrupt = true;
  serve.participant = panel;
  serve.participant_command = [](const std::string& line) -> std::optional<std::string> {
    if (line == "ready") return std::string("ok");  // a second click of Start
    return std::nullopt;
  };
  o.serve = serve;
  forgetFinishedRun(r.dir);
  int code = 0;
  try {
    runSession(session, o);
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "godfinger experiment: trial %s failed: %s\n", r.dir.c_str(), ex.what());
    code = 1;
  }
  if (interruptSignal() != 0) return std::nullopt;
  if (code == 0) recordFinishedRun(r.dir, r.key);
  return judgeTrial(task.goal, r.fingers, r.dir, code, task.time_limit);  // not the device's fade after it
}

// A participant's trials, their runs, and the outcomes of those finished before (unless
// options.restart). Throws InputError when a trial was run before under other settings.
struct ParticipantTrials {
  std::vector<Trial> trials;
  std::vector<TrialRun> runs;
  std::vector<std::optional<TrialOutcome>> outcomes;
};

ParticipantTrials planParticipant(const ExperimentDesc& e, const ExperimentOptions& options) {
  const int p = options.participant - 1;
  ParticipantTrials plan;
  std::vector<Trial>& trials = plan.trials;
  for (const Trial& t : planTrials(e)) {
    if (t.participant == p) trials.push_back(t);
  }
  std::vector<TrialRun>& runs = plan.runs;
  std::vector<std::optional<TrialOutcome>>& outcomes = plan.outcomes;
  outcomes.resize(trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const TaskDesc& task = e.tasks[static_cast<std::size_t>(trials[i].task)];
    runs.push_back(prepareWebTrial(e, trials[i], loadSceneFile(task.scene), options.out));
    if (options.restart) continue;
    if (runFinishedWith(runs[i].dir, runs[i].key)) {
      outcomes[i] = judgeTrial(task.goal, runs[i].fingers, runs[i].dir, 0);
    } else if (fs::exists(fs::path(runs[i].dir) / kStudyRunRecord)) {  // a person's trial is never overwritten unasked
      throw InputError(runs[i].dir, 0, 0, "", "this trial of " + participantId(p) + " was run under other settings (the "
                       "experiment or task file changed?): give another --out, or --restart to run the participant again");
    }
  }
  return plan;
}

// A participant's session: the phases in turn, the trials, the questionnaires, the tables.
class WebSession {
 public:
  WebSession(const ExperimentDesc& e, const ExperimentOptions& options)
      : e_(e), options_(options), p_(options.participant - 1), plan_(planParticipant(e, options)), serve_(*options.serve) {
    const fs::path file = fs::path(options.out) / participantId(p_) / "beh" / (questionnaireStem(e, p_) + ".tsv");
    answers_ = readAnswers(file);
  }

  // Every trial not finished before, each block's questionnaire after its last trial.
  void run() {
    const std::vector<Trial>& trials = plan_.trials;
    for (std::size_t i = 0; i < trials.size() && !interrupted_ && !stopped_; ++i) {
      const TaskDesc& task = e_.tasks[static_cast<std::size_t>(trials[i].task)];
      if (plan_.outcomes[i]) {
        previous_ = outcomeJson(task, *plan_.outcomes[i]);
        continue;
      }
      if (!askFinishedBlocks()) return;
      stopped_ = options_.stop_after > 0 && ran_ >= options_.stop_after;
      if (stopped_) return;
      const SessionDesc session = trialSession(e_, plan_.runs[i]);
      const auto ready = [](const std::string& line) { return line == "ready" ? std::string() : "expected: ready"; };
      interrupted_ = !waitForPage(session, serve_, announced_, panelFor(e_, trials, i, "ready", previous_), ready) ||
                     interruptSignal() != 0;
      if (interrupted_) return;
      const std::optional<TrialOutcome> o =
          runWebTrial(task, plan_.runs[i], session, serve_, panelFor(e_, trials, i, "trial", previous_));
      interrupted_ = !o;
      if (interrupted_) return;
      plan_.outcomes[i] = *o;
      previous_ = outcomeJson(task, *o);
      ++ran_;
      writeParticipantTable(e_, options_.out, p_, trials, plan_.runs, plan_.outcomes);  // each trial kept as it ends
    }
    if (!interrupted_ && !stopped_) askFinishedBlocks();
  }

  // Writes the tables and the report; the exit code.
  int finish() {
    writeDatasetFiles(e_, options_.out);
    writeParticipantTable(e_, options_.out, p_, plan_.trials, plan_.runs, plan_.outcomes);
    writeAnswers(e_, options_.out, p_, plan_.trials, answers_);
    printSummary(e_, plan_.trials, plan_.outcomes);
    reportExperiment(options_.out);
    const auto done = std::count_if(plan_.outcomes.begin(), plan_.outcomes.end(), [](const auto& o) { return o.has_value(); });
    std::fprintf(stderr, "godfinger experiment: %s: %d trials run now, %ld of %zu done; wrote %s/\n", participantId(p_).c_str(),
                 ran_, static_cast<long>(done), plan_.trials.size(), options_.out.c_str());
    if (interrupted_) std::fprintf(stderr, "godfinger experiment: interrupted; run the same command again to go on\n");
    if (stopped_) std::fprintf(stderr, "godfinger experiment: stopped after %d trials (--stop-after); run again to resume\n", ran_);
    return interrupted_ || stopped_ ? 130 : 0;
  }

 private:
  // The questionnaire of every block whose trials are all done and which has no answers yet, in
  // order (false: interrupted).
  bool askFinishedBlocks() {
    const std::vector<Trial>& trials = plan_.trials;
    for (std::size_t i = 0; i < trials.size(); ++i) {
      const int block = trials[i].block;
      const bool block_ends = i + 1 == trials.size() || trials[i + 1].block != block;
      if (!block_ends || answers_.contains(block)) continue;
      bool done = true;
      for (std::size_t j = 0; j < trials.size(); ++j) done = done && (trials[j].block != block || plan_.outcomes[j].has_value());
      if (done && !ask(block, i)) return false;
    }
    return true;
  }

  // The questionnaire of `block`, on the page of its last trial `i` (false: interrupted).
  bool ask(int block, std::size_t i) {
    json panel = panelFor(e_, plan_.trials, i, "questionnaire", previous_);
    panel["id"] = "questionnaire-" + std::to_string(block) + "-" + sessionMark();
    panel["block"] = block;
    panel["last"] = i + 1 == plan_.trials.size();
    const auto check = [block](const std::string& line) {
      std::string why;
      return parseAnswers(line, block, why) ? std::string() : why;
    };
    const std::optional<std::string> line = waitForPage(trialSession(e_, plan_.runs[i]), serve_, announced_, panel, check);
    if (line) {
      std::string why;
      answers_[block] = *parseAnswers(*line, block, why);
      writeAnswers(e_, options_.out, p_, plan_.trials, answers_);
    }
    interrupted_ = !line || interruptSignal() != 0;
    return !interrupted_;
  }

  const ExperimentDesc& e_;
  const ExperimentOptions& options_;
  const int p_;
  ParticipantTrials plan_;
  std::map<int, BlockAnswers> answers_;
  ServeOptions serve_;
  bool announced_ = false;  // the page's address printed
  json previous_ = nullptr;
  int ran_ = 0;
  bool interrupted_ = false, stopped_ = false;
};

}  // namespace

double BlockAnswers::rawTlx() const {
  double sum = 0.0;
  for (const int v : tlx) sum += v;
  return sum / static_cast<double>(tlx.size());
}

std::optional<BlockAnswers> parseAnswers(const std::string& line, int block, std::string& why) {
  const std::vector<std::string_view> words = splitCells(line, ' ');
  if (words.empty() || words[0] != "answers") {
    why = "expected: answers mental_demand=0..100 ... frustration=0..100 realism=1..7";
    return std::nullopt;
  }
  BlockAnswers a;
  a.block = block;
  std::array<bool, 7> given{};
  for (std::size_t w = 1; w < words.size(); ++w) {
    const std::string_view word = words[w];
    const std::size_t eq = word.find('=');
    const std::string_view key = word.substr(0, eq == std::string_view::npos ? word.size() : eq);
    std::size_t k = 0;
    while (k < kTlxScales.size() && key != kTlxScales[k]) ++k;
    if (k == kTlxScales.size() && key != "realism") {
      why = "answers: unknown scale '" + std::string(key) + "'";
      return std::nullopt;
    }
    int v = -1;
    const std::string_view value = eq == std::string_view::npos ? std::string_view() : word.substr(eq + 1);
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    const int lo = k < kTlxScales.size() ? 0 : 1, hi = k < kTlxScales.size() ? 100 : 7;
    if (ec != std::errc() || end != value.data() + value.size() || v < lo || v > hi || given[k]) {
      why = "answers: " + std::string(key) + (given[k] ? " given twice" : " must be a whole number in " + std::to_string(lo) + ".." + std::to_string(hi));
      return std::nullopt;
    }
    given[k] = true;
    (k < kTlxScales.size() ? a.tlx[k] : a.realism) = v;
  }
  for (std::size_t k = 0; k < given.size(); ++k) {
    if (given[k]) continue;
    why = std::string("answers: ") + (k < kTlxScales.size() ? kTlxScales[k] : "realism") + " is missing";
    return std::nullopt;
  }
  return a;
}

int runWebParticipant(const ExperimentDesc& e, const ExperimentOptions& options) {
  const fs::path folder = fs::path(options.out) / participantId(options.participant - 1);
  if (options.restart && fs::exists(folder)) {  // a person's data is moved aside, never deleted
    const fs::path aside = folder.string() + ".before-" + std::to_string(std::time(nullptr));
    fs::rename(folder, aside);
    std::fprintf(stderr, "godfinger experiment: --restart: the earlier %s moved to %s\n", folder.filename().c_str(), aside.c_str());
  }
  WebSession session(e, options);
  const InterruptScope interrupt;  // held across the phases and the trials: no signal falls between
  try {
    session.run();
  } catch (...) {
    session.finish();  // what was reached is written, then the error is reported
    throw;
  }
  return session.finish();
}

}  // namespace gf::app

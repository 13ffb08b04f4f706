// Running an experiment's trials and writing its BIDS-like outputs.
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "app/experiment/experiment.hpp"
#include "app/experiment/hand.hpp"
#include "app/experiment/outcome.hpp"
#include "app/experiment/trial_tables.hpp"
#include "app/runs/files.hpp"
#include "app/runs/jobs.hpp"
#include "app/runs/run_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/study/study_resume.hpp"
#include "sim/scene/settings.hpp"
#include "sim/about.hpp"

namespace gf::app {

namespace fs = std::filesystem;

std::string trialName(const Trial& t) {
  char b[16];
  std::snprintf(b, sizeof b, "%03d", t.number);
  return b;
}

fs::path behDir(const std::string& out, const Trial& t) { return fs::path(out) / participantId(t.participant) / "beh"; }

std::string tsvCell(std::string s) {
  for (char& c : s) {
    if (c == '\t' || c == '\n' || c == '\r') c = ' ';
  }
  return s.empty() ? "n/a" : s;
}

namespace {

std::string na(double v, int digits = 6) { return shortText(v, digits); }
std::string cell(std::string s) { return tsvCell(std::move(s)); }

nlohmann::json columnSidecar(const ExperimentDesc& e) {
  nlohmann::json j = {
      {"trial", {{"Description", "the trial's number in the participant's session, in the order run"}}},
      {"block", {{"Description", "the block's number (a level of the blocked factor each)"}}},
      {"practice", {{"Description", "1 for a practice trial (left out of the statistics)"}, {"Levels", {{"0", "test"}, {"1", "practice"}}}}},
      {"task", {{"Description", "the task performed"}}},
      {"success", {{"Description", "1 when the goal held for its hold time within the time limit and no limit was passed"},
                   {"Levels", {{"0", "failed"}, {"1", "succeeded"}}}}},
      {"completion_time", {{"Description", "when the goal began to hold in the stretch that held it"}, {"Units", "s"}}},
      {"failure", {{"Description", "why the trial failed"}}},
      {"max_tilt", {{"Description", "the body's largest tilt from its starting orientation until the trial was decided"}, {"Units", "deg"}}},
      {"roll_ratio", {{"Description", "angle turned times radius over distance travelled (1 rolling, 0 sliding), for a goal that limits it"}}},
      {"end_distance", {{"Description", "the body's centre from the goal zone when the trial was decided"}, {"Units", "mm"}}},
      {"end_angle", {{"Description", "the turn left to the goal orientation when the trial was decided"}, {"Units", "deg"}}},
      {"peak_force", {{"Description", "the largest coupling force of any finger"}, {"Units", "N"}}},
      {"time_limit", {{"Description", "the trial's length"}, {"Units", "s"}}},
      {"run", {{"Description", "the trial's run folder (trace.csv, summary.json, contacts/), from the participant's folder"}}},
  };
  for (const ExperimentFactor& f : e.factors) {
    nlohmann::json levels = nlohmann::json::object();
    for (const ExperimentLevel& l : f.levels) {
      std::string set;
      for (const StudyOverride& o : l.set) set += (set.empty() ? "" : "; ") + o.text;
      if (l.noise) set += (set.empty() ? "" : "; ") + std::string("hand noise ") + shortText(*l.noise);
      levels[l.name] = set;
    }
    j[f.name] = {{"Description", std::string(f.within ? "within" : "between") + "-participant factor"}, {"Levels", levels}};
  }
  return j;
}

}  // namespace

// The participant's table: one row a trial (those not run yet left out).
void writeParticipantTable(const ExperimentDesc& e, const std::string& out, int p, const std::vector<Trial>& trials,
                           const std::vector<TrialRun>& runs, const std::vector<std::optional<TrialOutcome>>& outcomes) {
  std::string text = "trial\tblock\tpractice\ttask";
  for (const ExperimentFactor& f : e.factors) text += "\t" + f.name;
  text += "\tsuccess\tcompletion_time\tfailure\tmax_tilt\troll_ratio\tend_distance\tend_angle\tpeak_force\ttime_limit\trun\n";
  fs::path dir;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const Trial& t = trials[i];
    if (t.participant != p || !outcomes[i]) continue;
    dir = behDir(out, t);
    const TrialOutcome& o = *outcomes[i];
    text += std::to_string(t.number) + "\t" + std::to_string(t.block) + "\t" + (t.practice ? "1" : "0") + "\t" +
            e.tasks[static_cast<std::size_t>(t.task)].name;
    for (std::size_t f = 0; f < e.factors.size(); ++f) text += "\t" + e.factors[f].levels[static_cast<std::size_t>(t.levels[f])].name;
    text += std::string("\t") + (!o.ran ? "n/a" : o.success ? "1" : "0") + "\t" + na(o.completion_s) + "\t" + cell(o.failure) + "\t" +
            na(o.max_tilt_deg, 4) + "\t" + na(o.roll_ratio, 4) + "\t" + na(o.end_distance_m * 1e3, 4) + "\t" +
            na(o.end_angle_deg, 4) + "\t" + na(o.peak_force_n, 4) + "\t" +
            sim::numberText(e.tasks[static_cast<std::size_t>(t.task)].time_limit) + "\t" +
            fs::path(runs[i].dir).lexically_relative(fs::path(out) / participantId(p)).generic_string() + "\n";
  }
  const std::string stem = participantId(p) + "_task-" + e.task_label + "_beh";
  if (dir.empty()) {  // no trial of theirs finished: no table, not even one an earlier run left
    const fs::path beh = fs::path(out) / participantId(p) / "beh";
    std::error_code ec;
    fs::remove(beh / (stem + ".tsv"), ec);
    fs::remove(beh / (stem + ".json"), ec);
    return;
  }
  writeFileAtomically((dir / (stem + ".tsv")).string(), text);
  writeFileAtomically((dir / (stem + ".json")).string(), columnSidecar(e).dump(2) + "\n");
}

void writeExperimentRecord(const ExperimentDesc& e, const std::string& out) {
  nlohmann::json factors = nlohmann::json::array();
  for (const ExperimentFactor& f : e.factors) {
    nlohmann::json levels = nlohmann::json::array();
    for (const ExperimentLevel& l : f.levels) {
      nlohmann::json level = {{"name", l.name}};
      if (l.noise) level["noise"] = *l.noise;
      levels.push_back(level);
    }
    factors.push_back({{"name", f.name}, {"within", f.within}, {"levels", levels}});
  }
  nlohmann::json tasks = nlohmann::json::array();
  for (const TaskDesc& t : e.tasks) tasks.push_back(t.name);
  const nlohmann::json record = {{"name", e.name}, {"summary", e.summary}, {"source", e.source}, {"task_label", e.task_label},
                                 {"participants", e.participants}, {"block_by", e.block_by}, {"factors", factors}, {"tasks", tasks}};
  writeFileAtomically((fs::path(out) / kExperimentRecord).string(), record.dump(2) + "\n");
}

void writeDatasetFiles(const ExperimentDesc& e, const std::string& out) {
  writeExperimentRecord(e, out);
  const nlohmann::json description = {
      {"Name", e.name + (e.summary.empty() ? "" : ": " + e.summary)},
      {"BIDSVersion", "1.8.0"},
      {"DatasetType", "raw"},
      {"GeneratedBy", {{{"Name", "godfinger"}, {"Version", sim::libraryVersion()},
                        {"Description", "godfinger experiment " + e.source}}}},
  };
  writeFileAtomically((fs::path(out) / "dataset_description.json").string(), description.dump(2) + "\n");
  std::string text = "participant_id";
  for (const ExperimentFactor& f : e.factors) {
    if (!f.within) text += "\t" + f.name;
  }
  const bool simulated = e.device == "simulated";
  text += simulated ? "\tblock_order\treaction_time\tpace\tendpoint_sd\ttremor_rms\tgrip_sd\n" : "\tblock_order\n";
  const std::vector<Trial> trials = planTrials(e);
  for (int p = 0; p < e.participants; ++p) {
    // People come one at a time: those with a folder are listed.
    if (!simulated && !fs::is_directory(fs::path(out) / participantId(p) / "beh")) continue;
    const auto first = std::find_if(trials.begin(), trials.end(), [p](const Trial& t) { return t.participant == p; });
    text += participantId(p);
    for (std::size_t f = 0; f < e.factors.size(); ++f) {
      if (!e.factors[f].within) text += "\t" + e.factors[f].levels[static_cast<std::size_t>(first->levels[f])].name;
    }
    std::string order;
    const auto block = std::find_if(e.factors.begin(), e.factors.end(), [&](const ExperimentFactor& f) { return f.name == e.block_by; });
    for (int b = 1, seen = 0; block != e.factors.end() && seen < static_cast<int>(block->levels.size()); ++b) {
      const auto at = std::find_if(trials.begin(), trials.end(), [&](const Trial& t) { return t.participant == p && t.block == b; });
      if (at == trials.end()) break;
      order += (order.empty() ? "" : ",") + block->levels[static_cast<std::size_t>(at->levels[static_cast<std::size_t>(block - e.factors.begin())])].name;
      ++seen;
    }
    if (!simulated) {
      text += "\t" + cell(order) + "\n";
      continue;
    }
    const HandParams h = drawHand(e.seed, p, e.noise);
    text += "\t" + cell(order) + "\t" + shortText(h.reaction_s, 3) + "\t" + shortText(h.speed, 3) + "\t" +
            shortText(h.endpoint_sd_m * 1e3, 3) + "\t" + shortText(h.tremor_rms_m * 1e3, 3) + "\t" +
            shortText(h.grip_sd_m * 1e3, 3) + "\n";
  }
  writeFileAtomically((fs::path(out) / "participants.tsv").string(), text);
  nlohmann::json columns = {
      {"participant_id", {{"Description", "a simulated participant (the seeded hand of app/experiment/hand.hpp); the hand's figures at the experiment's noise scale"}}},
      {"block_order", {{"Description", "the blocks' levels in the order met"}}},
      {"reaction_time", {{"Description", "delay before each movement starts"}, {"Units", "s"}}},
      {"pace", {{"Description", "the scripted durations are divided by it"}}},
      {"endpoint_sd", {{"Description", "scatter of the hand's waypoints per axis"}, {"Units", "mm"}}},
      {"tremor_rms", {{"Description", "physiological tremor (8-12 Hz), RMS per axis"}, {"Units", "mm"}}},
      {"grip_sd", {{"Description", "the squeeze's bias and slow wander along the grip"}, {"Units", "mm"}}},
  };
  if (!simulated) {
    columns = {{"participant_id", {{"Description", "a person who performed the trials in the browser (" + e.device + " device)"}}},
               {"block_order", columns["block_order"]}};
  }
  writeFileAtomically((fs::path(out) / "participants.json").string(), columns.dump(2) + "\n");
}

// Per task and level of every within factor: test trials' success rate and median completion time.
void printSummary(const ExperimentDesc& e, const std::vector<Trial>& trials, const std::vector<std::optional<TrialOutcome>>& outcomes) {
  for (std::size_t f = 0; f < e.factors.size(); ++f) {
    std::printf("%-24s", (e.factors[f].name + " \\ task").c_str());
    for (const TaskDesc& task : e.tasks) std::printf(" %22s", task.name.c_str());
    std::printf("\n");
    for (std::size_t l = 0; l < e.factors[f].levels.size(); ++l) {
      std::printf("%-24s", e.factors[f].levels[l].name.c_str());
      for (std::size_t task = 0; task < e.tasks.size(); ++task) {
        int n = 0, ok = 0;
        std::vector<double> times;
        for (std::size_t i = 0; i < trials.size(); ++i) {
          const Trial& t = trials[i];
          if (t.practice || !outcomes[i] || !outcomes[i]->ran || static_cast<std::size_t>(t.task) != task ||
              static_cast<std::size_t>(t.levels[f]) != l) {
            continue;
          }
          ++n;
          ok += outcomes[i]->success;
          if (outcomes[i]->success) times.push_back(outcomes[i]->completion_s);
        }
        std::sort(times.begin(), times.end());
        char b[64];
        if (n == 0) std::snprintf(b, sizeof b, "-");
        else if (times.empty()) std::snprintf(b, sizeof b, "%d/%d", ok, n);
        else std::snprintf(b, sizeof b, "%d/%d, %.2f s", ok, n, 0.5 * (times[(times.size() - 1) / 2] + times[times.size() / 2]));
        std::printf(" %22s", b);
      }
      std::printf("\n");
    }
  }
}

namespace {

// A trial's run: its hand's tracks written (beside its folder), its overrides and its key (the
// study runner's, with the tracks' bytes: another seed or noise is another trial).
TrialRun prepareTrial(const ExperimentDesc& e, const Trial& t, const sim::SceneDesc& scene, const std::string& out,
                      const std::string& binary) {
  const TaskDesc& task = e.tasks[static_cast<std::size_t>(t.task)];
  TrialRun r;
  for (const sim::FingerDesc& f : scene.fingers) r.fingers.push_back(f.name);
  const fs::path beh = behDir(out, t);
  r.dir = (beh / "trials" / trialName(t)).string();
  fs::create_directories(beh / "hand");
  const double noise = trialNoise(e, t);
  const HandParams hand = drawHand(e.seed, t.participant, noise);
  std::uint64_t hash = fnv1a64(kFnv1a64Basis, "godfinger experiment trial 1");
  for (const HandTrack& track : moveHand(scene.fingers, task.grip, hand, t.seed, noise, task.time_limit)) {
    const std::string file = fs::absolute(beh / "hand" / (trialName(t) + "-" + track.finger + ".csv")).string();
    writeHandCsv(file, track);
    const std::string content = fileFnv1a64(file);
    hash = fnv1a64(hash, std::string_view(content.c_str(), content.size() + 1));
    r.hand_files.push_back(file);
    std::string quoted;  // a TOML basic string
    for (const char c : file) quoted += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
    r.run.overrides.push_back({"fingers." + track.finger + ".device={csv=\"" + quoted + "\"}", {}, {}});
  }
  for (const std::string& o : trialOverrides(e, t, r.fingers)) r.run.overrides.push_back({o, {}, {}});
  for (const std::string& o : goalTargetOverrides(task.goal)) r.run.overrides.push_back({o, {}, {}});
  r.run.overrides.push_back({"duration=" + exactSeconds(task.time_limit), {}, {}});
  r.run.overrides.push_back({"record.trace_rate=" + sim::numberText(kTraceRateHz), {}, {}});
  r.run.scene = task.scene;
  // The key names the tracks by their bytes (in `hash`), not by their paths: a folder moved
  // keeps its trials.
  StudyRun keyed = r.run;
  for (StudyOverride& o : keyed.overrides) {
    if (o.text.find(".device={csv=") != std::string::npos) o.text = o.text.substr(0, o.text.find('=')) + "=hand";
  }
  r.key = hex64(fnv1a64(hash, studyRunKey(binary, keyed)));
  return r;
}

}  // namespace

int runExperiment(const ExperimentDesc& e, const ExperimentOptions& options) {
  const std::vector<Trial> trials = planTrials(e);
  const std::string binary = fileFnv1a64(options.godfinger);
  // Each task's scene once: its fingers.
  std::vector<SessionDesc> scenes;
  for (const TaskDesc& task : e.tasks) scenes.push_back(loadSceneFile(task.scene));
  std::vector<TrialRun> runs(trials.size());
  std::vector<std::size_t> todo;
  std::vector<std::string> lines;
  int kept = 0;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const Trial& t = trials[i];
    runs[i] = prepareTrial(e, t, scenes[static_cast<std::size_t>(t.task)].scene, options.out, binary);
    const TrialRun& r = runs[i];
    if (!options.restart && runFinishedWith(r.dir, r.key)) {
      ++kept;
      continue;
    }
    forgetFinishedRun(r.dir);
    todo.push_back(i);
    std::vector<std::string> arguments = runArguments(r.run);
    arguments.push_back("--quiet");
    lines.push_back(godfingerRunLine(options.godfinger, r.run.scene, r.dir, arguments));
  }
  if (kept > 0) std::fprintf(stderr, "godfinger experiment: %d of %zu trials finished before; running the other %zu\n", kept, trials.size(), lines.size());
  const bool stopped = options.stop_after > 0 && lines.size() > static_cast<std::size_t>(options.stop_after);
  if (stopped) lines.resize(static_cast<std::size_t>(options.stop_after));
  const auto start = std::chrono::steady_clock::now();
  std::size_t finished = 0;
  std::map<std::size_t, int> exit_codes;
  const bool interrupted = runJobs(lines, options.jobs, [&](std::size_t k, int code) {
    const std::size_t i = todo[k];
    ++finished;
    exit_codes[i] = code;
    if (code == 0) recordFinishedRun(runs[i].dir, runs[i].key);
    if (options.progress && (finished % 10 == 0 || finished == lines.size())) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double eta = elapsed / static_cast<double>(finished) * static_cast<double>(lines.size() - finished);
      std::fprintf(stderr, "[experiment] %s: %zu / %zu trials, %s elapsed, ETA %s\n", e.name.c_str(), finished, lines.size(),
                   formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
    }
  });
  // Every trial that finished, now or before, is judged; the others are left out of the tables.
  std::vector<std::optional<TrialOutcome>> outcomes(trials.size());
  int failed_runs = 0;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const auto code = exit_codes.find(i);
    const bool finished_before = code == exit_codes.end() && runFinishedWith(runs[i].dir, runs[i].key);
    if (code == exit_codes.end() && !finished_before) continue;
    const int exit_code = finished_before ? 0 : code->second;
    if (interrupted && exit_code != 0) continue;  // stopped by the signal: it runs again on resume
    failed_runs += exit_code != 0;
    outcomes[i] = judgeTrial(e.tasks[static_cast<std::size_t>(trials[i].task)].goal, runs[i].fingers, runs[i].dir, exit_code);
  }
  writeDatasetFiles(e, options.out);
  for (int p = 0; p < e.participants; ++p) writeParticipantTable(e, options.out, p, trials, runs, outcomes);
  printSummary(e, trials, outcomes);
  reportExperiment(options.out);
  std::fprintf(stderr, "godfinger experiment: wrote %s/ (report.md, participants.tsv, sub-*/beh/)\n", options.out.c_str());
  if (interrupted) std::fprintf(stderr, "godfinger experiment: interrupted; the trials that finished are in the tables\n");
  if (stopped) std::fprintf(stderr, "godfinger experiment: stopped after %d trials (--stop-after); run again to resume\n", options.stop_after);
  if (interrupted || stopped) return 130;
  if (failed_runs > 0) {
    std::fprintf(stderr, "godfinger experiment: %d trial runs failed (their run.log says why; success n/a, left out of the report)\n",
                 failed_runs);
  }
  return failed_runs == 0 ? 0 : 1;
}

}  // namespace gf::app

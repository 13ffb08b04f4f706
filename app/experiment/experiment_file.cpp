// Experiment and task files: reading and checking them (assets/experiments/README.md).
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

#include "app/experiment/experiment.hpp"
#include "app/experiment/outcome.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/scene/toml_reader.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

constexpr const char* kOrderKinds[] = {"williams", "latin", "fixed"};

toml::table parseToml(const std::string& text, const std::string& source_name) {
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw InputError(source_name, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column), "",
                     std::string(e.description()));
  }
}

std::string readText(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, 0, "", "cannot open the " + what);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

StudySource sourceOfNode(const toml::node& n, const std::string& field) {
  return {static_cast<int>(n.source().begin.line), static_cast<int>(n.source().begin.column), field};
}

// A name used in folder names and table columns: letters, digits, '-' and '_'.
void checkName(Reader& r, const std::string& key, const std::string& name) {
  const bool fine = !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
  });
  if (!fine) r.fail(r.nodeOf(key), key, "'" + name + "': expected 1 to 64 letters, digits, '-' or '_'");
}

TaskGoal readGoal(Reader& r) {
  TaskGoal g;
  g.body = r.string("body", "");
  if (g.body.empty()) r.fail(nullptr, "body", "missing: the dynamic body the goal is about");
  if (const std::optional<std::pair<sim::Vec3, sim::Vec3>> zone = r.box("zone")) {
    std::tie(g.zone_min, g.zone_max) = *zone;
    g.has_zone = true;
  }
  if (r.has("orientation") || r.has("rotation")) g.orientation = r.orientation(sim::Quat::Identity());
  g.orientation_tolerance_deg = r.number("orientation_tolerance_deg", g.orientation_tolerance_deg, 0.1, 180.0);
  g.hold = r.number("hold", g.hold, 0.0, 60.0);
  g.released = r.boolean("released", g.released);
  if (r.has("max_tilt_deg")) g.max_tilt_deg = r.number("max_tilt_deg", 0.0, 0.0, 180.0);
  if (r.has("max_roll_ratio")) {
    g.max_roll_ratio = r.number("max_roll_ratio", 0.0, 0.0, 10.0);
    g.roll_radius = r.requiredNumber("roll_radius", 1e-4, 10.0);
  }
  if (!g.has_zone && !g.orientation) r.fail(nullptr, "zone", "missing: a goal needs a zone, an orientation (or rotation) or both");
  r.finish();
  return g;
}

TaskDesc parseTask(const std::string& text, const std::string& path) {
  toml::table root = parseToml(text, path);
  Reader r(root, "", path);
  TaskDesc t;
  t.source = path;
  t.name = r.string("name", fs::path(path).stem().string());
  checkName(r, "name", t.name);
  t.instruction = r.string("instruction", "");
  if (t.instruction.empty()) r.fail(nullptr, "instruction", "missing: what the participant is asked to do");
  const std::string scene = r.string("scene", "");
  if (scene.empty()) r.fail(nullptr, "scene", "missing: the task's scene file");
  try {
    t.scene = resolveSceneIn(fs::path(path).parent_path().string(), scene);
  } catch (const InputError& e) {
    r.fail(r.nodeOf("scene"), "scene", e.reason());
  }
  t.time_limit = r.requiredNumber("time_limit", 0.1, 600.0);
  const toml::node* goal = r.find("goal");
  if (!goal || !goal->is_table()) r.fail(goal, "goal", "missing: the [goal] table");
  Reader gr(*goal->as_table(), "goal", path);
  t.goal = readGoal(gr);
  const toml::node* grip = r.find("grip");
  if (grip && !grip->is_table()) r.fail(grip, "grip", std::string("expected a table FINGER = [x, y, z], got ") + typeName(*grip));
  std::optional<Reader> grip_reader;
  if (grip) {
    grip_reader.emplace(*grip->as_table(), "grip", path);
    for (const auto& [key, value] : *grip->as_table()) {
      const std::string finger(key.str());
      const sim::Vec3 d = grip_reader->vec3(finger, sim::Vec3::Zero());
      if (!(d.norm() > 0.0)) grip_reader->fail(&value, finger, "must not be zero: the direction a squeeze moves the finger");
      t.grip.emplace_back(finger, d.normalized());
    }
    grip_reader->finish();
  }
  r.finish();
  // The scene: its goal body dynamic, its gripping fingers there, its fingers scripted.
  const SessionDesc s = loadSceneFile(t.scene);
  const auto body = std::find_if(s.scene.bodies.begin(), s.scene.bodies.end(),
                                 [&](const sim::BodyDesc& b) { return b.name == t.goal.body; });
  if (body == s.scene.bodies.end() || body->mass <= 0.0) {
    gr.fail(gr.nodeOf("body"), "body", "'" + t.goal.body + "' is no dynamic body of " + t.scene);
  }
  for (const auto& grip_of : t.grip) {
    const std::string& finger = grip_of.first;
    const bool there = std::any_of(s.scene.fingers.begin(), s.scene.fingers.end(),
                                   [&](const sim::FingerDesc& f) { return f.name == finger; });
    if (!there) grip_reader->fail(grip_reader->nodeOf(finger), finger, "no finger '" + finger + "' in " + t.scene);
  }
  if (s.scene.fingers.empty()) r.fail(r.nodeOf("scene"), "scene", t.scene + " has no finger");
  for (const sim::FingerDesc& f : s.scene.fingers) {
    if (f.device.keyframes.empty()) {
      r.fail(r.nodeOf("scene"), "scene", "finger '" + f.name + "' of " + t.scene + " has no keyframes: a simulated hand moves along them");
    }
  }
  return t;
}


// "ease-of-manipulation" -> "easeofmanipulation": BIDS labels are letters and digits.
std::string bidsLabel(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += c;
  }
  return out;
}

std::string resolveTask(const std::string& base_dir, const std::string& task) {
  const fs::path p = fs::path(base_dir) / task;
  if (fs::is_regular_file(p)) return fs::absolute(p).lexically_normal().string();
  const fs::path bundled = fs::path(bundledExperimentDir()) / "tasks" / (task + ".toml");
  if (task.find('/') == std::string::npos && fs::is_regular_file(bundled)) return fs::absolute(bundled).string();
  throw InputError(p.string(), 0, 0, "", "no such task file, and no bundled task of that name (assets/experiments/tasks)");
}

std::vector<ExperimentLevel> readLevels(Reader& r) {
  std::vector<ExperimentLevel> out;
  for (const auto& [key, t] : r.arrayTables("levels", ": the factor's levels", true)) {
    Reader lr(*t, r.field(key), r.file());
    ExperimentLevel level;
    level.name = lr.string("name", "");
    checkName(lr, "name", level.name);
    for (const ExperimentLevel& other : out) {
      if (other.name == level.name) lr.fail(lr.nodeOf("name"), "name", "'" + level.name + "' is already a level");
    }
    const auto items = lr.strings("set");
    for (std::size_t i = 0; i < items.size(); ++i) {
      const std::string& text = items[i].first;
      const std::size_t eq = text.find('=');
      if (eq == std::string::npos || eq == 0) lr.fail(items[i].second, "set", "expected \"FIELD=VALUE\", got '" + text + "'");
      level.set.push_back({text, sourceOfNode(*items[i].second, lr.field("set") + "." + std::to_string(i)), {}});
    }
    if (lr.has("noise")) level.noise = lr.number("noise", 1.0, 0.0, 10.0);
    if (level.set.empty() && !level.noise) lr.fail(nullptr, "set", "missing: a level sets scene fields (set), the hand's noise (noise) or both");
    lr.finish();
    out.push_back(std::move(level));
  }
  return out;
}

// Fields a trial sets itself (the hand's tracks, the time limit, the trace's rate): a level may
// not set them.
bool trialOwned(const std::string& field) {
  const bool device = field.starts_with("fingers.") && (field.find(".device") != std::string::npos);
  return device || field == "duration" || field.starts_with("record.trace_rate");
}

// Every condition a trial runs in (each task under each combination of levels the plan makes),
// loaded as the trial loads it (the hand's tracks a placeholder): a bad override is named where
// its level gave it, and a level may not set what a trial sets.
void checkConditions(const ExperimentDesc& e) {
  const fs::path placeholder = fs::temp_directory_path() / ("gf-experiment-check-" + std::to_string(::getpid()) + ".csv");
  std::ofstream(placeholder) << "t,x,y,z\n0,0,0,0\n";
  struct Remove {
    fs::path p;
    ~Remove() {
      std::error_code ec;
      fs::remove(p, ec);
    }
  } remove{placeholder};
  for (const ExperimentFactor& factor : e.factors) {
    for (const ExperimentLevel& level : factor.levels) {
      for (const StudyOverride& o : level.set) {
        const std::string field = o.text.substr(0, o.text.find('='));
        if (trialOwned(field.starts_with("fingers.*.") ? "fingers.x." + field.substr(10) : field)) {
          throw InputError(e.source, o.source.line, o.source.column, o.source.field,
                           "'" + o.text + "': a trial sets its fingers' devices (the hand), its duration (the task's time limit) "
                           "and its trace's rate itself");
        }
      }
    }
  }
  std::set<std::pair<int, std::vector<int>>> seen;
  std::vector<std::vector<std::string>> fingers(e.tasks.size());
  std::vector<std::vector<sim::FingerDesc>> descs(e.tasks.size());
  for (std::size_t t = 0; t < e.tasks.size(); ++t) {
    descs[t] = loadSceneFile(e.tasks[t].scene).scene.fingers;
    for (const sim::FingerDesc& f : descs[t]) fingers[t].push_back(f.name);
  }
  for (const Trial& trial : planTrials(e)) {
    if (!seen.insert({trial.task, trial.levels}).second) continue;
    const TaskDesc& task = e.tasks[static_cast<std::size_t>(trial.task)];
    std::vector<StudyOverride> overrides;
    const std::vector<sim::FingerDesc>& task_fingers = descs[static_cast<std::size_t>(trial.task)];
    for (std::size_t f = 0; f < task_fingers.size(); ++f) {
      if (e.device == "simulated") {
        overrides.push_back({"fingers." + task_fingers[f].name + ".device={csv=\"" + placeholder.string() + "\"}", {}, {}});
      } else {  // a person's device (its address checked with the file)
        overrides.push_back({participantDeviceOverride(e, task_fingers[f], static_cast<int>(f)), {}, {}});
      }
    }
    for (std::size_t f = 0; f < e.factors.size(); ++f) {
      for (const StudyOverride& o : e.factors[f].levels[static_cast<std::size_t>(trial.levels[f])].set) {
        for (const std::string& text : expandFingers(o.text, fingers[static_cast<std::size_t>(trial.task)])) {
          overrides.push_back({text, o.source, o.source});
        }
      }
    }
    for (const std::string& o : goalTargetOverrides(task.goal)) overrides.push_back({o, {}, {}});
    overrides.push_back({"duration=" + sim::numberText(task.time_limit), {}, {}});
    loadSceneWithOverrides(e.source, task.scene, overrides);
  }
}

}  // namespace

std::vector<std::string> expandFingers(const std::string& text, const std::vector<std::string>& fingers) {
  constexpr std::string_view kAll = "fingers.*.";
  if (!text.starts_with(kAll)) return {text};
  std::vector<std::string> out;
  for (const std::string& f : fingers) out.push_back("fingers." + f + "." + text.substr(kAll.size()));
  return out;
}

std::string bundledExperimentDir() {
  if (const char* env = std::getenv("GODFINGER_EXPERIMENTS"); env && *env) return env;
  return (fs::path(bundledSceneDir()).parent_path() / "experiments").string();
}

TaskDesc loadTaskFile(const std::string& path) { return parseTask(readText(path, "task file"), path); }

ExperimentDesc loadExperimentFile(const std::string& name_or_path) {
  const std::string path = resolveBundledFile(name_or_path, bundledExperimentDir(), "experiment", "assets/experiments");
  return parseExperimentText(readText(path, "experiment file"), path, fs::path(path).parent_path().string());
}

// `device` and, for a UDP participant, `udp`: its address checked as a scene's `udp` is.
void readDevice(Reader& r, ExperimentDesc& e) {
  static constexpr const char* kDevices[] = {"simulated", "web", "udp"};
  e.device = kDevices[r.choice("device", kDevices, 0)];
  const toml::node* n = r.find("udp");
  if (!n) return;
  if (e.device != "udp") r.fail(n, "udp", "the address of a UDP participant's device: only with device = \"udp\"");
  e.udp = r.string("udp", e.udp);
  e.udp_source = sourceOfNode(*n, "udp");
  std::string quoted;  // a TOML basic string
  for (const char c : e.udp) quoted += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  try {
    parseSceneText("duration = 1\neffects = []\n[bodies.ground]\nshape = \"plane\"\n[fingers.f.device]\nudp = \"" + quoted + "\"\n",
                   "udp", "", {});
  } catch (const InputError& error) {
    r.fail(n, "udp", error.reason());
  }
}

ExperimentDesc parseExperimentText(const std::string& text, const std::string& source_name, const std::string& base_dir) {
  toml::table root = parseToml(text, source_name);
  Reader r(root, "", source_name);
  ExperimentDesc e;
  e.source = source_name;
  e.name = r.string("name", fs::path(source_name).stem().string());
  checkName(r, "name", e.name);
  e.task_label = bidsLabel(e.name);
  if (e.task_label.empty()) r.fail(r.nodeOf("name"), "name", "needs a letter or a digit (the BIDS task label)");
  e.summary = r.string("summary", "");
  e.participants = r.integer("participants", e.participants, 1, 99);
  e.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, 2147483647));
  e.noise = r.number("noise", e.noise, 0.0, 10.0);
  readDevice(r, e);
  for (const auto& [task, node] : r.strings("tasks")) {
    try {
      e.tasks.push_back(loadTaskFile(resolveTask(base_dir, task)));
    } catch (const InputError& err) {
      if (!err.file().empty() && err.line() > 0) throw;  // the task file's own error
      r.fail(node, "tasks", err.reason());
    }
    for (std::size_t i = 0; i + 1 < e.tasks.size(); ++i) {
      if (e.tasks[i].name == e.tasks.back().name) r.fail(node, "tasks", "task '" + e.tasks.back().name + "' is listed twice");
    }
  }
  if (e.tasks.empty()) r.fail(r.nodeOf("tasks"), "tasks", "missing: the list of task files (or bundled task names)");
  for (const auto& [key, t] : r.arrayTables("factors", ": the conditions compared", true)) {
    Reader fr(*t, key, source_name);
    ExperimentFactor f;
    f.source = sourceOfNode(*t, key);
    f.name = fr.string("name", "");
    checkName(fr, "name", f.name);
    for (const ExperimentFactor& other : e.factors) {
      if (other.name == f.name) fr.fail(fr.nodeOf("name"), "name", "'" + f.name + "' is already a factor");
    }
    // The columns of the trial tables and participants.tsv.
    static constexpr const char* kReserved[] = {"trial", "block", "practice", "task", "success", "completion_time",
                                                "failure", "max_tilt", "roll_ratio", "end_distance", "end_angle",
                                                "peak_force", "time_limit", "run", "participant_id", "block_order",
                                                "reaction_time", "pace", "endpoint_sd", "tremor_rms", "grip_sd"};
    for (const char* word : kReserved) {
      if (f.name == word) fr.fail(fr.nodeOf("name"), "name", "'" + f.name + "' names a column of the trials' table");
    }
    f.within = fr.boolean("within", true);
    f.levels = readLevels(fr);
    fr.finish();
    e.factors.push_back(std::move(f));
  }
  const toml::node* design = r.find("design");
  if (design && !design->is_table()) r.fail(design, "design", std::string("expected a table, got ") + typeName(*design));
  if (design) {
    Reader dr(*design->as_table(), "design", source_name);
    e.order = static_cast<OrderKind>(dr.choice("order", kOrderKinds, 0));
    e.block_by = dr.string("block_by", "");
    e.repetitions = dr.integer("repetitions", e.repetitions, 1, 100);
    e.practice = dr.integer("practice", e.practice, 0, 100);
    e.shuffle = dr.boolean("shuffle", e.shuffle);
    if (!e.block_by.empty()) {
      const auto f = std::find_if(e.factors.begin(), e.factors.end(), [&](const ExperimentFactor& x) { return x.name == e.block_by; });
      if (f == e.factors.end() || !f->within) dr.fail(dr.nodeOf("block_by"), "block_by", "'" + e.block_by + "' is no within factor");
    }
    dr.finish();
  }
  r.finish();
  const std::size_t trials = trialCount(e);
  if (trials > 10000) r.fail(r.nodeOf("participants"), "participants", "the design makes " + std::to_string(trials) + " trials, more than 10000");
  int groups = 1;
  for (const ExperimentFactor& f : e.factors) groups *= f.within ? 1 : static_cast<int>(f.levels.size());
  if (e.participants % groups != 0) {
    r.fail(r.nodeOf("participants"), "participants",
           std::to_string(e.participants) + " participants do not fill the " + std::to_string(groups) +
               " between-participant groups equally: give a multiple of " + std::to_string(groups));
  }
  checkConditions(e);
  return e;
}

}  // namespace gf::app

// Experiments (app/experiment/): counterbalanced orders, the trial plan, the simulated hand
// against its closed forms, the files' errors, and whole experiments run, interrupted and
// resumed (trials judged against their goals: outcome_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "app/experiment/experiment.hpp"
#include "app/experiment/hand.hpp"
#include "app/experiment/outcome.hpp"
#include "app/scene/input_error.hpp"
#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using sim::Vec3;
using test::exitStatus;
using test::freshFolder;
using test::kBin;
using test::readFile;

const std::string kTasks = std::string(GF_SOURCE_DIR) + "/assets/experiments/tasks/";

// ---- orders ----

// Over n participants a Latin square puts every level at every position once.
TEST(ExperimentOrder, LatinSquarePutsEveryLevelAtEveryPositionOnce) {
  for (int n = 2; n <= 5; ++n) {
    std::map<std::pair<int, int>, int> at;  // (position, level) -> count
    for (int p = 0; p < n; ++p) {
      const std::vector<int> order = levelOrder(OrderKind::kLatin, n, p);
      ASSERT_EQ(std::set<int>(order.begin(), order.end()).size(), static_cast<std::size_t>(n));
      for (int j = 0; j < n; ++j) ++at[{j, order[static_cast<std::size_t>(j)]}];
    }
    EXPECT_EQ(at.size(), static_cast<std::size_t>(n * n));
    for (const auto& [key, count] : at) EXPECT_EQ(count, 1) << "n " << n;
  }
}

// Williams: over its rows (n for an even n, 2n for an odd one) every level is at every position
// equally often and follows every other level equally often (first-order carry-over balanced).
TEST(ExperimentOrder, WilliamsBalancesPositionsAndWhatFollowsWhat) {
  for (int n = 2; n <= 6; ++n) {
    const int rows = n % 2 == 0 ? n : 2 * n;
    std::map<std::pair<int, int>, int> position, follows;
    for (int p = 0; p < rows; ++p) {
      const std::vector<int> order = levelOrder(OrderKind::kWilliams, n, p);
      ASSERT_EQ(std::set<int>(order.begin(), order.end()).size(), static_cast<std::size_t>(n)) << "n " << n << " row " << p;
      for (int j = 0; j < n; ++j) ++position[{j, order[static_cast<std::size_t>(j)]}];
      for (int j = 0; j + 1 < n; ++j) ++follows[{order[static_cast<std::size_t>(j)], order[static_cast<std::size_t>(j + 1)]}];
      EXPECT_EQ(levelOrder(OrderKind::kWilliams, n, p + rows), order) << "the rows repeat";
    }
    for (const auto& [key, count] : position) EXPECT_EQ(count, rows / n) << "n " << n;
    EXPECT_EQ(follows.size(), static_cast<std::size_t>(n * (n - 1))) << "every ordered pair occurs, n " << n;
    for (const auto& [key, count] : follows) EXPECT_EQ(count, rows / n) << "n " << n;
  }
  EXPECT_EQ(levelOrder(OrderKind::kFixed, 3, 5), (std::vector<int>{0, 1, 2}));
}

// ---- the plan ----

ExperimentDesc smallDesign() {
  ExperimentDesc e;
  e.participants = 6;
  e.practice = 2;
  e.repetitions = 2;
  e.block_by = "model";
  e.tasks.resize(3);
  for (int i = 0; i < 3; ++i) e.tasks[static_cast<std::size_t>(i)].name = "task" + std::to_string(i);
  e.factors.push_back({"model", true, {{"a", {}, {}}, {"b", {}, {}}, {"c", {}, {}}}, {}});
  e.factors.push_back({"size", true, {{"small", {}, {}}, {"large", {}, {}}}, {}});
  e.factors.push_back({"group", false, {{"g1", {}, {}}, {"g2", {}, {}}}, {}});
  return e;
}

// Every participant meets every task under every within condition `repetitions` times in test
// trials, one blocked level a block in the Williams order, a between level by participant number,
// and the practice trials first in each block.
TEST(ExperimentPlan, EveryParticipantMeetsEveryConditionInBlocks) {
  const ExperimentDesc e = smallDesign();
  const std::vector<Trial> trials = planTrials(e);
  const std::size_t per_block = 3 * 2 * 2;  // tasks x sizes x repetitions
  ASSERT_EQ(trials.size(), static_cast<std::size_t>(e.participants) * 3 * (per_block + 2));
  std::map<int, int> group_count;
  for (int p = 0; p < e.participants; ++p) {
    std::map<std::tuple<int, int, int>, int> met;  // (task, model, size) -> test trials
    int number = 0, group = -1;
    const std::vector<int> order = levelOrder(OrderKind::kWilliams, 3, p / 2);  // two between groups
    for (const Trial& t : trials) {
      if (t.participant != p) continue;
      EXPECT_EQ(t.number, ++number);
      EXPECT_EQ(t.levels[0], order[static_cast<std::size_t>(t.block - 1)]) << "the block's model";
      if (group < 0) group = t.levels[2];
      EXPECT_EQ(t.levels[2], group) << "a between factor stays";
      const int in_block = (t.number - 1) % static_cast<int>(per_block + 2);
      EXPECT_EQ(t.practice, in_block < 2) << "practice first in each block";
      if (!t.practice) ++met[{t.task, t.levels[0], t.levels[1]}];
    }
    EXPECT_EQ(met.size(), 3u * 3u * 2u);
    for (const auto& [key, count] : met) EXPECT_EQ(count, 2);
    EXPECT_EQ(group, p % 2);
    ++group_count[group];
  }
  EXPECT_EQ(group_count[0], group_count[1]);
  // The plan is a function of the file: the same twice; a trial's hand noise has its own seed.
  const std::vector<Trial> again = planTrials(e);
  std::set<std::uint64_t> seeds;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    EXPECT_EQ(again[i].task, trials[i].task);
    EXPECT_EQ(again[i].levels, trials[i].levels);
    EXPECT_EQ(again[i].seed, trials[i].seed);
    seeds.insert(trials[i].seed);
  }
  EXPECT_EQ(seeds.size(), trials.size());
}

// Each between group is counterbalanced on its own: two groups of six meet the three blocked
// levels in the six Williams rows each (every level opens a block twice per group).
TEST(ExperimentPlan, EachBetweenGroupIsCounterbalancedOnItsOwn) {
  ExperimentDesc e = smallDesign();
  e.participants = 12;
  e.practice = 0;
  EXPECT_EQ(trialCount(e), planTrials(e).size());
  std::map<std::pair<int, int>, int> opens;  // (group, first block's model) -> participants
  for (const Trial& t : planTrials(e)) {
    if (t.number == 1) ++opens[{t.levels[2], t.levels[0]}];
  }
  ASSERT_EQ(opens.size(), 6u);
  for (const auto& [key, count] : opens) EXPECT_EQ(count, 2) << "group " << key.first << " model " << key.second;
}

TEST(ExperimentPlan, FingerWildcardsExpandOverTheScenesFingers) {
  EXPECT_EQ(expandFingers("fingers.*.n_sgo=0", {"left", "right"}),
            (std::vector<std::string>{"fingers.left.n_sgo=0", "fingers.right.n_sgo=0"}));
  EXPECT_EQ(expandFingers("world.solver_iterations=20", {"left"}), (std::vector<std::string>{"world.solver_iterations=20"}));
}

// ---- the hand ----

sim::FingerDesc scriptedFinger(const std::vector<std::pair<double, Vec3>>& keys) {
  sim::FingerDesc f;
  f.name = "index";
  for (const auto& [t, p] : keys) f.device.keyframes.push_back({t, p, sim::Quat::Identity()});
  return f;
}

Vec3 rowPosition(const std::vector<double>& row) { return {row[1], row[2], row[3]}; }

// Without noise the hand passes through the scripted waypoints at their times, at rest there, and
// between two of them moves on a minimum-jerk profile: its peak speed is 15/8 of the mean, at the
// middle (Flash & Hogan 1985).
TEST(ExperimentHand, WithoutNoiseItIsTheScriptOnMinimumJerkSegments) {
  const sim::FingerDesc f = scriptedFinger({{0.0, Vec3(0, 0.02, 0)}, {1.0, Vec3(0, 0.02, 0)}, {3.0, Vec3(0.1, 0.02, 0)}});
  const HandParams hand = drawHand(7, 0, 0.0);
  EXPECT_EQ(hand.reaction_s, 0.0);
  EXPECT_EQ(hand.speed, 1.0);
  const std::vector<HandTrack> tracks = moveHand({f}, {}, hand, 42, 0.0, 4.0, 1000.0);
  ASSERT_EQ(tracks.size(), 1u);
  const auto& rows = tracks[0].rows;
  ASSERT_EQ(rows.size(), 4001u);
  EXPECT_NEAR((rowPosition(rows[1000]) - Vec3(0, 0.02, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rowPosition(rows[3000]) - Vec3(0.1, 0.02, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rowPosition(rows[4000]) - Vec3(0.1, 0.02, 0)).norm(), 0.0, 1e-12);
  double peak = 0.0, peak_t = 0.0;
  for (std::size_t i = 1000; i < 3000; ++i) {
    const double v = (rowPosition(rows[i + 1]) - rowPosition(rows[i])).norm() * 1000.0;
    if (v > peak) {
      peak = v;
      peak_t = rows[i][0] + 0.0005;
    }
  }
  EXPECT_NEAR(peak, 15.0 / 8.0 * 0.1 / 2.0, 1e-4) << "m/s";
  EXPECT_NEAR(peak_t, 2.0, 1e-3);
  EXPECT_LT((rowPosition(rows[1001]) - rowPosition(rows[1000])).norm() * 1000.0, 1e-6) << "at rest at a waypoint";
}

// The tremor's RMS per axis is the population's times the noise and the participant's
// steadiness; the same seed gives the same track, another seed another.
TEST(ExperimentHand, TremorHasItsRmsAndSeedsRepeat) {
  const sim::FingerDesc f = scriptedFinger({{0.0, Vec3(0, 0.05, 0)}});
  HandPopulation pop;
  pop.grip_sd_m = 0.0;
  pop.endpoint_sd_m = 0.0;
  pop.finger_sd_m = 0.0;
  const HandParams hand = drawHand(3, 1, 2.0, pop);
  const std::vector<HandTrack> a = moveHand({f}, {}, hand, 99, 2.0, 20.0, 1000.0);
  Vec3 sum = Vec3::Zero(), sq = Vec3::Zero();
  for (const auto& row : a[0].rows) {
    const Vec3 d = rowPosition(row) - Vec3(0, 0.05, 0);
    sum += d;
    sq += d.cwiseProduct(d);
  }
  const double n = static_cast<double>(a[0].rows.size());
  for (int axis = 0; axis < 3; ++axis) {
    const double rms = std::sqrt(sq[axis] / n - (sum[axis] / n) * (sum[axis] / n));
    // Four sinusoids of random frequency: their sum's RMS over 20 s is the nominal within 10 %.
    EXPECT_NEAR(rms / hand.tremor_rms_m, 1.0, 0.1) << "axis " << axis;
  }
  const std::vector<HandTrack> again = moveHand({f}, {}, hand, 99, 2.0, 20.0, 1000.0);
  const std::vector<HandTrack> other = moveHand({f}, {}, hand, 100, 2.0, 20.0, 1000.0);
  EXPECT_EQ(again[0].rows, a[0].rows);
  EXPECT_NE(other[0].rows, a[0].rows);
}

// A participant's reaction delays the start; the grip pushes along its direction only.
TEST(ExperimentHand, ReactionDelaysTheStartAndGripGoesAlongItsDirection) {
  const sim::FingerDesc f = scriptedFinger({{0.0, Vec3::Zero()}, {1.0, Vec3(0, 0.05, 0)}});
  HandPopulation pop;
  pop.tremor_rms_m = 0.0;
  pop.endpoint_sd_m = 0.0;
  pop.finger_sd_m = 0.0;
  pop.grip_sd_m = 1e-3;
  const HandParams hand = drawHand(5, 0, 1.0, pop);
  ASSERT_GT(hand.reaction_s, 0.1);
  const std::vector<HandTrack> t = moveHand({f}, {{"index", Vec3::UnitX()}}, hand, 11, 1.0, 3.0, 1000.0);
  const std::size_t before = static_cast<std::size_t>(std::floor(hand.reaction_s * 1000.0 * 0.5));
  EXPECT_EQ(t[0].rows[before][2], 0.0) << "y has not moved before the reaction";
  double largest_x = 0.0;
  for (const auto& row : t[0].rows) {
    EXPECT_EQ(row[3], 0.0) << "no grip across its direction";
    largest_x = std::max(largest_x, std::abs(row[1]));
  }
  EXPECT_GT(largest_x, 1e-5) << "the grip moves along x";
  EXPECT_NEAR(t[0].rows.back()[2], 0.05, 1e-12);
}

// ---- files ----

fs::path writeFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path;
}

// What loading the experiment `text` throws ("file:line:column: field: reason"), or "loaded".
std::string experimentError(const std::string& text) {
  const fs::path dir = freshFolder("experiment-errors");
  const fs::path p = writeFile(dir / "e.toml", text);
  try {
    loadExperimentFile(p.string());
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string folder = dir.string() + "/";
    const std::size_t at = what.find(folder);
    return at == std::string::npos ? what : what.substr(0, at) + what.substr(at + folder.size());
  }
  return "loaded";
}

const std::string kModels = "[[factors]]\nname = \"model\"\nlevels = [\n"
                            "  { name = \"go\", set = [\"fingers.*.contact_model=\\\"god_object\\\"\"] },\n"
                            "  { name = \"gf\", set = [\"fingers.*.contact_model=\\\"god_finger\\\"\"] },\n]\n";

TEST(ExperimentFile, ErrorsNameTheFileLineAndField) {
  const std::string tasks = "tasks = [\"" + kTasks + "push-no-roll.toml\"]\n";
  const auto expectError = [](const std::string& text, const std::string& expected) {
    const std::string said = experimentError(text);
    EXPECT_NE(said.find(expected), std::string::npos) << said;
  };
  EXPECT_EQ(experimentError(tasks + kModels), "loaded");
  expectError(tasks + "colour = 3\n" + kModels, "e.toml:2:10: colour: unknown field");
  expectError(tasks + "participants = 0\n" + kModels, "e.toml:2:16: participants: must be in 1..99");
  expectError(tasks + "device = \"glove\"\n" + kModels, "e.toml:2:10: device: unknown value 'glove' (one of simulated, web, udp)");
  EXPECT_EQ(experimentError(tasks + "device = \"web\"\n" + kModels), "loaded");
  EXPECT_EQ(experimentError(tasks + "device = \"udp\"\nudp = \"127.0.0.1:47005\"\n" + kModels), "loaded");
  expectError(tasks + "udp = \"127.0.0.1:47005\"\n" + kModels, "e.toml:2:7: udp: the address of a UDP participant's device: only with");
  expectError(tasks + "device = \"udp\"\nudp = \"127.0.0.1:99999\"\n" + kModels,
              "e.toml:3:7: udp: the port must be a whole number in 0..65535");  // as a scene's udp
  expectError(tasks + kModels + "[design]\nblock_by = \"size\"\n", "e.toml:9:12: design.block_by: 'size' is no within factor");
  expectError(tasks, "e.toml:1:1: factors: missing");
  expectError("tasks = [\"no-such-task\"]\n" + kModels, "e.toml:1:10: tasks: no such task file");
  // A level's override the task scene refuses is named at the level's line.
  expectError(tasks + "[[factors]]\nname = \"model\"\nlevels = [\n  { name = \"x\", set = [\"fingers.*.contact_model=\\\"rubber\\\"\"] },\n]\n",
              "e.toml:5:");
  expectError(tasks + "[[factors]]\nname = \"task\"\nlevels = [{ name = \"x\", noise = 1 }]\n",
              "e.toml:3:8: factors.0.name: 'task' names a column of the trials' table");
  expectError(tasks + "[[factors]]\nname = \"m\"\nlevels = [{ name = \"x\" }]\n", "factors.0.levels.0.set: missing");
  expectError(tasks + "[[factors]]\nname = \"peak_force\"\nlevels = [{ name = \"x\", noise = 1 }]\n",
              "factors.0.name: 'peak_force' names a column");
  expectError(tasks + "[[factors]]\nname = \"m\"\nlevels = [{ name = \"x\", set = [\"duration=9\"] }]\n",
              "e.toml:4:32: factors.0.levels.0.set.0: 'duration=9': a trial sets");
  expectError(tasks + "[[factors]]\nname = \"m\"\nlevels = [{ name = \"x\", set = [\"fingers.*.device.csv=\\\"a.csv\\\"\"] }]\n",
              "a trial sets its fingers' devices");
  expectError(tasks + "participants = 3\n[[factors]]\nname = \"g\"\nwithin = false\nlevels = [{ name = \"a\", noise = 1 }, { name = \"b\", noise = 2 }]\n",
              "e.toml:2:16: participants: 3 participants do not fill the 2 between-participant groups");
  expectError(tasks + "participants = 99\n[design]\nrepetitions = 100\n" + kModels, "more than 10000");
}

TEST(ExperimentFile, TaskErrorsNameTheTaskFile) {
  const fs::path dir = freshFolder("experiment-task-errors");
  const std::string scene = kTasks + "push-no-roll.scene.toml";
  const auto taskError = [&](const std::string& text) {
    const fs::path p = writeFile(dir / "t.toml", text);
    try {
      loadTaskFile(p.string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  const std::string head = "instruction = \"push\"\nscene = \"" + scene + "\"\ntime_limit = 3\n";
  EXPECT_EQ(taskError(head + "[goal]\nbody = \"ball\"\nzone = { min = [0, 0, 0], max = [1, 1, 1] }\n"), "loaded");
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ground\"\nzone = { min = [0, 0, 0], max = [1, 1, 1] }\n")
                .find("t.toml:5:8: goal.body: 'ground' is no dynamic body"),
            std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\nzone = { min = [0, 0, 0], max = [1, 0, 1] }\n").find("goal.zone.max: every coordinate"),
            std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\n").find("goal.zone: missing"), std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\norientation = [0, 0, 0, 0]\n").find("goal.orientation: quaternion has zero length"),
            std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\norientation = [0, 0, 0, 1]\nrotation = [0, 45, 0]\n")
                .find("goal.rotation: give either orientation or rotation"),
            std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\nzone = { min = [0, 0, 0], max = [1, 1, 1] }\n[grip]\nthumb = [1, 0, 0]\n")
                .find("grip.thumb: no finger 'thumb'"),
            std::string::npos);
  EXPECT_NE(taskError(head + "[goal]\nbody = \"ball\"\nzone = { min = [0, 0, 0], max = [1, 1, 1] }\n[grip]\nindex = [0, 0, 0]\n")
                .find("grip.index: must not be zero"),
            std::string::npos);
}

// ---- whole experiments ----

// A TSV file: its header's names and every row's cells.
struct Tsv {
  std::vector<std::string> names;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  }
};

Tsv readTsv(const fs::path& path) {
  Tsv t;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    for (std::size_t at = 0;;) {
      const std::size_t end = line.find('\t', at);
      cells.push_back(line.substr(at, end == std::string::npos ? std::string::npos : end - at));
      if (end == std::string::npos) break;
      at = end + 1;
    }
    if (t.names.empty()) t.names = cells;
    else t.rows.push_back(cells);
  }
  return t;
}

// The bundled battery by one steady hand (noise 0: the scripted waypoints at their times): the god-finger
// does every task; a god-object's single points drop the tile (Fig. 6), let the pinched cylinder
// swing (Fig. 8) and roll the ball (Fig. 5); the docking push turns the box under both.
// One steady participant (noise 0) doing `tasks` (TOML list items) under the two models: the
// trial table of the experiment `name`.
Tsv steadyHand(const std::string& name, const std::string& tasks) {
  const fs::path dir = freshFolder("experiment-" + name);
  const fs::path file = writeFile(dir / (name + ".toml"), "participants = 1\nnoise = 0.0\ntasks = [" + tasks + "]\n[design]\n"
                                                                                                   "block_by = \"model\"\n" + kModels);
  const int status = exitStatus(kBin + " experiment " + file.string() + " --jobs 2 --out " + (dir / "out").string() + " > " +
                                (dir / "said.txt").string() + " 2>&1");
  EXPECT_EQ(status, 0) << readFile(dir / "said.txt");
  return readTsv(dir / "out/sub-01/beh" / ("sub-01_task-" + name + "_beh.tsv"));
}

TEST(ExperimentRun, TheBatteryByASteadyHandSeparatesTheModelsWhereThePaperSays) {
  const Tsv rows = steadyHand("battery", "\"lift-and-hold\", \"pinch-carry\", \"push-no-roll\", \"turn-to-target\"");
  ASSERT_EQ(rows.rows.size(), 8u);
  std::map<std::string, std::string> success;  // "model task" -> success
  for (const auto& row : rows.rows) success[row[rows.column("model")] + " " + row[rows.column("task")]] = row[rows.column("success")];
  EXPECT_EQ(success["gf lift-and-hold"], "1");
  EXPECT_EQ(success["gf pinch-carry"], "1");
  EXPECT_EQ(success["gf push-no-roll"], "1");
  EXPECT_EQ(success["gf turn-to-target"], "1");
  EXPECT_EQ(success["go lift-and-hold"], "0");
  EXPECT_EQ(success["go pinch-carry"], "0");
  EXPECT_EQ(success["go push-no-roll"], "0");
  EXPECT_EQ(success["go turn-to-target"], "1");
}

// Setting down and letting go, by one steady hand: a pinch with contact areas (the god-finger's,
// or the soft finger's torsional friction about the pinch axis) carries the cylinder into the box
// and the cube onto the base upright; two points let them swing and they land upside down.
TEST(ExperimentRun, PlacingTasksNeedATorsionResistingPinch) {
  const Tsv rows = steadyHand("placing", "\"pick-and-place\", \"stack\"");
  ASSERT_EQ(rows.rows.size(), 4u);
  for (const auto& row : rows.rows) {
    const bool gf = row[rows.column("model")] == "gf";
    EXPECT_EQ(row[rows.column("success")], gf ? "1" : "0") << row[rows.column("model")] << " " << row[rows.column("task")];
    if (!gf) {
      EXPECT_GT(std::stod(row[rows.column("end_angle")]), 90.0) << "landed upside down";
    }
  }
}

// Pivoting a tile up on its edge needs no contact area: the tile's edge on the stop and one
// point under the finger already hold it (three supports with its weight between them), so the
// steady hand raises it to the goal under both models, within 0.1 s of each other (the pad's
// resistance to the face rolling on it slows the tile by a fraction of a degree).
TEST(ExperimentRun, PivotingNeedsNoContactArea) {
  const Tsv rows = steadyHand("pivoting", "\"pivot\"");
  ASSERT_EQ(rows.rows.size(), 2u);
  std::vector<double> times;
  for (const auto& row : rows.rows) {
    EXPECT_EQ(row[rows.column("success")], "1") << row[rows.column("model")];
    if (row[rows.column("success")] == "1") times.push_back(std::stod(row[rows.column("completion_time")]));
  }
  ASSERT_EQ(times.size(), 2u);
  EXPECT_NEAR(times[0], times[1], 0.1);
}

// A trial whose run crashes (the binary in its place aborts for trial 002 while a marker file
// exists) is the software's failure, not the participant's: its row says n/a, the report leaves
// it out and says so, the experiment exits 1. Run again once the crash is gone, only that trial
// runs (the other's run folder untouched), and the table equals a run that never crashed.
TEST(ExperimentRun, ACrashedTrialIsNotAFailureAndRunsAgain) {
  const fs::path dir = freshFolder("experiment-crash");
  const fs::path file = writeFile(dir / "crash.toml", "participants = 1\nnoise = 0.0\ntasks = [\"turn-to-target\"]\n"
                                                      "[design]\nblock_by = \"model\"\n" + kModels);
  const fs::path marker = writeFile(dir / "crash-now", "");
  const fs::path crashing = writeFile(dir / "crashing.sh", "#!/bin/sh\ncase \"$*\" in *trials/002*) if [ -e '" + marker.string() +
                                                               "' ]; then echo 'Aborted'; exit 134; fi;; esac\nexec '" + kBin + "' \"$@\"\n");
  fs::permissions(crashing, fs::perms::owner_all);
  const ExperimentDesc desc = loadExperimentFile(file.string());
  ExperimentOptions options;
  options.jobs = 2;
  options.progress = false;
  options.out = (dir / "out").string();
  options.godfinger = crashing.string();
  EXPECT_EQ(runExperiment(desc, options), 1);
  const fs::path table = dir / "out/sub-01/beh/sub-01_task-crash_beh.tsv";
  const Tsv crashed = readTsv(table);
  ASSERT_EQ(crashed.rows.size(), 2u);
  const auto cell = [&](std::size_t row, const std::string& name) { return crashed.rows[row][crashed.column(name)]; };
  EXPECT_EQ(cell(0, "success"), "1");
  EXPECT_EQ(cell(1, "success"), "n/a");
  EXPECT_EQ(cell(1, "completion_time"), "n/a");
  EXPECT_EQ(cell(1, "failure").rfind("run failed (exit 134", 0), 0u) << cell(1, "failure");
  EXPECT_NE(readFile(dir / "out/report.md").find("and 1 whose run failed"), std::string::npos) << readFile(dir / "out/report.md");
  const fs::path kept_trace = dir / "out/sub-01/beh/trials/001/trace.csv";
  const auto kept_time = fs::last_write_time(kept_trace);
  fs::remove(marker);
  EXPECT_EQ(runExperiment(desc, options), 0);
  EXPECT_EQ(fs::last_write_time(kept_trace), kept_time) << "the trial that ran is kept";
  options.out = (dir / "whole").string();
  EXPECT_EQ(runExperiment(desc, options), 0);
  EXPECT_EQ(readFile(table), readFile(dir / "whole/sub-01/beh/sub-01_task-crash_beh.tsv"));
}

// Two participants, two models, two short tasks with a practice trial a block (12 trials):
// stopped after 5 trials and run again, the experiment keeps those 5 (their files untouched),
// runs the other 7, and its tables equal an uninterrupted run's byte for byte; the BIDS-like
// files are all there.
TEST(ExperimentRun, InterruptedAndRerunItResumesWithIdenticalResults) {
  const fs::path dir = freshFolder("experiment-resume");
  const fs::path file = writeFile(dir / "resume.toml", "participants = 2\nseed = 5\ntasks = [\"push-no-roll\", \"turn-to-target\"]\n"
                                                         "[design]\npractice = 1\nblock_by = \"model\"\n" + kModels);
  const auto run = [&](const fs::path& out, const std::string& more) {
    return exitStatus(kBin + " experiment " + file.string() + " --jobs 2 --out " + out.string() + " " + more + " > " +
                      (out.string() + ".said") + " 2>&1");
  };
  ASSERT_EQ(run(dir / "whole", ""), 0) << readFile(dir / "whole.said");
  ASSERT_EQ(run(dir / "cut", "--stop-after 5"), 130) << readFile(dir / "cut.said");
  const std::string first = readFile(dir / "cut/sub-01/beh/sub-01_task-resume_beh.tsv") +
                            readFile(dir / "cut/sub-02/beh/sub-02_task-resume_beh.tsv");
  EXPECT_EQ(std::count(first.begin(), first.end(), '\n'), 5 + 1) << "5 trials and one header (sub-02 not reached)";
  const fs::path kept_trace = dir / "cut/sub-01/beh/trials/001/trace.csv";
  const auto kept_time = fs::last_write_time(kept_trace);
  ASSERT_EQ(run(dir / "cut", ""), 0) << readFile(dir / "cut.said");
  EXPECT_NE(readFile(dir / "cut.said").find("5 of 12 trials finished before; running the other 7"), std::string::npos)
      << readFile(dir / "cut.said");
  EXPECT_EQ(fs::last_write_time(kept_trace), kept_time) << "a kept trial is not run again";
  for (const char* f : {"participants.tsv", "participants.json", "dataset_description.json",
                               "sub-01/beh/sub-01_task-resume_beh.tsv", "sub-01/beh/sub-01_task-resume_beh.json",
                               "sub-02/beh/sub-02_task-resume_beh.tsv"}) {
    ASSERT_TRUE(fs::exists(dir / "whole" / f)) << f;
    EXPECT_EQ(readFile(dir / "cut" / f), readFile(dir / "whole" / f)) << f;
  }
  const Tsv table = readTsv(dir / "whole/sub-02/beh/sub-02_task-resume_beh.tsv");
  ASSERT_EQ(table.rows.size(), 6u);
  EXPECT_EQ(table.rows[0][table.column("practice")], "1");
  EXPECT_EQ(table.rows[3][table.column("practice")], "1");
  for (const auto& row : table.rows) {
    EXPECT_TRUE(fs::exists(dir / "whole/sub-02" / row[table.column("run")] / "trace.csv")) << row[table.column("run")];
  }
  const nlohmann::json description = nlohmann::json::parse(readFile(dir / "whole/dataset_description.json"));
  EXPECT_EQ(description.at("BIDSVersion"), "1.8.0");
  const Tsv participants = readTsv(dir / "whole/participants.tsv");
  ASSERT_EQ(participants.rows.size(), 2u);
  EXPECT_EQ(participants.rows[0][participants.column("block_order")], "go,gf");
  EXPECT_EQ(participants.rows[1][participants.column("block_order")], "gf,go");
  // The report: a row of conditions.tsv per task and level, the charts, and the same report
  // written again by `godfinger experiment report`.
  const Tsv conditions = readTsv(dir / "whole/conditions.tsv");
  EXPECT_EQ(conditions.rows.size(), 2u * 2u);
  for (const char* f : {"report.md", "success-rate.png", "completion-time.png"}) EXPECT_TRUE(fs::exists(dir / "whole" / f)) << f;
  const std::string report = readFile(dir / "whole/report.md");
  EXPECT_NE(report.find("8 test trials of 2 participants (4 practice trials left out)"), std::string::npos) << report;
  fs::remove(dir / "whole/report.md");
  ASSERT_EQ(exitStatus(kBin + " experiment report " + (dir / "whole").string() + " > /dev/null 2>&1"), 0);
  EXPECT_EQ(readFile(dir / "whole/report.md"), report);
  EXPECT_NE(exitStatus(kBin + " experiment report " + dir.string() + " > /dev/null 2>&1"), 0) << "no experiment there";
}

}  // namespace
}  // namespace gf::app

// Experiments (assets/experiments/README.md): manipulation tasks performed trial by trial under
// conditions (contact model, n_SGO, any scene field) in counterbalanced orders, by simulated
// participants (a seeded human-like hand, app/experiment/hand.hpp). Every trial is an ordinary
// `godfinger run` of its task's scene with the condition's overrides and the hand's device
// tracks; its outcome (success, completion time) is read from its trace.csv against the task's
// goal. The outputs are laid out as BIDS-like behavioural data.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "app/serve/web_server.hpp"
#include "app/study/study.hpp"
#include "sim/math.hpp"

namespace gf::app {

/// A task's goal: where the body must be brought and held, and what it must not do on the way.
struct TaskGoal {
  std::string body;  ///< the scene's dynamic body the goal is about
  /// m: the zone its centre must be in (world frame, both corners); unbounded without one
  sim::Vec3 zone_min = sim::Vec3::Constant(-1e300), zone_max = sim::Vec3::Constant(1e300);
  bool has_zone = false;
  /// The orientation it must be turned to, within orientation_tolerance_deg (unit quaternion)
  std::optional<sim::Quat> orientation;
  double orientation_tolerance_deg = 10.0;
  double hold = 0.5;  ///< s: how long the goal must hold, uninterrupted, to count as reached
  /// The goal holds only while no finger holds the body: every finger's coupling force below
  /// kReleasedForce ("set it down and let go")
  bool released = false;
  /// deg: the largest tilt (from its starting orientation; a spin about the vertical is none)
  /// allowed at any time until the goal is reached and held: "without swinging"
  std::optional<double> max_tilt_deg;
  /// The largest roll ratio (app/measures/roll_ratio.hpp) allowed until then: "without rolling"
  std::optional<double> max_roll_ratio;
  double roll_radius = 0.0;  ///< m: the body's radius for the roll ratio (a sphere's)
};

/// N: a finger whose coupling force is below this holds nothing. A free proxy (0.1 kg) pulled
/// along by its device feels its own inertia: up to about 0.15 N in the tasks' reaches, 0.08 N
/// under four times a typical hand's tremor; a grip presses 1 to 5 N.
inline constexpr double kReleasedForce = 0.25;

/// A task of the battery: a scene (its fingers' keyframes are the movement a simulated hand
/// makes, its bodies the set-up), a goal and a time limit.
struct TaskDesc {
  std::string name, instruction;
  std::string scene;   ///< resolved path of its scene file
  std::string source;  ///< the task file
  double time_limit = 5.0;  ///< s: the trial's length
  TaskGoal goal;
  /// Per finger of the scene: the direction a squeeze moves it (grip noise goes along it); a
  /// finger without one gets none.
  std::vector<std::pair<std::string, sim::Vec3>> grip;
};

/// One level of a factor: its scene overrides. A field "fingers.*.FIELD" applies to every finger
/// of the trial's scene.
struct ExperimentLevel {
  std::string name;
  std::vector<StudyOverride> set;
  /// The simulated hand's noise scale in this level's trials (instead of the experiment's), for
  /// success and completion time against noise
  std::optional<double> noise;
};

struct ExperimentFactor {
  std::string name;
  bool within = true;  ///< every participant meets every level; else each meets one (between)
  std::vector<ExperimentLevel> levels;
  StudySource source;
};

enum class OrderKind {
  kWilliams,  ///< balanced Latin square: every level follows every other equally often (2n rows for odd n)
  kLatin,     ///< cyclic Latin square: every level at every position equally often
  kFixed,     ///< the file's order for everyone
};

struct ExperimentDesc {
  std::string name, summary, source;
  std::string task_label;  ///< BIDS task label (letters and digits): the experiment's name without the rest
  int participants = 8;    ///< simulated participants sub-01 .. sub-NN
  std::uint64_t seed = 1;
  double noise = 1.0;      ///< scale of the simulated hand's noise (0: the nominal movement)
  /// Who performs the trials: "simulated" (seeded hands, every participant in one go) or "web"
  /// (a person in the browser, one participant a session: app/experiment/web_participant.hpp)
  std::string device = "simulated";
  /// device = "udp": the address the session listens on for the participant's device program
  /// ("HOST:PORT" or a port; loopback unless a host is given); a task's fingers take channels 0,
  /// 1, ... in the order its scene lists them
  std::string udp = "127.0.0.1:47001";
  StudySource udp_source;  ///< where the file gives `udp`, for errors
  OrderKind order = OrderKind::kWilliams;
  std::string block_by;    ///< a within factor: each of its levels is a block; "" one block
  int repetitions = 1;     ///< of each task × condition in a block
  int practice = 0;        ///< practice trials at each block's start (not in the statistics)
  bool shuffle = true;     ///< a block's trials in a seeded order per participant (else task order)
  std::vector<ExperimentFactor> factors;
  std::vector<TaskDesc> tasks;
};

/// Reads an experiment file (a path, or the name of a bundled experiment) and its task files.
/// Checks both and every task scene with every level's overrides, so a bad field names the file
/// line that gave it before anything runs. Throws InputError.
ExperimentDesc loadExperimentFile(const std::string& name_or_path);

/// The same from text; `base_dir` resolves the task files. Throws InputError.
ExperimentDesc parseExperimentText(const std::string& text, const std::string& source_name, const std::string& base_dir);

/// Reads one task file. Throws InputError.
TaskDesc loadTaskFile(const std::string& path);

/// The folder of bundled experiments: $GODFINGER_EXPERIMENTS if set, else assets/experiments.
std::string bundledExperimentDir();

/// The order participant `p` (0-based) meets `n` levels in.
std::vector<int> levelOrder(OrderKind kind, int n, int p);

/// One trial of a participant.
struct Trial {
  int participant = 0;       ///< 0-based (sub-01 is 0)
  int number = 0;            ///< 1-based within the participant, in the order they are run
  int block = 0;             ///< 1-based
  bool practice = false;
  int task = 0;              ///< index into ExperimentDesc::tasks
  std::vector<int> levels;   ///< per factor, the level's index
  std::uint64_t seed = 0;    ///< the hand's noise in this trial
};

/// Every trial of every participant, in run order: between factors by participant number (mixed
/// radix: the first factor's level changes with every participant), blocks in levelOrder of
/// `block_by` taking the rows in turn within each between group (row p / groups), each block's trials (tasks × the other within
/// levels × repetitions) shuffled by the participant's seed, its first `practice` repeated before
/// it as practice.
std::vector<Trial> planTrials(const ExperimentDesc& e);

/// How many trials planTrials makes, counted without making them.
std::size_t trialCount(const ExperimentDesc& e);

/// "sub-03".
std::string participantId(int participant);

/// `text` ("FIELD=VALUE") for every finger when FIELD starts "fingers.*.", else itself.
std::vector<std::string> expandFingers(const std::string& text, const std::vector<std::string>& fingers);

/// The hand's noise scale in trial `t`: the last factor level that sets one, else the experiment's.
double trialNoise(const ExperimentDesc& e, const Trial& t);

/// The device of finger `channel` (its index in the task scene) for a person's trial: the
/// browser's pointer (web) or the session's UDP address on that channel, starting where the
/// finger's track starts. A scene override ("fingers.NAME.device={...}").
std::string participantDeviceOverride(const ExperimentDesc& e, const sim::FingerDesc& finger, int channel);

/// Numbers as a TOML array for a scene override, each to 17 significant digits (read back
/// exactly): "[0.1, 0.02, 0]".
std::string exactArray(std::initializer_list<double> values);

/// The condition's overrides of a trial, with "fingers.*." expanded over `fingers`.
std::vector<std::string> trialOverrides(const ExperimentDesc& e, const Trial& t, const std::vector<std::string>& fingers);

struct ExperimentOptions {
  std::string out;
  int jobs = 1;
  bool progress = true;
  std::string godfinger;
  bool restart = false;
  int stop_after = 0;  ///< tests of resuming: start at most this many trials, then stop as if interrupted
  int participant = 0;  ///< a web experiment's participant this session runs (1-based)
  std::optional<ServeOptions> serve;  ///< a web experiment's page: where it is served
};

/// What an experiment's folder records of it for its report (name, factors, levels, tasks).
inline constexpr char kExperimentRecord[] = "experiment.json";

/// Writes report.md, conditions.tsv and the charts (success-rate.png, completion-time.png) of
/// the experiment in `folder` from its trial tables (the trials run so far). Returns 0. Throws
/// InputError for a folder without an experiment or with a malformed table.
int reportExperiment(const std::string& folder);

/// Runs every trial not finished before (jobs at a time), then writes the BIDS-like outputs:
/// dataset_description.json, participants.tsv(+json), per participant
/// sub-NN/beh/sub-NN_task-LABEL_beh.tsv(+json) with one row per trial, each trial's run folder
/// under sub-NN/beh/trials/NNN/ and its hand's tracks beside it. Returns the exit code (0 all
/// trials ran; 130 interrupted). Then reports (reportExperiment).
int runExperiment(const ExperimentDesc& e, const ExperimentOptions& options);

}  // namespace gf::app

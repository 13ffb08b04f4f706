// Accuracy studies: a study file (assets/studies/README.md) names a base scene, the fields to
// vary, the measures taken from each run's outputs and their references. Every configuration is
// an ordinary `godfinger run` command line, so any job runner can execute a study; the results
// are then collected from the run folders into results.csv, a work-precision chart and a report.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "sim/mesh/mesh.hpp"

namespace gf::app {

/// Where a value came from in the study file, for errors found later (e.g. by the scene loader).
struct StudySource {
  int line = 0, column = 0;
  std::string field;  ///< dotted path in the study file ("axes.0.values.2")
};

/// An override of a scene field ("fields.path=VALUE", as `godfinger run --set` takes it).
struct StudyOverride {
  std::string text;
  StudySource source;
  StudySource field_source;  ///< of an axis value: where the axis names its field
};

/// Scene fields varied together over a list of values (e.g. both fingers' n_sgo).
struct StudyAxis {
  std::vector<std::string> fields;    ///< as for --set
  std::string name;                   ///< results.csv's column and the labels' name: `name`, else the first field
  /// `chart = true`: every measure is also charted against this axis' values (numbers), one
  /// line per series (StudyDesc::chart_axes).
  bool chart = false;
  std::vector<StudyOverride> values;  ///< each value in TOML syntax (text without "field=")
  std::vector<StudyOverride> quick;   ///< the values --quick uses (default: the first)
};

/// What a measure is computed from, and how its error is formed.
enum class MeasureKind {
  kFrictionTorque,  ///< applied torque about `axis` minus inertia times the fitted angular acceleration (N m)
  kFrictionForce,   ///< applied force minus mass times the fitted acceleration, across `axis` (N)
  kRollRatio,       ///< rotation angle times the body's radius over the distance travelled
  kSwing,           ///< largest rotation about `axis` after the window's start (deg)
  kForceSd,         ///< s.d. of the non-gravity force along `axis` over the window (N)
  kGeodesicRadius,  ///< mean great-circle distance from the contact point to the SGOs on a sphere (m)
  kTrajectory,      ///< RMS distance between the body's path and the reference run's (m)
  kTipMoment,       ///< applied torque about `axis` minus I times the angular acceleration when the
                    ///< body has turned kTipAngleDeg about it: the moment the contact held (N m)
};

/// The study folder's table of every run's measures, one row a run (report.md beside it).
inline constexpr char kResultsFile[] = "results.csv";

/// The turn (deg) about a tip_moment measure's axis at which the body has tipped.
inline constexpr double kTipAngleDeg = 1.0;

enum class ReferenceKind {
  kRun,                 ///< the same measure in the study's reference run
  kTwoThirdsMuFR,       ///< (2/3) mu F r: a uniformly pressed pad's torsion limit
  kMuFR,                ///< mu F r: every point of the pad at its rim
  kHertzMuFR,           ///< (3 pi / 16) mu F r: a Hertzian pressure distribution
  kThinLayerMuFR,       ///< (8 / 15) mu F r: a thin elastic layer on a rigid core, pressure ∝ a² − r² (Winkler)
  kMuF,                 ///< mu F: Coulomb sliding
  kRollingPrediction,   ///< 0 (slides) when theta + r/R >= 1, else 1 (rolls)
  kPatchRadius,         ///< the Eq. 1 radius the patch walked
  kFR,                  ///< F r: a pad whose whole load has moved to its rim (the tilt limit)
  kValue,               ///< a number the study file gives (StudyMeasure::reference_value)
};

enum class ErrorKind {
  kRelative,   ///< measure / reference - 1
  kAbsolute,   ///< measure - reference (the measure's unit)
  kDeviation,  ///< measure / reference, for a measure that is itself a distance from the reference
};

struct StudyMeasure {
  std::string name;  ///< column prefix (the first measure's columns are measure, reference, error)
  MeasureKind kind = MeasureKind::kFrictionTorque;
  ReferenceKind reference = ReferenceKind::kRun;
  double reference_value = NAN;          ///< ReferenceKind::kValue's, in the measure's unit
  ErrorKind error = ErrorKind::kRelative;
  std::string body, finger;              ///< scene names (finger: the first when empty)
  sim::Vec3 axis = sim::Vec3::UnitY();   ///< world axis of the measure
  double from = 0.0, to = 1e300;         ///< time window (s)
  double at = 0.0;                       ///< time of the contacts snapshot (geodesic radius)
  StudySource source;
};

/// One line of the work-precision chart: its own overrides and axes, crossed with the study's.
struct StudySeries {
  std::string name;
  std::string scene;  ///< resolved path of its scene file
  std::vector<StudyOverride> set;
  std::vector<StudyAxis> axes;
  std::vector<StudyMeasure> measures;
  std::vector<StudyOverride> reference_set;  ///< the reference run: scene + study set + these
  std::vector<StudyOverride> reference_quick_set;  ///< and these last with --quick
  bool has_reference_run = false;
  bool quick = true;  ///< part of the --quick grid
};

enum class CostKind { kStep, kPatch };

/// What a study asks (its `question`): what accuracy costs (a work-precision chart, the best
/// run per budget), or how its measures change along its charted axes (charts against them).
enum class StudyQuestion { kCost, kEffect };

struct StudyDesc {
  std::string name, summary, source;
  CostKind cost = CostKind::kStep;
  /// `scored`: whether the measures' references are the truth the runs are scored against (an
  /// error each). When false they are comparison values (e.g. a flat pad's limit, which a tilted
  /// pad is designed to differ from): the report shows values, no error and no budget.
  bool scored = true;
  StudyQuestion question = StudyQuestion::kCost;
  std::vector<StudySeries> series;
  std::vector<StudyOverride> quick_set;  ///< overrides every --quick run gets last
  /// The study-level axes with `chart = true`, by name: each measure gets a chart against each
  /// (MEASURE-vs-AXIS.png beside work-precision.png).
  std::vector<std::string> chart_axes;
};

/// Reads a study file (a path, or the name of a bundled study). Checks the file itself; the
/// scene fields it names are checked by expandStudy. Throws InputError.
StudyDesc loadStudyFile(const std::string& name_or_path);

/// Same as loadStudyFile, from text: `source_name` names it in errors (and gives the study's
/// default name), `base_dir` resolves relative scene paths. Throws InputError.
StudyDesc parseStudyText(const std::string& text, const std::string& source_name, const std::string& base_dir);

/// A scene file named in an input file at `base_dir`: a path from there, or the name of a bundled
/// scene. Throws InputError.
std::string resolveSceneIn(const std::string& base_dir, const std::string& scene);

/// Loads `scene` with `overrides`; an override the scene refuses is reported where the input
/// file `source` gave it (its value's line, or its field's for an unknown field). Throws
/// InputError.
SessionDesc loadSceneWithOverrides(const std::string& source, const std::string& scene,
                                   const std::vector<StudyOverride>& overrides);

/// The folder of bundled studies: $GODFINGER_STUDIES if set, else the source tree's
/// assets/studies.
std::string bundledStudyDir();

/// One run of a study.
struct StudyRun {
  std::string id;     ///< folder name under DIR/runs ("003-god_finger-ring")
  int series = -1;    ///< index into StudyDesc::series; -1 for a reference run
  std::string scene;  ///< scene file path
  std::vector<StudyOverride> overrides;
  std::vector<std::pair<std::string, std::string>> axis_values;  ///< field, value as written
  int reference = -1;  ///< index of its reference run in the run list (-1: none)
  int measured_as = 0; ///< the series whose measures it is measured with (its own, or a reference's first user)
};

struct StudyPlan {
  StudyDesc study;
  bool quick = false;              ///< the grid: --quick
  std::vector<std::string> extra;  ///< and the command's --set
  std::vector<StudyRun> runs;  ///< reference runs first
};

/// Every configuration: per series, its axes crossed with the study's, plus one reference run
/// per distinct reference configuration. `extra` (the command's --set) applies to every run
/// before its axis values. Loads each configuration's scene with its overrides, so an unknown
/// field or a bad value is reported against the study file line that gave it, before anything
/// runs. A grid of more than 1000 runs is refused before it is listed. Throws InputError.
StudyPlan expandStudy(const StudyDesc& study, bool quick, const std::vector<std::string>& extra);

/// The arguments of one run's `godfinger run` after the scene and --out: `--expectations report`
/// and its overrides as `--set` pairs.
std::vector<std::string> runArguments(const StudyRun& run);

/// The shell command line of one run, writing into `out_dir`/runs/<id>/ (absolute paths, so it
/// works from any folder), its output in run.log there.
std::string runCommandLine(const std::string& godfinger, const std::string& out_dir, const StudyRun& run);

struct StudyOptions {
  std::string out;        ///< DIR
  int jobs = 1;
  bool progress = true;   ///< progress lines on stderr
  std::string godfinger;  ///< the executable runs are started with
  /// Redo every run, even those a run before finished with the same key (app/study/study_resume.hpp).
  bool restart = false;
  /// Start at most this many runs, then collect and return 130 as if interrupted (0: all). For
  /// tests of resuming (`godfinger study --stop-after N`, hidden).
  int stop_after = 0;
};

/// Runs every configuration (jobs at a time), then collects. A run a run before finished into
/// the same folder with the same key (same scene file, overrides and executable; its outputs
/// whole) is kept, not run again, unless `options.restart`; how many are kept is printed.
/// Returns the process exit code: 0 when every run succeeded and was measured.
int runStudy(const StudyPlan& plan, const StudyOptions& options);

/// How a study's grid was made: recorded as DIR/grid.json by a run or an emit, so that --collect
/// rebuilds the same runs.
struct StudyGrid {
  std::string study;               ///< the study file
  bool quick = false;
  std::vector<std::string> extra;  ///< the command's --set
};
void writeStudyGrid(const std::string& dir, const StudyGrid& grid);
/// The grid recorded in `dir`, if any. Throws InputError for a malformed record.
std::optional<StudyGrid> readStudyGrid(const std::string& dir);

/// Writes one command line per run into `jobs_file`.
void emitStudyJobs(const StudyPlan& plan, const StudyOptions& options, const std::string& jobs_file);

/// Reads the run folders under `runs_dir` (the --out of the runs) and writes results.csv,
/// work-precision.png and report.md into `out`. The report says the step times were taken with
/// several runs at once when `parallel_times` is set or when two runs' steps overlapped on one
/// host (from their summary.json; also when a run does not say). Returns 0 when every run was
/// found and measured.
int collectStudy(const StudyPlan& plan, const std::string& runs_dir, const std::string& out, bool parallel_times);

}  // namespace gf::app

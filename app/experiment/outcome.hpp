// A trial's outcome, read from its run's trace.csv against its task's goal.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/experiment/experiment.hpp"
#include "app/runs/run_reader.hpp"

namespace gf::app {

struct TrialOutcome {
  /// The trial's run ended well (exit 0, a trace): else the software failed, not the participant,
  /// and the trial is left out of the statistics (its success "n/a" in the tables)
  bool ran = true;
  bool success = false;
  /// s: when the goal began to hold in the stretch that held it `hold` s (NaN when not reached)
  double completion_s = NAN;
  std::string failure;           ///< why not, "" on success
  double max_tilt_deg = NAN;     ///< largest tilt until the trial was decided (its end on failure)
  double roll_ratio = NAN;       ///< over the same window, when the goal limits it and the body went far enough
  double end_distance_m = NAN;   ///< the centre's distance from the zone at the decision (0 inside)
  double end_angle_deg = NAN;    ///< the turn left to the target orientation at the decision
  double peak_force_n = NAN;     ///< the largest coupling force of any finger over the trial
};

/// `v` to `digits` significant digits ("%g"); "n/a" when not finite (the tables' missing value).
std::string shortText(double v, int digits = 4);

/// Judges a trace (trace.csv's columns) against `goal`: the goal holds at a row when the body's
/// centre is in the zone, its orientation within tolerance and (`released`) no finger's force
/// reaches kReleasedForce; the trial succeeds at the first
/// stretch that holds it `goal.hold` s, unless a limit (max_tilt_deg, max_roll_ratio) was passed
/// before that stretch ended. `fingers` names the fingers whose forces are read.
TrialOutcome judgeTrace(const TaskGoal& goal, const std::vector<std::string>& fingers, const CsvTable& trace);

/// The scene overrides that draw `goal` in a trial's frames as the scene's target "goal"
/// ([targets.NAME]): its zone's box when it has one, and the goal body's ghost turned to the
/// goal orientation when it has one (at the zone's centre, else where the body starts).
std::vector<std::string> goalTargetOverrides(const TaskGoal& goal);

/// The outcome of the trial run in `dir` that exited with `exit_code`, judged on its trace's rows
/// up to `until_s` (a run that went on after the trial's time limit: the device's force fading
/// out): a run that failed (not 0) or left no readable trace did not run (`ran` false, failure
/// "run failed ...").
TrialOutcome judgeTrial(const TaskGoal& goal, const std::vector<std::string>& fingers, const std::filesystem::path& dir,
                        int exit_code, double until_s = HUGE_VAL);

}  // namespace gf::app

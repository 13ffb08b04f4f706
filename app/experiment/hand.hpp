// A simulated participant's hand: the movement a task's scene scripts (its fingers' keyframes)
// made the way a person makes it. Each participant reacts after a delay, moves at their own pace
// along minimum-jerk segments (Flash & Hogan 1985), misses each waypoint by a scatter of their
// own (common to the hand, plus a little per finger), trembles at 8-12 Hz and squeezes with a
// grip that wanders slowly about a bias. Open loop: the hand does not correct what it feels. Every
// draw comes from the experiment's seed (app/experiment/random.hpp), so a trial is the same on
// every run. The values and where they come from: docs/experiments.md.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/scene/scene_desc.hpp"

namespace gf::app {

/// One participant's hand, at noise level 1 (a typical adult); `noise` scales every spread.
struct HandParams {
  double reaction_s = 0.0;     ///< delay before the movement starts (s)
  double speed = 1.0;          ///< pace: the scripted durations are divided by it
  double endpoint_sd_m = 0.0;  ///< scatter of the hand's waypoints, per axis (m)
  double finger_sd_m = 0.0;    ///< each finger's own scatter about the hand's, per axis (m)
  double tremor_rms_m = 0.0;   ///< physiological tremor (8-12 Hz), RMS per axis (m)
  double grip_sd_m = 0.0;      ///< the squeeze's slow wander (0.5-2 Hz) and bias along the grip (m)
};

/// Population means and spreads at noise 1 (docs/experiments.md gives their sources).
struct HandPopulation {
  double reaction_mean_s = 0.25, reaction_sd_s = 0.04;  ///< visual simple reaction time
  double speed_log_sd = 0.15;                           ///< between participants (log pace)
  double endpoint_sd_m = 1.0e-3;
  double finger_sd_m = 0.3e-3;
  double tremor_rms_m = 0.05e-3;
  double grip_sd_m = 0.3e-3;
};

/// Participant `participant`'s hand for an experiment seeded `seed`. With `noise` 0 the hand
/// reaches the scripted waypoints exactly at their times (no delay, pace 1, no scatter, tremor
/// or wander), on minimum-jerk segments whatever the script's interpolation.
HandParams drawHand(std::uint64_t seed, int participant, double noise, const HandPopulation& population = {});

/// A device track as `godfinger run` plays it back (app/scene/device_csv.cpp): rows t, x, y, z
/// (and qw, qx, qy, qz when the scripted movement turns the device).
struct HandTrack {
  std::string finger;
  bool oriented = false;
  std::vector<std::vector<double>> rows;
};

/// The fingers' tracks for one trial from 0 to `duration` s, a row every 1/`rate_hz` s. `grip`:
/// per finger the unit direction a squeeze moves it (fingers without one get no grip wander).
/// `trial_seed` draws this trial's own variation (pace, scatter, tremor phases, grip).
std::vector<HandTrack> moveHand(const std::vector<sim::FingerDesc>& fingers,
                                const std::vector<std::pair<std::string, sim::Vec3>>& grip, const HandParams& hand,
                                std::uint64_t trial_seed, double noise, double duration, double rate_hz = 500.0);

/// Writes `track` as CSV (shortest round-trip numbers). Throws std::runtime_error when it cannot.
void writeHandCsv(const std::string& path, const HandTrack& track);

}  // namespace gf::app

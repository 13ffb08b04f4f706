// The table of reference pictures: fixed (scene, time, camera) pairs rendered offline. The
// visual-regression test compares them with the goldens in screenshots/; `godfinger
// screenshots --out screenshots` (from the repository root) writes new goldens; the README
// shows them.
#pragma once

#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "render/frames/image.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::app {

/// Size of the reference pictures (pixels).
inline constexpr int kShotWidth = 640;
inline constexpr int kShotHeight = 360;

/// One reference picture: a frame of a scene, or (with `models`) a frame of `godfinger
/// compare` drawn in-process (no step times in the labels).
struct Shot {
  std::string name;                    ///< file name without .png
  std::string scene;                   ///< bundled scene name
  double time = 0.0;                   ///< s of simulated time
  std::string camera;                  ///< camera of the scene ("" for its first)
  std::vector<std::string> overrides;  ///< --set FIELD=VALUE applied to the scene
  std::vector<std::string> models = {};  ///< a comparison of these contact models
  double chart_duration = 0.0;           ///< s: the comparison's chart spans [0, chart_duration]
  int width = kShotWidth, height = kShotHeight;
};

/// Every reference picture, in README order.
const std::vector<Shot>& referenceShots();

/// The state of `session`'s scene after running it offline from t = 0 to `time` (s). With
/// `frames_before`, also the states of the frames a run at 60 frames/s draws in the
/// `seconds` before `time` (oldest first).
sim::Snapshot snapshotAt(const SessionDesc& session, double time, std::vector<sim::Snapshot>* frames_before = nullptr,
                         double seconds = 0.0);

/// Runs the shot's scene offline up to its time and renders that instant. Deterministic on one
/// machine. Throws InputError for a broken scene, render::GlError when GL fails.
render::Image renderShot(const Shot& shot);

/// Tolerance of the comparison: a pixel differs when a channel is off by more than this...
inline constexpr int kShotChannelThreshold = 24;
/// ...and a picture fails when more than this share of its pixels differ.
inline constexpr double kShotMaxDifferingShare = 0.004;

}  // namespace gf::app

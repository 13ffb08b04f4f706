// A recorded session: run a scene through the haptic loop, write trace and summary.
#pragma once

#include <string>

#include "sim/haptic_loop.hpp"
#include "sim/scene_desc.hpp"

namespace gf::app {

/// What a session run writes and how it is clocked.
struct SessionOptions {
  std::string out_dir = "out";  ///< created if missing; trace.csv and summary.json go there
  bool realtime = false;        ///< realtime clock (absolute deadlines) instead of offline
  bool progress = true;         ///< progress lines (sim time, steps, ETA) on stderr
};

/// Runs `scene` for scene.duration and writes `trace.csv` and `summary.json` into out_dir.
/// Returns the loop statistics. Throws std::runtime_error (naming the path) on I/O failure.
sim::LoopStats runSession(const sim::SceneDesc& scene, const SessionOptions& options);

}  // namespace gf::app

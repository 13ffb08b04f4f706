// A recorded session: run a scene through the haptic loop and write what it asks to record.
#pragma once

#include <string>

#include "app/session_desc.hpp"
#include "sim/haptic_loop.hpp"

namespace gf::app {

/// What a session run writes and how it is clocked.
struct SessionOptions {
  std::string out_dir = "out";  ///< created if missing
  bool realtime = false;        ///< realtime clock (absolute deadlines) instead of offline
  bool progress = true;         ///< progress lines (sim time, steps, ETA) on stderr
};

/// Runs the session for scene.duration and writes into out_dir: summary.json, trace.csv (when
/// recorded), contacts/t<time>.json at the recorded times, forces.csv (when bodies are listed).
/// Every file is written whole through a rename, so an earlier run's file is replaced only by a
/// complete one. Returns the loop statistics. Throws std::runtime_error (naming the path) on
/// I/O failure.
sim::LoopStats runSession(const SessionDesc& session, const SessionOptions& options);

}  // namespace gf::app

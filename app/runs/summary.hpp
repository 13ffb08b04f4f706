// summary.json, the one writer of it: what made a run (scene, settings, effects, build, command),
// what it did (counters, step and patch times, render timings, realtime lateness) and what it
// showed (expectations, measures). app/runs/run_reader.hpp reads it back.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "render/render_thread.hpp"
#include "sim/loop/haptic_loop.hpp"
#include "sim/world/world.hpp"

namespace gf::app {

/// The version and commit of this build ("0.1.0", "1a2b3c4d5e6f" or "...+dirty" or "unknown").
std::string versionString();
std::string commitString();

/// The run's description and what the loop did: scene, source, overrides, clock, settings,
/// effects, fingers, bodies (mass, inertia), mesh files, step and patch times, counters, wall
/// time, when and on which host it finished.
nlohmann::json summaryJson(const SessionDesc& session, const sim::World& world, const sim::LoopStats& stats,
                           bool realtime);

/// How the realtime loop kept its deadlines: policy, spin, late steps and their share.
nlohmann::json realtimeJson(const sim::LoopStats& stats, bool fifo_requested);
/// A periodic sleeper's lateness (sim::runSleeper), as `godfinger bench realtime` reports it.
nlohmann::json sleeperJson(const sim::SleeperStats& s);

/// The render thread's figures: frames drawn and `published` (handed over by the haptic thread),
/// frame times (it sorts its copy of them), encoders, priority and GL.
nlohmann::json renderJson(render::RenderStats r, long published);

/// What made the result: the build, the command line and the scene file's bytes (FNV-1a 64).
nlohmann::json provenanceJson(const SessionDesc& session, const std::vector<std::string>& command_line);

/// The expectations' checks as summary.json lists them, and the headline measures (each checked
/// expectation's worst value, by name) for a quick look.
void addExpectations(nlohmann::json& summary, const nlohmann::json& checks, std::size_t failed);

}  // namespace gf::app

// A recorded session: run a scene through the haptic loop and write what it asks to record.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "app/serve/web_server.hpp"
#include "app/session/expectations.hpp"
#include "render/render_thread.hpp"
#include "sim/loop/haptic_loop.hpp"

namespace gf::app {

/// What a session run writes and how it is clocked.
struct SessionOptions {
  std::string out_dir = "out";  ///< created if missing
  bool realtime = false;        ///< realtime clock (absolute deadlines) instead of offline
  bool progress = true;         ///< progress lines (sim time, steps, ETA) on stderr
  bool frames = false;          ///< PNG sequence out_dir/frames/000000.png ...
  std::string video_path;       ///< MP4 of the frames (ffmpeg); empty: none
  std::string camera;           ///< camera of the frame stream; empty: the scene's first
  bool close_ups = true;        ///< close-up PNG beside each contact snapshot
  /// When set, receives the scene's expectations that failed (also printed and in summary.json)
  std::vector<ExpectFailure>* expect_failures = nullptr;
  /// Ctrl-C or SIGTERM stop the run and it writes what it reached (the command line; off in
  /// tests and embedding, which keep their own signal handling).
  bool stop_on_interrupt = false;
  /// As stop_on_interrupt, the caller holding the InterruptScope across several runs (an
  /// experiment's session: a signal between two runs is not lost).
  bool stop_on_held_interrupt = false;
  /// Realtime: ask for SCHED_FIFO for the haptic loop (root or CAP_SYS_NICE); false runs as a
  /// user without either does (`run --no-fifo`).
  bool fifo = true;
  /// Realtime: the haptic loop sleeps until this long before each deadline, then spins (us).
  double spin_us = 0.0;
  /// Realtime without SCHED_FIFO: the haptic loop asks for the scheduler's shortest slice.
  bool short_slice = true;
  /// Realtime on two or more CPUs: the haptic loop runs alone on the last CPU and every other
  /// thread of the run (the renderer, llvmpipe's workers, encoders, ffmpeg, file writers) on the
  /// others (`run --pin`): for a machine with a CPU kept free for the loop. Off by default: on a
  /// shared machine it made late steps more frequent ([Performance](performance.md)).
  bool pin_cpus = false;
  /// Realtime: the render thread, its encoders and llvmpipe's workers run at nice 10 so the
  /// haptic loop at nice 0 wins the cores even without root, while frames still get the rest
  /// (`run --no-yield` turns it off).
  bool yield_render = true;
  /// Realtime: serve the browser view (`run --serve`): the frames, the state and `live`
  /// commands over HTTP (app/serve/web_server.hpp), frames drawn whatever else is written.
  std::optional<ServeOptions> serve{};
  /// The scene's duration was cut short for this run (`run --max-duration`; the short variants
  /// of the sanitizer builds): the [expect] limits taken at the end of a run are left unchecked
  /// and summary.json says `"cut_short": true`.
  bool cut_short = false;
  /// The command line that started the run, recorded in summary.json (empty: not recorded).
  std::vector<std::string> command_line{};
  /// Tests only: trace.csv's writes fail once it would pass this many bytes, as on a disk that
  /// fills during the run (0: never).
  std::uint64_t trace_fail_after_bytes = 0;
};

/// The camera called `name` in the session (the first when empty; a default view of the scene
/// when it has none). Throws InputError naming the camera when there is no such camera.
view::Camera sessionCamera(const SessionDesc& session, const std::string& name);

/// The render thread's settings for this session and these options.
render::FrameOutputSettings frameSettings(const SessionDesc& session, const SessionOptions& options);

/// Runs the session for scene.duration and writes into out_dir: summary.json, trace.csv (when
/// recorded), contacts/t<time>.json at the recorded times, forces.csv (when bodies are listed).
/// In stages: the outputs are prepared (the folder locked for the run: a second run into it is
/// refused naming this one's pid; room for the outputs checked and the folders proven writable;
/// only then what an earlier run left of a run's kinds of output removed), the threads started
/// (writers, the render thread), the loop run, and every output finished on its own. Every file
/// is written whole through a rename, so an earlier run's file is replaced only by a complete
/// one. Returns the loop statistics. Throws std::runtime_error (naming the path) on I/O failure.
/// Frames (options.frames, options.video_path) are drawn by a render thread, at every 1/60 s of
/// simulated time; summary.json then holds the render timings. When an output fails during the
/// run (a full disk, a dead ffmpeg) the loop stops, every other output is written for the time
/// reached, summary.json records the error, and the error is thrown.
sim::LoopStats runSession(const SessionDesc& session, const SessionOptions& options);

}  // namespace gf::app

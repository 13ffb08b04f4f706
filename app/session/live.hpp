// `godfinger live`: an interactive session driven by one command a line, answered line by line.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "app/serve/web_server.hpp"
#include "sim/world/world.hpp"

namespace gf::render {
class RenderThread;
}

namespace gf::app {

/// Where a live session comes from and where its snapshots go.
struct LiveOptions {
  std::string scene_path;              ///< scene file
  std::vector<std::string> overrides;  ///< --set given on the command line
  std::string out_dir = "out";         ///< snapshots go to out_dir/contacts/
  std::string input_name = "<stdin>";  ///< names the input in error messages
  /// Ctrl-C or SIGTERM end the session: a running `step N` stops at the next step boundary and
  /// answers, then the session ends with status 130 (143 for SIGTERM). The command line sets
  /// it; tests and embedding keep their own signal handling.
  bool stop_on_interrupt = false;
  /// Serve the browser view (`live --serve`): frames drawn after every command, the state, and
  /// commands posted to /command, taken in turn with standard input's. End of input then does
  /// not end the session: `quit` on standard input or Ctrl-C does.
  std::optional<ServeOptions> serve{};
  std::string camera;  ///< --serve: the camera of the frames (empty: the scene's first)
};

class LiveView;
struct LiveCommand;

/// One live session: a scene's world, stepped and steered by the live protocol's commands. Used
/// by `godfinger live`, the browser view and the Python module's World. One thread at a time.
class LiveSession {
 public:
  /// Loads options.scene_path with options.overrides. Throws InputError when the scene cannot be
  /// loaded or follows a UDP device (live steps on command, a UDP device in wall-clock time).
  explicit LiveSession(const LiveOptions& options);
  /// A session of a scene already loaded (`session` as loadSceneFile gave it for
  /// options.scene_path and options.overrides): no file is read, so the same `session` starts
  /// the same world again, bit for bit (the Python World's reset and restore). Throws
  /// InputError for a UDP device, as above. Allocates.
  LiveSession(const LiveOptions& options, SessionDesc session);

  /// The scene as loaded, with the `set` commands' changes since.
  const SessionDesc& session() const { return session_; }
  double time() const { return world_.time(); }
  /// The world itself, for reads between steps (the session's thread).
  const sim::World& world() const { return world_; }
  /// --serve: the frames go to `renderer` after every command, and `record` to `view`.
  void show(render::RenderThread* renderer, LiveView* view);
  /// Runs one line, checked whole before anything runs; the answer goes into `answer`. Returns
  /// false on quit. Throws std::invalid_argument (or std::runtime_error) with the error's text.
  bool execute(const std::string& line, std::string& answer, bool posted = false);
  /// One haptic step (1 / haptic_rate_hz) with the devices sampled at the step's start: what
  /// `step` runs N times. No allocation once the world has warmed up.
  void step();
  /// The world now (the session's own snapshot, valid until the next call).
  const sim::Snapshot& snapshot();

 private:
  std::string move(const LiveCommand& c);
  std::string state();
  void publish();  // --serve: the world as it is now, for the next frame

  LiveOptions options_;
  SessionDesc session_;
  sim::World world_;
  std::vector<sim::DeviceTrack> devices_;
  std::vector<sim::DeviceSample> samples_;
  sim::Snapshot snap_;
  render::RenderThread* renderer_ = nullptr;
  LiveView* view_ = nullptr;
};

/// Runs commands from `in` until `quit` or end of input, answering each on `out`:
///   move FINGER X Y Z [SECONDS]   device to (X, Y, Z) m, straight, over SECONDS (default 0)
///   set fingers.NAME.FIELD=VALUE  a live finger setting of sim/scene/settings.hpp (n_sgo, r_max, d0,
///                                 alpha, stretch_length, max_stretch, tau_a in
///                                 degrees, friction), checked by its validator
///   step [N]                      N haptic steps (default 1), then the state
///   state                         the state: time, per finger proxy, force, SGOs, and per
///                                 dynamic body position, orientation (x y z w), velocity and
///                                 angular velocity (world frame)
///   snapshot [NAME]               contacts JSON to out_dir/contacts/NAME.json
///   record start|stop             --serve: frames of the view to out_dir/frames/
///   help, quit
/// Answers start with "ok" or "error: INPUT:LINE: ...". Returns 0 when every command
/// succeeded, 1 otherwise, 130 / 143 when interrupted (see stop_on_interrupt). Throws InputError when the scene itself cannot be loaded.
int runLive(const LiveOptions& options, std::istream& in, std::ostream& out);

}  // namespace gf::app

// godfinger.World's C++ side: a live session (app/session/live.hpp) owned by one Python object,
// with the session's lifetime (close, reset), its history (save, restore) and its state as numpy
// arrays. world_bind.cpp binds it; docs/python.md describes it for Python's users.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/session/live.hpp"

namespace gf::app::python {

namespace py = pybind11;

/// What a World was made from: the scene as first loaded, which reset and restore start from
/// again (no file is read twice). Shared by a World and the States it saved; immutable.
struct WorldOrigin {
  LiveOptions options;  ///< scene path and `set` overrides, as given
  SessionDesc start;    ///< the scene as loadSceneFile read it then
};

/// One thing a World did since its start, replayed in order by restore: `steps` haptic steps
/// when `line` is empty, else one accepted `move` or `set` line of the live protocol.
struct HistoryEntry {
  std::string line;
  long steps = 0;
  /// Same line and steps (what restore compares histories by).
  bool operator==(const HistoryEntry&) const = default;
};

/// godfinger.State: a World's point in time, as the steps and commands that led there from the
/// scene's start. Opaque to Python; restores only into a World of the same origin.
struct SavedState {
  std::shared_ptr<const WorldOrigin> origin;
  std::vector<HistoryEntry> history;
  double time = 0.0;  ///< simulated time (s) when saved
  long step = 0;      ///< haptic steps since the start when saved
};

/// A live session for Python. Every method throws RuntimeError once closed or when called from
/// another thread than the one that made it (sim::World's owner rule), ValueError or InputError
/// for bad input; none crashes. Allocates.
class World {
 public:
  /// Loads `scene` (a bundled scene's name or a file: str or os.PathLike) with set={field:
  /// value} as --set. Throws InputError for a scene that cannot be loaded.
  World(const py::object& scene, const py::dict& set);

  /// Ends the session and frees its world; a second close does nothing.
  void close();
  /// close() has run.
  bool closed() const { return !live_; }
  /// Throws RuntimeError when closed or called from another thread (what every method checks).
  void requireOpen() { live(); }
  /// n haptic steps (1..10^7). Checks for Ctrl-C (Python's pending signals) every
  /// kStepsPerSignalCheck steps: a raised KeyboardInterrupt leaves the world at a whole step.
  void step(long n);
  /// Back to the scene's start with the settings it was made with (`set` commands undone).
  void reset();
  /// The world's point in time, for restore.
  SavedState save();
  /// Back to a point save() returned: rebuilt from the start and the history replayed, so the
  /// steps after it are bit for bit those after save(). Throws ValueError for another World's
  /// state; on KeyboardInterrupt during the replay the world stays as it was.
  void restore(const SavedState& state);

  /// The live `state` answer as Python objects.
  py::object state();
  /// `move FINGER X Y Z SECONDS`; returns live's answer without "ok ".
  std::string move(const std::string& finger, const std::vector<double>& xyz, double seconds);
  /// `set FIELD=VALUE` for one live finger setting.
  void set(const std::string& field, const py::object& value);
  /// The session's snapshot with per-SGO arrays (convert.hpp's snapshotDict).
  py::dict snapshot();
  /// The contacts JSON of live's `snapshot` command, as Python objects.
  py::object contacts();
  /// The state as numpy arrays, read from the world directly (no snapshot, no JSON).
  py::dict arrays();
  /// Simulated time (s).
  double time();
  /// The scene's finger or body names.
  std::vector<std::string> names(bool fingers);
  /// `<godfinger.World NAME at t=T s>`, or `(closed)`; never throws.
  std::string repr() const;

  /// Steps between two checks for Ctrl-C: about 0.5 to 3 ms of the bundled scenes' steps.
  static constexpr long kStepsPerSignalCheck = 64;

 private:
  LiveSession& live();
  std::string command(const std::string& line);
  void addSteps(long n);

  std::shared_ptr<const WorldOrigin> origin_;
  std::unique_ptr<LiveSession> live_;
  std::vector<HistoryEntry> history_;
  std::thread::id owner_ = std::this_thread::get_id();
};

}  // namespace gf::app::python

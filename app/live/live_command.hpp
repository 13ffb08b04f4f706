// The `live` protocol's commands and answers, shared by `godfinger live` (standard input) and the
// browser view (POST /command, app/serve/): one line is read and checked whole before anything
// runs, so a bad line changes nothing.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

#include "sim/scene/scene_desc.hpp"
#include "sim/scene/settings.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::app {

/// One line of the live protocol, parsed and checked against the scene.
struct LiveCommand {
  enum class Kind { kNone, kQuit, kHelp, kStep, kState, kMove, kSet, kSnapshot, kRecord };
  Kind kind = Kind::kNone;  ///< kNone: an empty line or a comment
  long steps = 1;           ///< kStep
  int finger = -1;          ///< kMove, kSet: index into the scene's fingers
  sim::Vec3 target = sim::Vec3::Zero();  ///< kMove: device position (m)
  double seconds = 0.0;     ///< kMove: straight there over this long (0: at once)
  const sim::Setting<sim::FingerDesc>* setting = nullptr;  ///< kSet: a live finger setting
  double value = 0.0;       ///< kSet: in the setting's unit, checked by its validator
  std::string text;         ///< kSet: the assignment as given; kSnapshot: the name ("" : a default)
  bool on = false;          ///< kRecord: start (true) or stop
};

/// The words of the help answer.
extern const char* const kLiveHelp;

/// Parses one line. Throws std::invalid_argument with the answer's text when it is not a legal
/// command: unknown words, wrong argument counts, numbers out of range, a finger or a setting
/// the scene does not have, a value its validator refuses.
LiveCommand parseLiveCommand(const std::string& line, const sim::SceneDesc& scene);

/// The `state` answer's JSON: time; per finger its proxy, coupling force (N), SGOs of the step,
/// live settings and contacts (body, radius, SGOs); per dynamic body position, orientation
/// (x y z w), velocity and angular velocity (world frame).
nlohmann::json stateJson(const sim::Snapshot& snapshot, const sim::SceneDesc& scene);

/// The answer to a `move`: "ok FINGER to X Y Z by t=T".
std::string moveAnswer(const LiveCommand& command, const sim::SceneDesc& scene, double t_end);
/// Writes the contacts JSON of `snapshot` as out_dir/contacts/NAME.json (NAME: the command's, or
/// live_STEP) and answers "ok PATH". Throws std::runtime_error naming the folder it cannot make.
std::string writeSnapshot(const LiveCommand& command, const sim::Snapshot& snapshot, const sim::SceneDesc& scene,
                          const std::string& out_dir);

/// `finger`'s settings after `command` (a kSet) applied to `current`.
sim::PatchSettings applySet(const LiveCommand& command, const sim::PatchSettings& current);

}  // namespace gf::app

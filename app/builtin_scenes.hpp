// The one table of built-in scenes, shared by the `godfinger` command, the tests and the
// benchmarks. Scene files (TOML) will describe the same things; these stay as code so that tests
// and benchmarks need no file.
#pragma once

#include <span>
#include <string>

#include "sim/scene_desc.hpp"

namespace gf::app {

/// Options every built-in scene accepts.
struct SceneOptions {
  int n_sgo = 8;          ///< SGOs per finger; 0 gives the classic god-object
  double duration = 0.0;  ///< simulated seconds; 0 keeps the scene's own
};

/// One entry of the table.
struct BuiltinScene {
  const char* name;
  const char* summary;
  sim::SceneDesc (*make)(const SceneOptions&);
};

/// All built-in scenes, in display order.
std::span<const BuiltinScene> builtinScenes();

/// The scene called `name`; throws std::invalid_argument listing the known names otherwise.
sim::SceneDesc makeBuiltinScene(const std::string& name, const SceneOptions& options);

/// Paper Fig. 8: two fingers pick a standing cylinder along x, 1 cm under its centre of mass,
/// lift it 5 cm in 2 s and hold it still. Body 1 is the cylinder; fingers 0 (-x) and 1 (+x).
sim::SceneDesc pinchScene(const SceneOptions& options);

/// A box on a nearly frictionless table, pressed from above by one finger (body 1: the box).
sim::SceneDesc pressBoxScene(const SceneOptions& options);

}  // namespace gf::app

// The JSON Schema of scene files (`godfinger schema`).
#pragma once

#include <nlohmann/json.hpp>

namespace gf::app {

/// A JSON Schema (draft 2020-12) of scene files, built from the same tables that validate them
/// (sim/scene/settings.hpp: each setting's type, range, choices and unit), for editors that check and
/// complete TOML against a schema. Rules across fields (a mesh needs `mesh`, n_sgo 0 or 3..64)
/// are only checked when a scene loads. `godfinger schema` prints it.
nlohmann::json sceneSchema();

}  // namespace gf::app

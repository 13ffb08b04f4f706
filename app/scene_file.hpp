// Scene files (TOML): parsing, command-line overrides and the bundled scenes.
// The format is documented field by field in assets/scenes/README.md.
#pragma once

#include <nlohmann/json.hpp>

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/session_desc.hpp"

namespace gf::app {

/// Bad input: what() reads "FILE:LINE:COLUMN: FIELD: reason" (line and column when known).
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, int column, const std::string& field,
             const std::string& reason);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  int column() const { return column_; }
  const std::string& reason() const { return reason_; }

 private:
  static std::string message(const std::string& file, int line, int column, const std::string& field,
                             const std::string& reason);
  std::string file_;
  int line_;
  int column_;
  std::string field_;
  std::string reason_;
};

/// Loads a scene file and applies `overrides` ("fields.path=VALUE", VALUE in TOML syntax or a
/// bare string) before validation. Mesh and device CSV paths are relative to the file. Loads
/// every mesh once to check it. Throws InputError.
SessionDesc loadSceneFile(const std::string& path, std::span<const std::string> overrides = {});

/// Same as loadSceneFile, from text; `source_name` names it in errors and `base_dir` resolves
/// relative paths.
SessionDesc parseSceneText(const std::string& text, const std::string& source_name,
                           const std::string& base_dir, std::span<const std::string> overrides = {});

/// Reads a recorded device path: CSV with a header row "t,x,y,z" (s, m), strictly increasing
/// times; played back with linear interpolation. Throws InputError naming file and line.
sim::DeviceTrack readDeviceCsv(const std::string& path);

/// A JSON Schema (draft 2020-12) of scene files, built from the same tables that validate them
/// (sim/settings.hpp: each setting's type, range, choices and unit), for editors that check and
/// complete TOML against a schema. Rules across fields (a mesh needs `mesh`, n_sgo 0 or 3..64)
/// are only checked when a scene loads. `godfinger schema` prints it.
nlohmann::json sceneSchema();

/// The folder of bundled data (scenes/, studies/, meshes/, hard-cases/): $GODFINGER_DATA if
/// set; else beside the executable, installed (<prefix>/share/godfinger) or in a build tree
/// (<build>/share/godfinger, copied there by every build); else the install prefix's data (an
/// application embedding the installed library); else the source tree's assets/.
std::string dataDir();

/// The folder of bundled scene files: $GODFINGER_SCENES if set, else dataDir()/scenes.
std::string bundledSceneDir();

/// A scene argument as given on the command line: a path to a file, or the name of a bundled
/// scene (without ".toml"). Throws InputError when neither exists.
std::string resolveScenePath(const std::string& scene);

/// The bundled scene files, sorted by name.
std::vector<std::string> bundledScenePaths();

}  // namespace gf::app

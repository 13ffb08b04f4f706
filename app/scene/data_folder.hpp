// Where the bundled data is (scenes, studies, meshes, hard cases), and scene names on the
// command line.
#pragma once

#include <string>
#include <vector>

namespace gf::app {

/// The folder of bundled data (scenes/, studies/, meshes/, hard-cases/): $GODFINGER_DATA if
/// set; else beside the executable, installed (<prefix>/share/godfinger) or in a build tree
/// (<build>/share/godfinger, copied there by every build); else the install prefix's data (an
/// application embedding the installed library); else the source tree's assets/.
std::string dataDir();

/// The folder of bundled scene files: $GODFINGER_SCENES if set, else dataDir()/scenes.
std::string bundledSceneDir();

/// A file or folder named on the command line: `path` itself when it exists (relative to the
/// working directory) or is absolute; else the bundled data's copy when there is one, named as
/// in the repository ("assets/meshes/bunny.obj") or in the data folder ("meshes/bunny.obj");
/// else `path` unchanged (for the caller's error).
std::string resolveDataPath(const std::string& path);

/// A scene argument as given on the command line: a path to a file (resolveDataPath), or the name
/// of a bundled scene (without ".toml"). Throws InputError when neither exists.
std::string resolveScenePath(const std::string& scene);

/// An input file named on the command line: `name_or_path` when it is a file, else `folder`'s
/// NAME.toml for a bare name (no '/'). Throws InputError naming `what` ("study", "experiment")
/// and `shown` (the folder as a user knows it, "assets/studies") when neither exists.
std::string resolveBundledFile(const std::string& name_or_path, const std::string& folder, const std::string& what,
                               const std::string& shown);

/// The bundled scene files, sorted by name.
std::vector<std::string> bundledScenePaths();

}  // namespace gf::app

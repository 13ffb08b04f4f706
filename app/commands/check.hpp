// `godfinger check`: run many scenes offline, each as its own `godfinger run` process, and report
// whether each met its [expect] table (every scene at least stays finite).
#pragma once

#include <string>
#include <vector>

namespace gf::app {

struct CheckOptions {
  std::vector<std::string> paths;  ///< scene files, folders of them (searched recursively) or bundled names
  std::string out = "out/check";   ///< each scene's run folder goes under it (defaultOutFolder("check"))
  int jobs = 1;
  std::string godfinger;           ///< the executable runs are started with
  std::vector<std::string> overrides;  ///< `--set` for every run (e.g. world.contact_solver=aggregate)
  /// s: each run at most this long (`run --max-duration`: end-of-run limits unchecked); 0: whole
  double max_duration = 0.0;
};

/// The scene files `paths` name, sorted within each folder. Throws InputError for a path that
/// is neither a scene file, a folder nor a bundled scene.
std::vector<std::string> checkedScenes(const std::vector<std::string>& paths);

/// Runs every scene and prints one line each (PASS, FAIL or ERROR, with the worst figure); 0
/// when all passed, 1 otherwise, 130 when interrupted.
int runCheck(const CheckOptions& options);

}  // namespace gf::app

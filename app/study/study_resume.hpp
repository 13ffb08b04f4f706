// Resuming a study: every run that ends well gets a record in its folder (runs/<id>/study-run.json)
// holding its key, a hash of what made it (the executable's bytes, the scene file's bytes and the
// run's arguments), and the sizes of the files it wrote. A rerun into the same folder keeps a run
// whose record's key is the one it would run with and whose files are still those the record
// names, and runs the rest; results.csv and the charts are then collected from every run folder
// as after an uninterrupted study.
#pragma once

#include <string>
#include <vector>

#include "app/study/study.hpp"

namespace gf::app {

/// The record a finished run gets beside its outputs.
inline constexpr char kStudyRunRecord[] = "study-run.json";

/// The key of one run: FNV-1a 64 (16 hex digits) of `binary_hash` (fileFnv1a64 of the
/// executable), the bytes of the run's scene file and its runArguments. A scene's other files
/// (meshes, device CSVs) are not in it. Reads the scene file.
std::string studyRunKey(const std::string& binary_hash, const StudyRun& run);

/// Which runs of a plan a study keeps from an earlier one in its folder.
struct StudyResume {
  std::vector<std::string> keys;  ///< per run of the plan, its key
  std::vector<bool> kept;         ///< per run: finished before with this key, its outputs whole
  int kept_count = 0;
  int other_key = 0;  ///< runs with a record of another key (another executable, scene file or settings)
  int broken = 0;     ///< runs with a record whose files are missing, changed or unfinished
};

/// Reads each run's record under `out`/runs. With `restart`, keeps none (the keys are still
/// computed). Reads the executable once (about 40 ms for 30 MB).
StudyResume planResume(const StudyPlan& plan, const std::string& out, const std::string& godfinger, bool restart);

/// Whether the run in `dir` finished before with `key` and its files are still those its record
/// names (a run of any runner that records its runs: studies, experiments).
bool runFinishedWith(const std::string& dir, const std::string& key);

/// Writes `dir`'s record: `key` and the sizes of its summary.json, trace.csv and forces.csv (those
/// present). Call when the run ended with exit 0. Throws std::runtime_error when it cannot.
void recordFinishedRun(const std::string& dir, const std::string& key);

/// Removes `dir`'s record (before the run is started again), so a run cut short is never kept.
/// Throws std::runtime_error when it cannot.
void forgetFinishedRun(const std::string& dir);

}  // namespace gf::app

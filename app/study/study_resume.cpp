#include "app/study/study_resume.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>

#include "app/runs/files.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// What a record names: every file the run wrote into its folder (summary.json, trace.csv,
// forces.csv, contacts/...), by path relative to the folder, with its size in bytes; the run's
// log, the lock and the record itself aside.
std::map<std::string, std::uintmax_t> runFiles(const fs::path& dir) {
  std::map<std::string, std::uintmax_t> out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec)) continue;
    const std::string name = it->path().lexically_relative(dir).generic_string();
    if (name == kRunLogFile || name == kLockFile || name == kStudyRunRecord) continue;
    out[name] = it->file_size(ec);
  }
  return out;
}

enum class Kept { kYes, kNoRecord, kOtherKey, kBroken };

// Whether the run in `dir` finished before with `key` and still holds what it wrote then.
Kept keptRun(const fs::path& dir, const std::string& key) {
  std::error_code ec;
  if (!fs::exists(dir / kStudyRunRecord, ec)) return Kept::kNoRecord;
  try {
    const nlohmann::json record = readJsonFile(dir / kStudyRunRecord);
    if (record.at("key").get<std::string>() != key) return Kept::kOtherKey;
    const std::map<std::string, std::uintmax_t> files = record.at("files").get<std::map<std::string, std::uintmax_t>>();
    if (files != runFiles(dir) || !files.contains(kSummaryFile) || !files.contains(kTraceFile)) return Kept::kBroken;
    // A run that ended early (an output that failed, a signal) says so in its summary.
    const nlohmann::json summary = requireSummary(dir);
    if (summary.value("interrupted", false) || summary.contains("error") || summary.value("cut_short", false)) {
      return Kept::kBroken;
    }
  } catch (const std::exception&) {
    return Kept::kBroken;  // a record or summary that is not what a finished run writes
  }
  return Kept::kYes;
}

}  // namespace

std::string studyRunKey(const std::string& binary_hash, const StudyRun& run) {
  // Each part is ended by a NUL, so no two lists of parts hash the same text.
  std::uint64_t h = fnv1a64(kFnv1a64Basis, std::string_view("godfinger study run 1", 22));
  h = fnv1a64(h, std::string_view(binary_hash.c_str(), binary_hash.size() + 1));
  const std::string scene = fileFnv1a64(run.scene);
  h = fnv1a64(h, std::string_view(scene.c_str(), scene.size() + 1));
  for (const std::string& a : runArguments(run)) h = fnv1a64(h, std::string_view(a.c_str(), a.size() + 1));
  return hex64(h);
}

StudyResume planResume(const StudyPlan& plan, const std::string& out, const std::string& godfinger, bool restart) {
  StudyResume r;
  const std::string binary = fileFnv1a64(godfinger);
  for (const StudyRun& run : plan.runs) {
    r.keys.push_back(studyRunKey(binary, run));
    const Kept kept = restart ? Kept::kNoRecord : keptRun(fs::path(out) / "runs" / run.id, r.keys.back());
    r.kept.push_back(kept == Kept::kYes);
    r.kept_count += kept == Kept::kYes;
    r.other_key += kept == Kept::kOtherKey;
    r.broken += kept == Kept::kBroken;
  }
  return r;
}

bool runFinishedWith(const std::string& dir, const std::string& key) { return keptRun(dir, key) == Kept::kYes; }

void recordFinishedRun(const std::string& dir, const std::string& key) {
  const nlohmann::json record = {{"key", key}, {"files", runFiles(dir)}};
  writeFileAtomically((fs::path(dir) / kStudyRunRecord).string(), record.dump(1) + "\n");
}

void forgetFinishedRun(const std::string& dir) {
  std::error_code ec;
  if (!fs::remove(fs::path(dir) / kStudyRunRecord, ec) && ec) {
    throw std::runtime_error(dir + "/" + kStudyRunRecord + ": cannot remove: " + ec.message());
  }
}

}  // namespace gf::app

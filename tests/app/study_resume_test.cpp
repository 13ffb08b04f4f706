// Resuming a study (app/study/study_resume.cpp): a study stopped after k runs and run again keeps
// the k runs (their files untouched), runs the rest, and ends with the results of an uninterrupted
// study; a record whose key or files do not match is run again; --restart runs them all.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "app/runs/files.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/study/study.hpp"
#include "app/study/study_resume.hpp"
#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using test::exitStatus;
using test::freshFolder;
using test::kBin;
using test::readFile;

// Six runs of the pressed puck (1 s each): two models by three solver iteration counts, charted.
fs::path writeSmallStudy(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path p = dir / "resume.toml";
  std::ofstream(p) << "summary = \"resume test\"\nscene = \"" << GF_SOURCE_DIR << "/assets/scenes/pressed-puck.toml\"\n"
                   << "[[axes]]\nfield = \"world.solver_iterations\"\nvalues = [5, 10, 20]\nchart = true\n"
                   << "[[measures]]\nname = \"slip_torque\"\nkind = \"friction_torque\"\nbody = \"puck\"\n"
                   << "window = [0.7, 1.0]\nreference = \"two_thirds_mu_f_r\"\n"
                   << "[[series]]\nname = \"god_object\"\nset = [\"fingers.index.contact_model=god_object\"]\n"
                   << "[[series]]\nname = \"soft_finger\"\nset = [\"fingers.index.contact_model=soft_finger\"]\n";
  return p;
}

// `godfinger study` into `out` with `more` arguments; its exit status, stdout in `said`.
int studyCommand(const fs::path& file, const fs::path& out, const std::string& more, std::string& said) {
  const fs::path log = out.parent_path() / (out.filename().string() + ".stdout");
  const int status = exitStatus(kBin + " study " + file.string() + " --jobs 1 --out " + out.string() + " " + more +
                                " > " + log.string() + " 2> /dev/null");
  said = readFile(log);
  return status;
}

// Each run's summary.json, by run id: its inode and modification time (a rewrite renames a new
// file into place: a new inode).
std::map<std::string, std::pair<ino_t, long long>> summaryStamps(const fs::path& out) {
  std::map<std::string, std::pair<ino_t, long long>> r;
  for (const fs::directory_entry& e : fs::directory_iterator(out / "runs")) {
    struct stat s {};
    if (stat((e.path() / "summary.json").c_str(), &s) != 0) continue;
    r[e.path().filename().string()] = {s.st_ino, s.st_mtim.tv_sec * 1000000000LL + s.st_mtim.tv_nsec};
  }
  return r;
}

// results.csv without the step and patch times, which differ from one run of a configuration to
// the next.
std::vector<std::vector<std::string>> measuredCells(const fs::path& results) {
  const CsvText csv = readCsvText(results.string());
  std::vector<std::vector<std::string>> out;
  for (const std::vector<std::string>& row : csv.rows) {
    out.emplace_back();
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (csv.names[c] != "step_us_median" && csv.names[c] != "step_us_p99" && csv.names[c] != "patch_us_mean") {
        out.back().push_back(row[c]);
      }
    }
  }
  return out;
}

// Stopped after 2 of 6 runs and run again: "resuming: 2 of 6 runs kept, 4 to run", the 2 runs'
// files untouched, and results.csv equal to an uninterrupted study's, value for value (the step
// times aside), and byte for byte to a fresh collect of the same folder (charts too). A third
// run keeps all 6 and changes nothing; --restart runs all 6 again.
TEST(StudyResume, AStudyStoppedAfterTwoRunsResumesToTheUninterruptedResults) {
  const fs::path dir = freshFolder("gf_study_resume");
  const fs::path file = writeSmallStudy(dir), whole = dir / "whole", resumed = dir / "resumed";
  std::string said;
  ASSERT_EQ(studyCommand(file, whole, "", said), 0) << said;
  EXPECT_EQ(said.find("resuming"), std::string::npos) << said;
  ASSERT_EQ(studyCommand(file, resumed, "--stop-after 2", said), 130) << said;
  const auto first = summaryStamps(resumed);
  ASSERT_EQ(first.size(), 2u);
  ASSERT_EQ(studyCommand(file, resumed, "", said), 0) << said;
  EXPECT_NE(said.find("resuming: 2 of 6 runs kept, 4 to run"), std::string::npos) << said;
  const auto second = summaryStamps(resumed);
  ASSERT_EQ(second.size(), 6u);
  for (const auto& [id, stamp] : first) EXPECT_EQ(second.at(id), stamp) << id << " was rewritten";
  EXPECT_EQ(measuredCells(whole / kResultsFile), measuredCells(resumed / kResultsFile));
  // What a resumed study wrote is what collecting its folder writes.
  const StudyPlan plan = expandStudy(loadStudyFile(file.string()), false, {});
  const fs::path again = dir / "collected";
  ASSERT_EQ(collectStudy(plan, resumed.string(), again.string(), false), 0);
  for (const char* f : {kResultsFile, "work-precision.png", "slip_torque-vs-world.solver_iterations.png"}) {
    ASSERT_TRUE(fs::exists(resumed / f)) << f;
    EXPECT_EQ(readFile(resumed / f), readFile(again / f)) << f;
  }
  ASSERT_EQ(studyCommand(file, resumed, "", said), 0) << said;
  EXPECT_NE(said.find("resuming: 6 of 6 runs kept, 0 to run"), std::string::npos) << said;
  EXPECT_EQ(summaryStamps(resumed), second);
  EXPECT_EQ(readFile(resumed / kResultsFile), readFile(again / kResultsFile));
  ASSERT_EQ(studyCommand(file, resumed, "--restart", said), 0) << said;
  EXPECT_NE(said.find("restarting: all 6 runs to run"), std::string::npos) << said;
  for (const auto& [id, stamp] : summaryStamps(resumed)) EXPECT_NE(stamp, second.at(id)) << id << " was kept";
}

// A record is kept only for its key and its files: another executable, another override, a record
// edited, a trace cut short or a run stopped by a signal are all run again.
TEST(StudyResume, ARunIsKeptOnlyForItsKeyAndItsWholeFiles) {
  const fs::path dir = freshFolder("gf_study_resume_keys");
  const fs::path file = writeSmallStudy(dir), out = dir / "out";
  std::string said;
  ASSERT_EQ(studyCommand(file, out, "", said), 0) << said;
  const StudyPlan plan = expandStudy(loadStudyFile(file.string()), false, {});
  const StudyResume all = planResume(plan, out.string(), kBin, false);
  EXPECT_EQ(all.kept_count, 6);
  // Another executable (its bytes' hash) or other overrides: other keys.
  StudyRun changed = plan.runs[0];
  EXPECT_NE(studyRunKey("another binary", changed), studyRunKey(fileFnv1a64(kBin), changed));
  EXPECT_EQ(all.keys[0], studyRunKey(fileFnv1a64(kBin), changed));
  changed.overrides.push_back({"duration=0.5", {}, {}});
  EXPECT_NE(studyRunKey(fileFnv1a64(kBin), changed), all.keys[0]);
  const StudyResume other = planResume(expandStudy(loadStudyFile(file.string()), false, {"duration=0.9"}),
                                       out.string(), kBin, false);
  EXPECT_EQ(other.kept_count, 0);
  EXPECT_EQ(other.other_key, 6);
  // A record whose files changed, or a summary that says the run ended early.
  const fs::path run0 = out / "runs" / plan.runs[0].id, run1 = out / "runs" / plan.runs[1].id;
  fs::resize_file(run0 / kTraceFile, fs::file_size(run0 / kTraceFile) / 2);
  nlohmann::json summary = requireSummary(run1);
  summary["interrupted"] = true;
  std::ofstream(run1 / kSummaryFile) << summary.dump();
  nlohmann::json record = readJsonFile(run1 / kStudyRunRecord);
  record["files"][kSummaryFile] = fs::file_size(run1 / kSummaryFile);  // sizes that match: the summary decides
  std::ofstream(run1 / kStudyRunRecord) << record.dump();
  const StudyResume broken = planResume(plan, out.string(), kBin, false);
  EXPECT_EQ(broken.kept_count, 4);
  EXPECT_EQ(broken.broken, 2);
  EXPECT_FALSE(broken.kept[0]);
  EXPECT_FALSE(broken.kept[1]);
  EXPECT_EQ(planResume(plan, out.string(), kBin, true).kept_count, 0) << "--restart keeps none";
  ASSERT_EQ(studyCommand(file, out, "", said), 0) << said;
  EXPECT_NE(said.find("resuming: 4 of 6 runs kept, 2 to run"), std::string::npos) << said;
  EXPECT_EQ(planResume(plan, out.string(), kBin, false).kept_count, 6);
}

}  // namespace
}  // namespace gf::app

// trace.csv (app/runs/trace.cpp) and its file (app/runs/files.cpp): rows thinned by
// record.trace_rate at their exact times, a size projected and warned about once, and a disk that
// fills during the run keeping every whole row written before.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/runs/files.hpp"
#include "app/runs/run_folder.hpp"
#include "app/runs/run_reader.hpp"
#include "app/runs/trace.hpp"
#include "app/scene/data_folder.hpp"
#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"
#include "app/session/session.hpp"
#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;
using test::freshFolder;
using test::readFile;

// The lines of a text file.
std::vector<std::string> linesOf(const fs::path& p) {
  std::vector<std::string> out;
  std::istringstream in(readFile(p));
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A write that fails part-way through a chunk (a disk that fills): close() puts the file in place
// cut back to its last whole row, and says how many rows it kept.
TEST(RowFile, AWriteThatFailsKeepsEveryWholeRowBefore) {
  const fs::path path = freshFolder("gf_rows_full") / "rows.csv";
  RowFileOptions options;
  options.ring_rows = 16;
  options.fail_after_bytes = 1000;  // the header (2 bytes) and some rows of 2 to 6 bytes
  std::string pushed, closed;
  RowFile file(path.string(), {"i"}, options);
  try {
    for (int i = 0; i < 100000; ++i) {
      const double row[1] = {static_cast<double>(i)};
      file.push(row);
    }
  } catch (const std::runtime_error& e) {
    pushed = e.what();  // the owner learns of the failure at its next push
  }
  try {
    file.close();
  } catch (const std::runtime_error& e) {
    closed = e.what();
  }
  EXPECT_NE(pushed.find("cannot write (disk full?)"), std::string::npos) << pushed;
  const std::string& error = closed;
  ASSERT_TRUE(fs::exists(path)) << error;
  EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
  const std::string text = readFile(path);
  EXPECT_LE(text.size(), 1000u);
  ASSERT_EQ(text.back(), '\n') << "ends at a whole row";
  const std::vector<std::string> lines = linesOf(path);
  ASSERT_GT(lines.size(), 1u);
  for (std::size_t k = 1; k < lines.size(); ++k) EXPECT_EQ(lines[k], std::to_string(k - 1));
  EXPECT_NE(error.find("kept its first " + std::to_string(lines.size() - 1) + " rows"), std::string::npos) << error;
}

// A run whose trace.csv cannot be written past 20 kB (the pre-flight check passed, then the disk
// filled): it stops, trace.csv holds the whole rows written before as a valid CSV, summary.json
// records the error with the rows kept, and the run throws (the command exits 1).
TEST(Trace, ADiskThatFillsDuringTheRunKeepsTheRowsWritten) {
  SessionDesc s = loadSceneFile(resolveScenePath("press-box"));
  s.scene.duration = 2.0;
  SessionOptions o;
  o.out_dir = freshFolder("gf_trace_full").string();
  o.progress = false;
  o.trace_fail_after_bytes = 20000;
  std::string error;
  try {
    runSession(s, o);
  } catch (const std::runtime_error& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("trace.csv: cannot write (disk full?); kept its first"), std::string::npos) << error;
  const CsvTable trace = readTrace(o.out_dir);  // throws if a row were cut
  ASSERT_GT(trace.columns[0].size(), 5u);
  EXPECT_LT(trace.columns[0].size(), 2000u);
  EXPECT_LE(fs::file_size(fs::path(o.out_dir) / kTraceFile), 20000u);
  const nlohmann::json summary = test::summaryOf(o.out_dir);
  EXPECT_NE(summary["error"].get<std::string>().find("kept its first"), std::string::npos) << summary["error"];
}

// record.trace_rate = 100 at 1 kHz: a row every 10 steps, at t = 0.01, 0.02, ..., each the full
// trace's row of that step; 10 times fewer rows.
TEST(Trace, ATraceRateOf100HzWritesEveryTenthStepAtItsTime) {
  const std::string scene = resolveScenePath("press-box");
  SessionOptions o;
  o.progress = false;
  o.out_dir = freshFolder("gf_trace_full_rate").string();
  SessionDesc s = loadSceneFile(scene, std::vector<std::string>{"duration=0.5"});
  runSession(s, o);
  const std::vector<std::string> full = linesOf(fs::path(o.out_dir) / kTraceFile);
  o.out_dir = freshFolder("gf_trace_100hz").string();
  s = loadSceneFile(scene, std::vector<std::string>{"duration=0.5", "record.trace_rate=100"});
  EXPECT_EQ(s.record.trace_rate, 100.0);
  runSession(s, o);
  const std::vector<std::string> thin = linesOf(fs::path(o.out_dir) / kTraceFile);
  ASSERT_EQ(full.size(), 501u);  // the header and 500 steps
  ASSERT_EQ(thin.size(), 51u);
  EXPECT_EQ(thin[0], full[0]);
  for (std::size_t k = 1; k < thin.size(); ++k) EXPECT_EQ(thin[k], full[10 * k]) << "row " << k;
  const CsvTable t = readTrace(o.out_dir);
  for (std::size_t k = 0; k < t.columns[0].size(); ++k) EXPECT_NEAR(t.columns[0][k], 0.01 * (k + 1), 1e-12);
}

// A rate whose steps are not whole, or beyond the haptic rate, is refused naming the field.
TEST(Trace, ATraceRateThatDoesNotDivideTheHapticRateIsRefused) {
  const std::string scene = resolveScenePath("press-box");
  for (const char* bad : {"record.trace_rate=300", "record.trace_rate=2000", "record.trace_rate=0"}) {
    try {
      loadSceneFile(scene, std::vector<std::string>{bad});
      ADD_FAILURE() << bad << " was taken";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "record.trace_rate") << e.what();
    }
  }
  EXPECT_EQ(loadSceneFile(scene, std::vector<std::string>{"record.trace_rate=250"}).record.trace_rate, 250.0);
}

// The projection: a 1 kHz trace of 800 bytes a row over 300 s (240 MB) is warned about with its
// rate an hour and the thinning that divides it by ten; the same over 25 s (20 MB) is not.
TEST(Trace, ALargeTraceIsWarnedAboutWithHowToThinIt) {
  const std::string warning = traceSizeWarning(1000.0, 300.0, 1, 800.0);
  EXPECT_NE(warning.find("2.88 GB an hour"), std::string::npos) << warning;
  EXPECT_NE(warning.find("about 240 MB by the run's end"), std::string::npos) << warning;
  EXPECT_NE(warning.find("--set record.trace_rate=100"), std::string::npos) << warning;
  EXPECT_EQ(traceSizeWarning(1000.0, 25.0, 1, 800.0), "");
  EXPECT_EQ(traceSizeWarning(1000.0, 300.0, 10, 800.0), "") << "24 MB at 100 rows/s";
  EXPECT_EQ(traceStride(1000.0, 0.0), 1);
  EXPECT_EQ(traceStride(1000.0, 100.0), 10);
}

// A trace of an hour's run warns once after its first 1000 rows, on stderr and for summary.json
// (TraceWriter::sizeWarning); the same rows thinned to 10 Hz do not.
TEST(Trace, AnHourLongTraceIsWarnedAboutAfterItsFirstRows) {
  SessionDesc s = loadSceneFile(resolveScenePath("press-box"), std::vector<std::string>{"duration=3600"});
  const sim::World world(s.scene);
  const fs::path dir = freshFolder("gf_trace_warned");
  for (const int every : {1, 100}) {
    TraceWriter trace(world, (dir / kTraceFile).string(), {every, true, 0});
    for (std::size_t k = 0; k < kTraceWatchRows * static_cast<std::size_t>(every); ++k) trace.record(world);
    trace.close();
    const std::string& warning = trace.sizeWarning();
    if (every == 1) {
      EXPECT_NE(warning.find("trace.csv grows"), std::string::npos) << warning;
      EXPECT_NE(warning.find("GB an hour"), std::string::npos) << warning;
    } else {
      EXPECT_EQ(warning, "");
    }
  }
}

}  // namespace
}  // namespace gf::app

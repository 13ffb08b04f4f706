// What a run leaves behind when the user makes a mistake or stops it: every output path checked
// before the first step, one run per output folder, Ctrl-C / SIGTERM / a dead ffmpeg ending with
// valid files for the time reached, and requests that would do nothing said out loud.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

using namespace test;

// `--video missing/x.mp4`: the folder is made before the run, and the run writes everything
// (any file name: here with a space and a quote, ffmpeg is started without a shell).
TEST(Outputs, AVideoInAMissingFolderGetsTheFolder) {
  const fs::path dir = freshFolder("gf_out_missing_video");
  const fs::path video = dir / "missing" / "deeper" / "it's a.mp4";
  ASSERT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + (dir / "run").string() +
                       " --video \"" + video.string() + "\" > /dev/null 2>&1"),
            0);
  EXPECT_GT(videoSeconds(video), 0.15);
  EXPECT_TRUE(fs::exists(dir / "run" / "summary.json"));
  EXPECT_TRUE(fs::exists(dir / "run" / "trace.csv"));
}

// An output path that cannot be written is an error naming it before any step, and what an
// earlier run wrote into --out stays.
TEST(Outputs, AnUnwritablePathFailsBeforeAnyStepAndKeepsEarlierOutputs) {
  const fs::path dir = freshFolder("gf_out_unwritable");
  std::ofstream(dir / "trace.csv") << "earlier\n";
  const fs::path log = dir / "stderr.txt";
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + dir.string() +
                       " --video /proc/godfinger/x.mp4 2> " + log.string() + " > /dev/null"),
            1);
  EXPECT_NE(readFile(log).find("/proc/godfinger"), std::string::npos) << readFile(log);
  EXPECT_EQ(readFile(dir / "trace.csv"), "earlier\n");
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  // A video name ffmpeg cannot tell the format of, or the --out folder itself: the same.
  for (const std::string& video : {(dir / "movie").string(), dir.string()}) {
    EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + dir.string() + " --video " + video +
                         " 2> " + log.string() + " > /dev/null"),
              1);
    EXPECT_NE(readFile(log).find(video), std::string::npos) << readFile(log);
    EXPECT_EQ(readFile(dir / "trace.csv"), "earlier\n");
  }
  // --out under a file: the same, naming the folder.
  std::ofstream(dir / "a-file") << "x";
  EXPECT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.2 --out " + (dir / "a-file" / "out").string() +
                       " 2> " + log.string() + " > /dev/null"),
            1);
  EXPECT_NE(readFile(log).find("a-file"), std::string::npos) << readFile(log);
}

// ffmpeg dying during the run (here an ffmpeg that reads three frames and exits 1) is an error
// message and exit 1, not a SIGPIPE death; trace.csv, forces.csv and summary.json hold the time
// reached, and summary.json the error.
TEST(Outputs, ADeadFfmpegIsAnErrorAndTheOtherOutputsKeepTheTimeReached) {
  const fs::path dir = freshFolder("gf_out_dead_ffmpeg");
  fs::create_directories(dir / "bin");
  {
    std::ofstream fake(dir / "bin" / "ffmpeg");
    fake << "#!/bin/sh\nhead -c 8294400 > /dev/null\nexit 1\n";  // three 1280x720 RGB frames
  }
  fs::permissions(dir / "bin" / "ffmpeg", fs::perms::owner_all);
  const fs::path out = dir / "run", log = dir / "stderr.txt";
  EXPECT_EQ(exitStatus("PATH=" + (dir / "bin").string() + ":$PATH " + kBin + " run " + kFig8 +
                       " --quiet --duration 2 --out " + out.string() + " --video " + (dir / "x.mp4").string() +
                       " 2> " + log.string() + " > /dev/null"),
            1);
  const std::string said = readFile(log);
  EXPECT_NE(said.find("ffmpeg stopped reading frames"), std::string::npos) << said;
  const nlohmann::json summary = summaryOf(out);
  EXPECT_NE(summary["error"].get<std::string>().find("ffmpeg"), std::string::npos);
  EXPECT_FALSE(summary["interrupted"].get<bool>());
  const double reached = summary["time_reached_s"].get<double>();
  EXPECT_LT(reached, 2.0);
  EXPECT_DOUBLE_EQ(lastTraceTime(out), reached);
  EXPECT_TRUE(fs::exists(out / "forces.csv"));
  EXPECT_FALSE(fs::exists(out / "trace.csv.tmp"));
}

// Files that stop growing mid-run (here a 100 kB file size limit, as a full disk would): the run
// stops at the next step, says which file, keeps what still fits (summary.json with the error
// and the time reached) and leaves no temporary file; exit 1.
TEST(Outputs, AFileThatCannotGrowStopsTheRunAndTheRestIsKept) {
#ifdef __SANITIZE_THREAD__
  // ThreadSanitizer's runtime itself dies of a bus error under a 100 kB file-size limit; the
  // release and AddressSanitizer builds run this test.
  GTEST_SKIP() << "not under ThreadSanitizer";
#endif
  const fs::path dir = freshFolder("gf_out_file_limit");
  const fs::path out = dir / "run", log = dir / "stderr.txt";
  EXPECT_EQ(exitStatus("ulimit -f 200; " + kBin + " run " + kFig8 + " --quiet --duration 6 --out " + out.string() + " 2> " +
                       log.string() + " > /dev/null"),
            1);
  const std::string said = readFile(log);
  EXPECT_NE(said.find("trace.csv: cannot write"), std::string::npos) << said;
  const nlohmann::json summary = summaryOf(out);
  EXPECT_NE(summary["error"].get<std::string>().find("cannot write"), std::string::npos);
  EXPECT_LT(summary["time_reached_s"].get<double>(), 6.0);
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name.ends_with(".tmp") || name.ends_with(".part")) << e.path();
  }
}

// A run owns its --out folder: a 0.5 s run after a 1 s run shows 31 frames, not 61, and the
// first run's contact snapshot (at 0.8 s) is gone; files that are not a run's stay.
TEST(Outputs, ARunIntoAUsedFolderShowsOnlyThatRun) {
  const fs::path dir = freshFolder("gf_out_rerun");
  const std::string run = kBin + " run " + kFig8 + " --quiet --frames --out " + dir.string();
  ASSERT_EQ(exitStatus(run + " --duration 1 > /dev/null 2>&1"), 0);
  EXPECT_EQ(countFiles(dir / "frames"), 61);
  EXPECT_TRUE(fs::exists(dir / "contacts" / "t0.800.json"));
  std::ofstream(dir / "notes.txt") << "mine\n";
  std::ofstream(dir / "frames" / "cover.png") << "mine\n";
  ASSERT_EQ(exitStatus(run + " --duration 0.5 > /dev/null 2>&1"), 0);
  EXPECT_EQ(countFiles(dir / "frames"), 31 + 1);  // and cover.png
  EXPECT_FALSE(fs::exists(dir / "frames" / "000031.png"));
  EXPECT_FALSE(fs::exists(dir / "contacts" / "t0.800.json"));
  EXPECT_FALSE(fs::exists(dir / "contacts" / "t0.800-left.png"));
  EXPECT_EQ(readFile(dir / "notes.txt"), "mine\n");
  EXPECT_EQ(readFile(dir / "frames" / "cover.png"), "mine\n");
  EXPECT_DOUBLE_EQ(lastTraceTime(dir), 0.5);
}

// Ctrl-C (and SIGTERM) during a frames + video run: it stops at a step boundary and finishes:
// trace.csv to the time reached, summary.json marked interrupted (and no error: ffmpeg, in a
// process group of its own, does not get the terminal's signal), the MP4 closed so it plays,
// exit 130 (143). The signal goes to the whole process group, as from a terminal, once the run
// has printed its first progress line.
TEST(Outputs, AnInterruptedRunFinishesItsOutputsForTheTimeReached) {
  for (const int signal : {SIGINT, SIGTERM}) {
    const fs::path dir = freshFolder("gf_out_interrupted_" + std::to_string(signal));
    Child c = start(kBin + " run " + kFig8 + " --duration 4 --frames --out " + (dir / "run").string() + " --video " +
                        (dir / "x.mp4").string(),
                    "/dev/null");
    ASSERT_NE(c.lines, nullptr);
    ASSERT_GT(c.pid, 0);
    ASSERT_TRUE(waitForLine(c.lines, "[godfinger]"));  // 10 % of the run done
    ASSERT_EQ(kill(-c.pid, signal), 0);
    EXPECT_EQ(finish(c), 128 + signal);
    const nlohmann::json summary = summaryOf(dir / "run");
    EXPECT_TRUE(summary["interrupted"].get<bool>());
    EXPECT_FALSE(summary.contains("error")) << summary["error"];
    EXPECT_EQ(summary["signal"], signal == SIGINT ? "SIGINT" : "SIGTERM");
    const double reached = summary["time_reached_s"].get<double>();
    EXPECT_GE(reached, 0.4);
    EXPECT_LT(reached, 4.0);
    EXPECT_DOUBLE_EQ(lastTraceTime(dir / "run"), reached);
    const double seconds = videoSeconds(dir / "x.mp4");
    EXPECT_GT(seconds, 0.3) << "the MP4 plays";
    EXPECT_EQ(countFiles(dir / "run" / "frames"), summary["render"]["frames"].get<long>());
  }
}

// Snapshot times past the duration are warnings on stderr and in summary.json.
TEST(Outputs, SnapshotsPastTheEndAreWarnings) {
  const fs::path dir = freshFolder("gf_out_late_snapshots");
  const fs::path log = dir / "stderr.txt";
  ASSERT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --duration 0.5 --out " + (dir / "run").string() + " 2> " +
                       log.string() + " > /dev/null"),
            0);
  const std::string said = readFile(log);
  EXPECT_NE(said.find("warning: record.contacts: 0.8 s is past the run's duration (0.5 s)"), std::string::npos) << said;
  const nlohmann::json warnings = summaryOf(dir / "run")["warnings"];
  ASSERT_EQ(warnings.size(), 2u);  // fig8 records at 0.8 s and 4 s
  EXPECT_NE(warnings[1].get<std::string>().find("4 s"), std::string::npos);
}

// A mistyped finger or body in --set names the ones the scene has, instead of a complaint about
// a new finger's device.
TEST(Outputs, AMistypedFingerOrBodyNamesTheScenesOnes) {
  const fs::path dir = freshFolder("gf_out_typo");
  const fs::path log = dir / "stderr.txt";
  const std::string run = kBin + " run " + kFig8 + " --quiet --duration 0.1 --out " + (dir / "run").string();
  EXPECT_EQ(exitStatus(run + " --set fingers.finger.n_sgo=8 2> " + log.string()), 1);
  EXPECT_NE(readFile(log).find("fingers.finger: no such finger (the scene has: left, right)"), std::string::npos)
      << readFile(log);
  EXPECT_EQ(exitStatus(run + " --set bodies.cylindr.mass=1 2> " + log.string()), 1);
  EXPECT_NE(readFile(log).find("bodies.cylindr: no such body (the scene has: cylinder, ground)"), std::string::npos)
      << readFile(log);
  EXPECT_FALSE(fs::exists(dir / "run"));
}

// Progress to a file is a plain line at every tenth of the run (no carriage returns); --quiet
// prints none; summary.json says what made the result.
TEST(Outputs, ProgressInALogIsPlainLinesAndTheSummarySaysWhatMadeIt) {
  const fs::path dir = freshFolder("gf_out_progress");
  const fs::path log = dir / "stderr.txt";
  ASSERT_EQ(exitStatus(kBin + " run " + kFig8 + " --out " + (dir / "run").string() + " --duration 1 2> " + log.string() +
                       " > /dev/null"),
            0);
  const std::string said = readFile(log);
  EXPECT_EQ(said.find('\r'), std::string::npos);
  int lines = 0;
  for (std::size_t at = said.find("[godfinger]"); at != std::string::npos; at = said.find("[godfinger]", at + 1)) ++lines;
  EXPECT_EQ(lines, 10);
  ASSERT_EQ(exitStatus(kBin + " run " + kFig8 + " --quiet --out " + (dir / "run").string() + " --duration 1 2> " +
                       log.string() + " > /dev/null"),
            0);
  EXPECT_EQ(readFile(log).find("[godfinger]"), std::string::npos);
  const nlohmann::json s = summaryOf(dir / "run");
  EXPECT_EQ(s["godfinger"]["version"], "0.1.0");
  EXPECT_FALSE(s["godfinger"]["commit"].get<std::string>().empty());
  EXPECT_EQ(s["command_line"][1], "run");
  EXPECT_EQ(s["command_line"].back(), "1");
  EXPECT_EQ(s["scene_file_fnv1a64"].get<std::string>().size(), 16u);
  EXPECT_TRUE(s["measures"].contains("bodies.cylinder.max_rotation_deg"));
}

// `patch`: a point off the surface is an error giving its distance; without --normal the closest
// face's normal is used; the output says why a patch has fewer SGOs than asked.
TEST(Outputs, PatchNamesAFarPointAndExplainsMissingSgos) {
  const fs::path dir = freshFolder("gf_out_patch");
  {
    std::ofstream cube(dir / "cube.obj");  // a 2 cm cube, outward faces
    cube << "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
            "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
            "f 4 1 5\nf 4 5 8\n";
  }
  const std::string patch = kBin + " patch --mesh " + (dir / "cube.obj").string() + " --scale 0.01 --push 0,-0.002,0";
  const fs::path said = dir / "said.txt";
  EXPECT_EQ(exitStatus(patch + " --point 5,5,5 --out " + (dir / "far").string() + " > " + said.string() + " 2>&1"), 1);
  EXPECT_NE(readFile(said).find("--point: is 8.6"), std::string::npos) << readFile(said);
  EXPECT_NE(readFile(said).find("from the mesh surface"), std::string::npos) << readFile(said);
  EXPECT_FALSE(fs::exists(dir / "far" / "patch.json"));
  // The middle of the top face, no --normal: all 8 SGOs, nothing to explain.
  ASSERT_EQ(exitStatus(patch + " --point 0.001,0.01,0.002 --out " + (dir / "top").string() + " > " + said.string()), 0);
  EXPECT_NE(readFile(said).find("8 of 8 SGOs;"), std::string::npos) << readFile(said);
  const nlohmann::json top = nlohmann::json::parse(readFile(dir / "top" / "patch.json"));
  EXPECT_EQ(top["normal_from"].get<std::string>().rfind("closest face", 0), 0u);
  EXPECT_EQ(top["explanation"], "");
  // A corner: radial vectors pointing off it are dropped, and the output says so.
  ASSERT_EQ(exitStatus(patch + " --point 0.01,0.01,0.01 --out " + (dir / "corner").string() + " > " + said.string()), 0);
  const nlohmann::json corner = nlohmann::json::parse(readFile(dir / "corner" / "patch.json"));
  EXPECT_LT(corner["sgos"].size(), 8u);
  EXPECT_NE(corner["explanation"].get<std::string>().find("the hit is on a vertex"), std::string::npos);
  EXPECT_NE(corner["explanation"].get<std::string>().find("were dropped"), std::string::npos);
  EXPECT_NE(readFile(said).find("were dropped"), std::string::npos) << readFile(said);
}

// `godfinger plot`: trace columns against time into a PNG; a missing column or a cell that is
// not a number names the file, line and column.
TEST(Outputs, PlotDrawsTraceColumnsAndNamesBadOnes) {
  const fs::path dir = freshFolder("gf_out_plot");
  std::ofstream(dir / "trace.csv") << "t,a.x,a.y\n0,1,2\n0.001,1.5,\n0.002,2,2.5\n";
  const fs::path said = dir / "said.txt";
  ASSERT_EQ(exitStatus(kBin + " plot " + (dir / "trace.csv").string() + " --y a.x --y a.y > " + said.string()), 0);
  EXPECT_TRUE(fs::exists(dir / "plot.png"));
  EXPECT_EQ(exitStatus(kBin + " plot " + (dir / "trace.csv").string() + " --y a.z 2> " + said.string()), 1);
  EXPECT_NE(readFile(said).find("trace.csv:1: a.z: no such column (the file has: t, a.x, a.y)"), std::string::npos)
      << readFile(said);
  std::ofstream(dir / "bad.csv") << "t,a.x\n0,1\n0.001,oops\n";
  EXPECT_EQ(exitStatus(kBin + " plot " + (dir / "bad.csv").string() + " --y a.x 2> " + said.string()), 1);
  EXPECT_NE(readFile(said).find("bad.csv:3:2: a.x: expected a number, got 'oops'"), std::string::npos) << readFile(said);
}

// A device that starts inside a body puts the proxy there (a 1 cm proxy centre 2 cm into a
// 3 cm ball): a warning naming the finger, the body and the depth, on stderr and in
// summary.json; a proxy starting in the air is not.
TEST(Outputs, AProxyStartingInsideABodyIsAWarning) {
  const fs::path dir = freshFolder("gf_out_proxy_inside");
  const auto scene = [&](double y) {
    std::ofstream(dir / "scene.toml") << "name = \"inside\"\nduration = 0.01\neffects = [\"gravity\"]\n"
                                         "[bodies.ball]\nshape = \"sphere\"\nradius = 0.03\nstatic = true\n"
                                         "[fingers.index]\nproxy_radius = 0.01\n"
                                         "[fingers.index.device]\nkeyframes = [{ t = 0.0, p = [0, "
                                      << y << ", 0] }]\n";
  };
  const fs::path log = dir / "stderr.txt";
  scene(0.01);  // 2 cm inside the ball's surface, plus the proxy's 1 cm radius: 30 mm
  ASSERT_EQ(exitStatus(kBin + " run " + (dir / "scene.toml").string() + " --quiet --expectations report --out " +
                       (dir / "run").string() + " 2> " + log.string() + " > /dev/null"),
            0);
  EXPECT_NE(readFile(log).find("warning: fingers.index's proxy starts 30.0 mm inside bodies.ball"), std::string::npos)
      << readFile(log);
  EXPECT_EQ(summaryOf(dir / "run")["warnings"].size(), 1u);
  scene(0.05);
  ASSERT_EQ(exitStatus(kBin + " run " + (dir / "scene.toml").string() + " --quiet --out " + (dir / "run").string() +
                       " 2> " + log.string() + " > /dev/null"),
            0);
  EXPECT_EQ(readFile(log).find("inside bodies"), std::string::npos) << readFile(log);
  EXPECT_TRUE(summaryOf(dir / "run")["warnings"].empty());
}

// A body that starts inside the ground (a 3 cm ball with its centre 2.5 cm up: 5 mm in) is a
// warning on stderr and in summary.json; one resting on it (centre 3 cm up) is not.
TEST(Outputs, ABodyStartingInsideAnotherIsAWarning) {
  const fs::path dir = freshFolder("gf_out_overlap");
  const auto scene = [&](double y) {
    std::ofstream(dir / "scene.toml") << "name = \"overlap\"\nduration = 0.01\neffects = [\"gravity\"]\n"
                                         "[bodies.ground]\nshape = \"plane\"\n"
                                         "[bodies.ball]\nshape = \"sphere\"\nradius = 0.03\nmass = 0.1\nposition = [0, "
                                      << y << ", 0]\n";
  };
  const fs::path log = dir / "stderr.txt";
  scene(0.025);
  ASSERT_EQ(exitStatus(kBin + " run " + (dir / "scene.toml").string() + " --quiet --out " + (dir / "run").string() +
                       " 2> " + log.string() + " > /dev/null"),
            0);
  EXPECT_NE(readFile(log).find("warning: bodies.ground and bodies.ball start 5.0 mm inside each other"), std::string::npos)
      << readFile(log);
  EXPECT_EQ(summaryOf(dir / "run")["warnings"].size(), 1u);
  scene(0.03);
  ASSERT_EQ(exitStatus(kBin + " run " + (dir / "scene.toml").string() + " --quiet --out " + (dir / "run").string() +
                       " 2> " + log.string() + " > /dev/null"),
            0);
  EXPECT_EQ(readFile(log).find("inside each other"), std::string::npos) << readFile(log);
  EXPECT_TRUE(summaryOf(dir / "run")["warnings"].empty());
}

// Bare `godfinger` prints the usage with the commands.
TEST(Outputs, BareGodfingerPrintsTheUsage) {
  const fs::path dir = freshFolder("gf_out_bare");
  EXPECT_EQ(exitStatus(kBin + " > " + (dir / "usage.txt").string() + " 2>&1"), 1);
  const std::string usage = readFile(dir / "usage.txt");
  for (const char* command : {"Usage: godfinger", "run", "patch", "study", "check", "list", "live"}) {
    EXPECT_NE(usage.find(command), std::string::npos) << command;
  }
}

// `live`: Ctrl-C stops a long `step N` at a step boundary, answers, and ends with 130.
TEST(Outputs, AnInterruptedLiveSessionEndsWith130) {
  const fs::path dir = freshFolder("gf_out_live");
  std::ofstream(dir / "input.txt") << "step 10000000\nstate\n";
  // live answers on stdout: read that (stderr to a file) to know it started.
  std::FILE* lines = popen(("sh -c 'echo $$; exec setsid " + kBin + " live " + kFig8 + " --out " + dir.string() + " < " +
                            (dir / "input.txt").string() + " 2> " + (dir / "stderr.txt").string() + "'")
                               .c_str(),
                           "r");
  ASSERT_NE(lines, nullptr);
  char line[8192] = {};
  ASSERT_NE(std::fgets(line, sizeof line, lines), nullptr);
  const pid_t pid = static_cast<pid_t>(std::atol(line));
  ASSERT_TRUE(waitForLine(lines, "ok ready"));
  ASSERT_EQ(kill(-pid, SIGINT), 0);
  std::string rest;
  while (std::fgets(line, sizeof line, lines)) rest += line;
  const int status = pclose(lines);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_NE(rest.find("error: interrupted by SIGINT"), std::string::npos) << rest;
}

}  // namespace
}  // namespace gf::app

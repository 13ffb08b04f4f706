// The `godfinger` command line: bad input exits non-zero and keeps what an earlier run wrote.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

// The command line: a bad scene or override exits non-zero and leaves an earlier run's files.
TEST(Command, BadInputExitsNonZeroAndKeepsEarlierOutputs) {
  namespace fs = std::filesystem;
  const fs::path out = gf::test::scratchRoot() / "gf_command_out";
  fs::remove_all(out);
  fs::create_directories(out);
  std::ofstream(out / "trace.csv") << "earlier\n";
  const std::string bin = std::string(GF_BINARY_DIR) + "/godfinger";
  const std::string run = bin + " run " + GF_SOURCE_DIR + "/assets/scenes/fig5-push-ball.toml --out " +
                          out.string() + " ";
  EXPECT_NE(std::system((run + "--set fingers.index.n_sgo=nan 2>/dev/null").c_str()), 0);
  EXPECT_NE(std::system((run + "--set bodies.ball.mesh_file=x 2>/dev/null").c_str()), 0);
  EXPECT_NE(std::system((bin + " run no-such-scene --out " + out.string() + " 2>/dev/null").c_str()), 0);
  std::ifstream in(out / "trace.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "earlier");
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

// `godfinger check`: every bundled scene meets its [expect] (the paper scenes expect what their
// figures show) but the live-device ones (UDP, browser), skipped with a SKIP line, and a scene that does not (Fig. 6 with a god-object: the tile tips over) is a
// FAIL line naming the expectation, with exit 1.
TEST(Command, CheckPassesTheBundledScenesAndFailsAGodObjectLift) {
  namespace fs = std::filesystem;
  const fs::path out = gf::test::scratchRoot() / "gf_check_out";
  fs::remove_all(out);
  const std::string bin = std::string(GF_BINARY_DIR) + "/godfinger";
#ifdef GF_UNDER_SANITIZER
  // The soft bodies' scenes take minutes whole under the sanitizers: each scene's first second.
  const std::string cap = " --max-duration 1";
#else
  const std::string cap;
#endif
  const std::string all = bin + " check " + GF_SOURCE_DIR + "/assets/scenes --jobs 2" + cap + " --out " + out.string() +
                          " > " + (out.string() + ".txt");
  ASSERT_EQ(std::system(all.c_str()), 0);
  std::ifstream listing(out.string() + ".txt");
  std::string line;
  int passed = 0, skipped = 0;
  while (std::getline(listing, line)) {
    passed += line.rfind("PASS ", 0) == 0;
    if (line.rfind("SKIP ", 0) == 0) {
      ++skipped;
      EXPECT_TRUE(line.rfind("SKIP  device-udp ", 0) == 0 || line.rfind("SKIP  live-view ", 0) == 0)
          << "only the live-device scenes are skipped: " << line;
    }
  }
  EXPECT_EQ(skipped, 2);
  EXPECT_EQ(passed + skipped,
            static_cast<int>(std::distance(fs::directory_iterator(std::string(GF_SOURCE_DIR) + "/assets/scenes"),
                                           fs::directory_iterator{})) - 1)  // all but README.md
      << "every bundled scene passes";

  // Fig. 6 with a god-object, as a scene file of its own.
  const fs::path dir = gf::test::scratchRoot() / "gf_check_scenes";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream in(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig6-lift-one-finger.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::size_t at = scene.find("n_sgo = 8");
  ASSERT_NE(at, std::string::npos);
  scene.replace(at, 9, "n_sgo = 0");
  std::ofstream(dir / "fig6-god-object.toml") << scene;
  const std::string one = bin + " check " + dir.string() + " --out " + out.string() + " > " + (out.string() + ".txt");
  EXPECT_NE(std::system(one.c_str()), 0);
  std::ifstream result(out.string() + ".txt");
  std::getline(result, line);
  EXPECT_EQ(line.rfind("FAIL  fig6-god-object", 0), 0u) << line;
  EXPECT_NE(line.find("bodies.tile."), std::string::npos) << line;
}

// `godfinger --version`: the version and commit, the physics and mesh libraries, and the GL the
// frames are drawn with; exit 0 (no subcommand needed).
// `--max-duration`, the sanitizer builds' short variant of a long scene: the 5 min hold cut at
// 0.5 s runs 0.5 s, keeps its limits checked during the run and leaves `ends_above` (the lift's
// end, 0.08 m) unchecked; `--duration 0.5` is the scene shortened as it stands, so that limit
// fails (exit 3). A scene shorter than the cap runs whole and is not marked cut short.
TEST(Command, MaxDurationCutsALongSceneAndLeavesItsEndOfRunLimitsUnchecked) {
  namespace fs = std::filesystem;
  const fs::path out = gf::test::scratchRoot() / "gf_max_duration";
  fs::remove_all(out);
  const std::string bin = std::string(GF_BINARY_DIR) + "/godfinger";
  const std::string hold = bin + " run " + GF_SOURCE_DIR + "/assets/hard-cases/pinch-hold-5min.toml --quiet ";
  ASSERT_EQ(std::system((hold + "--max-duration 0.5 --out " + (out / "cut").string() + " > /dev/null").c_str()), 0);
  std::ifstream in(out / "cut" / "summary.json");
  const nlohmann::json cut = nlohmann::json::parse(in);
  EXPECT_NEAR(cut.at("time_reached_s").get<double>(), 0.5, 1e-9);
  EXPECT_TRUE(cut.value("cut_short", false));
  int during = 0;  // limits checked at every step: still checked
  for (const nlohmann::json& c : cut.at("expectations").at("checks")) {
    const std::string name = c.at("name");
    if (name == "bodies.cylinder.ends_above") {
      EXPECT_FALSE(c.at("checked").get<bool>()) << name;
    }
    if (name == "finite" || name == "max_speed" || name == "max_angular_speed" ||
        name.find(".port_energy") != std::string::npos || name.find(".no_tunnelling") != std::string::npos) {
      EXPECT_TRUE(c.at("checked").get<bool>()) << name;
      ++during;
    }
    EXPECT_TRUE(c.at("passed").get<bool>()) << name;
  }
  EXPECT_EQ(during, 7) << "finite, both speeds, and each finger's port energy and tunnelling";
  const int whole = std::system((hold + "--duration 0.5 --out " + (out / "short").string() + " > /dev/null 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(whole));
  EXPECT_EQ(WEXITSTATUS(whole), 3) << "ends_above fails on a run shortened without --max-duration";
  const std::string tetra = bin + " run " + GF_SOURCE_DIR + "/assets/hard-cases/tetrahedron.toml --quiet ";
  ASSERT_EQ(std::system((tetra + "--max-duration 100 --out " + (out / "whole").string() + " > /dev/null").c_str()), 0);
  std::ifstream whole_in(out / "whole" / "summary.json");
  const nlohmann::json full = nlohmann::json::parse(whole_in);
  EXPECT_NEAR(full.at("time_reached_s").get<double>(), 1.5, 1e-9);
  EXPECT_FALSE(full.contains("cut_short"));
}

TEST(Command, VersionNamesTheBuildAndItsLibraries) {
  const std::string command = std::string(GF_BINARY_DIR) + "/godfinger --version";
  std::FILE* p = popen(command.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string text;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, p)) text += buffer;
  EXPECT_EQ(pclose(p), 0) << text;
  for (const char* needed : {"godfinger 0.1.0 (commit ", "Bullet 3.", "(double precision)", "assimp 5.", "Eigen 3.",
                             "OpenGL ", "(OSMesa, offscreen)"}) {
    EXPECT_NE(text.find(needed), std::string::npos) << "no '" << needed << "' in:\n" << text;
  }
}

// `godfinger schema`: a JSON Schema every bundled scene and hard case meets, and that catches the
// mistakes an editor should underline: a misspelt field, a value out of its range, an unknown
// shape or effect, a device with two sources (checked with python3-jsonschema).
TEST(Command, SchemaAcceptsTheBundledScenesAndCatchesMistakes) {
  namespace fs = std::filesystem;
  const fs::path dir = gf::test::scratchRoot() / "gf_schema";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string schema = (dir / "schema.json").string();
  ASSERT_EQ(std::system((std::string(GF_BINARY_DIR) + "/godfinger schema > " + schema).c_str()), 0);
  const std::string validate = std::string(GF_PYTHON3) + " " + GF_SOURCE_DIR + "/tests/app/validate_schema.py " + schema + " ";
  const std::string assets = std::string(GF_SOURCE_DIR) + "/assets/";
  EXPECT_EQ(std::system((validate + "'" + assets + "scenes/*.toml' '" + assets + "hard-cases/*.toml' > " +
                         (dir / "bundled.txt").string()).c_str()),
            0)
      << std::ifstream(dir / "bundled.txt").rdbuf();
  std::ifstream in(assets + "scenes/press-box.toml");
  std::stringstream text;
  text << in.rdbuf();
  const std::string good = text.str();
  const auto mistake = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string scene = good;
    const std::size_t at = scene.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene.replace(at, from.size(), to);
    std::ofstream(dir / (name + ".toml")) << scene;
    EXPECT_NE(std::system((validate + (dir / (name + ".toml")).string() + " > /dev/null").c_str()), 0) << name;
  };
  mistake("misspelt-field", "n_sgo =", "n_sog =");
  mistake("out-of-range", "n_sgo = 8", "n_sgo = 1000");
  mistake("unknown-shape", "shape = \"box\"", "shape = \"cube\"");
  mistake("unknown-effect", "\"gravity\"", "\"gravitation\"");
  mistake("two-device-sources", "keyframes = [", "csv = \"x.csv\"\nkeyframes = [");
  mistake("negative-mass", "mass = ", "mass = -");
  mistake("tilt-beyond-half-turn", "keyframes = [", "tilt_deg = 200\nkeyframes = [");
  mistake("three-number-q", "p = [", "q = [1, 0, 0], p = [");
}

// `godfinger bench realtime`: each round's sleeper and loop are in bench.json, every wake-up and
// step counted, and the headline shares pooled over the rounds with their difference. Wall-clock
// values are checked for consistency only. A value out of range is refused before anything runs.
TEST(Command, BenchRealtimeReportsTheLoopBesideTheSleeper) {
  namespace fs = std::filesystem;
  const fs::path out = gf::test::scratchRoot() / "gf_bench_realtime";
  fs::remove_all(out);
  const std::string bin = std::string(GF_BINARY_DIR) + "/godfinger bench realtime ";
  ASSERT_EQ(std::system((bin + "fig7-side-pick --duration 0.2 --rounds 2 --no-frames --no-fifo --out " + out.string() +
                         " > " + (out.string() + ".txt")).c_str()),
            0);
  std::ifstream in(out / "bench.json");
  const nlohmann::json b = nlohmann::json::parse(in);
  ASSERT_EQ(b["rounds"].size(), 2u);
  long sleeper_late = 0, loop_late = 0;
  for (const nlohmann::json& r : b["rounds"]) {
    EXPECT_EQ(r["sleeper"]["wakeups"], 200);
    EXPECT_EQ(r["loop"]["histograms"]["lateness"]["counts"].get<std::vector<long>>().size(), 14u);
    EXPECT_TRUE(fs::exists(fs::path(r["run_folder"].get<std::string>()) / "summary.json"));
    sleeper_late += r["sleeper"]["late"].get<long>();
    loop_late += r["loop"]["late_steps"].get<long>();
  }
  EXPECT_DOUBLE_EQ(b["sleeper_late_percent"].get<double>(), 100.0 * sleeper_late / 400.0);
  EXPECT_DOUBLE_EQ(b["loop_late_percent"].get<double>(), 100.0 * loop_late / 400.0);
  EXPECT_DOUBLE_EQ(b["difference_points"].get<double>(),
                   b["loop_late_percent"].get<double>() - b["sleeper_late_percent"].get<double>());
  EXPECT_NE(std::system((bin + "--rounds 0 --out " + out.string() + " 2>/dev/null").c_str()), 0);
}

// `--set` with a control character (a newline would start a second TOML line and set a field
// unseen) is refused naming --set and the field, the character written out; a tab (TOML's
// whitespace) is taken. Nothing is written.
TEST(Command, ASetWithANewlineIsRefusedNamingTheField) {
  namespace fs = std::filesystem;
  const fs::path out = gf::test::scratchRoot() / "gf_set_newline";
  fs::remove_all(out);
  const std::string run = std::string(GF_BINARY_DIR) + "/godfinger run press-box --quiet --out " + out.string() + " ";
  const std::string log = out.string() + ".txt";
  EXPECT_EQ(WEXITSTATUS(std::system((run + "--set \"$(printf 'duration=0.05\\nfingers.index.r_max = 0.5')\" 2> " + log).c_str())), 1);
  std::ifstream in(log);
  const std::string said((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(said.find("--set duration=0.05\\nfingers.index.r_max = 0.5: duration: holds a control character (0x0a, "
                      "a newline) at byte 13"),
            std::string::npos)
      << said;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  EXPECT_NE(WEXITSTATUS(std::system((run + "--set \"$(printf 'duration=0.05\\r')\" 2> /dev/null").c_str())), 0);
  EXPECT_NE(WEXITSTATUS(std::system((run + "--set \"$(printf 'duration=0.05\\177')\" 2> /dev/null").c_str())), 0);
  EXPECT_EQ(WEXITSTATUS(std::system((run + "--set \"$(printf 'duration=\\t0.05')\" > /dev/null 2>&1").c_str())), 0);
}

// Without --out, every command writes under out/ of the folder it runs in: `run` into
// out/run-SCENE, `check` into out/check (never the source tree or the data's folder).
TEST(Command, DefaultOutputsGoUnderOutOfTheCurrentFolder) {
  namespace fs = std::filesystem;
  const fs::path here = gf::test::scratchRoot() / "gf_default_out";
  fs::remove_all(here);
  fs::create_directories(here);
  const std::string bin = std::string(GF_BINARY_DIR) + "/godfinger";
  const std::string cd = "cd '" + here.string() + "' && " + bin;
  ASSERT_EQ(WEXITSTATUS(std::system((cd + " run press-box --quiet --duration 0.05 > /dev/null").c_str())), 0);
  EXPECT_TRUE(fs::exists(here / "out" / "run-press-box" / "summary.json"));
  ASSERT_EQ(WEXITSTATUS(std::system((cd + " check press-box --max-duration 0.05 > /dev/null").c_str())), 0);
  EXPECT_TRUE(fs::exists(here / "out" / "check" / "press-box" / "summary.json"));
  std::vector<std::string> top;
  for (const fs::directory_entry& e : fs::directory_iterator(here)) top.push_back(e.path().filename().string());
  EXPECT_EQ(top, std::vector<std::string>{"out"});
}

}  // namespace
}  // namespace gf::app

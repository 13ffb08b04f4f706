// `godfinger live`: one answer per line, errors naming the input line.
#include "app/session/live.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include <filesystem>
#include <sstream>
#include "tests/scratch.hpp"

namespace gf::app {
namespace {

namespace fs = std::filesystem;

// What a live session of fig7-side-pick answers to `input`, a line each, with its exit code.
struct Answers {
  std::vector<std::string> lines;
  int exit_code = 0;
  std::string out_dir;
};

Answers runFig7SidePick(const std::string& input, const std::string& out_name) {
  LiveOptions o;
  o.scene_path = std::string(GF_SOURCE_DIR) + "/assets/scenes/fig7-side-pick.toml";
  o.out_dir = (gf::test::scratchRoot() / out_name).string();
  std::istringstream in(input);
  std::ostringstream out;
  Answers a;
  a.exit_code = runLive(o, in, out);
  a.out_dir = o.out_dir;
  std::istringstream answers(out.str());
  for (std::string l; std::getline(answers, l);) a.lines.push_back(l);
  return a;
}

TEST(Live, AnswersEachLineAndReportsBadCommands) {
  const Answers a = runFig7SidePick(
      "step 600\nset fingers.left.n_sgo=0\nmove right 0.05 0.05 0 0.1\nstep 10\nsnapshot s1\n"
      "jump\nset fingers.left.n_sgo=2\nquit\nstep\n",
      "gf_live");
  const std::vector<std::string>& lines = a.lines;
  EXPECT_EQ(a.exit_code, 1) << "two bad lines";
  ASSERT_EQ(lines.size(), 9u);  // ready + 8 answers; nothing after quit
  EXPECT_NE(lines[1].find("\"t\":0.6"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[2], "ok fingers.left.n_sgo=0");
  EXPECT_EQ(lines[6].rfind("error: <stdin>:6: unknown command 'jump'", 0), 0u) << lines[6];
  EXPECT_NE(lines[7].find("<stdin>:7"), std::string::npos) << lines[7];
  EXPECT_NE(lines[7].find("fingers.left.n_sgo"), std::string::npos) << lines[7];
  EXPECT_TRUE(fs::exists(fs::path(a.out_dir) / "contacts" / "s1.json"));
}

// `set` takes the live finger settings only, in the unit of the scene files, and checks each
// with its validator.
TEST(Live, SetChecksEachLiveSettingWithItsValidator) {
  const Answers a = runFig7SidePick(
      "set fingers.left.tau_a=30\nset fingers.left.proxy_mass=1\nset fingers.left.n_sgo=2\n"
      "set fingers.left.r_max=x\nset fingers.thumb.n_sgo=4\nstep 400\n",
      "gf_live_set");
  const std::vector<std::string>& lines = a.lines;
  EXPECT_EQ(a.exit_code, 1);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[1], "ok fingers.left.tau_a=30");
  EXPECT_NE(lines[2].find("FIELD one of n_sgo, r_max, d0, alpha, stretch_length, max_stretch, tau_a, friction"),
            std::string::npos)
      << lines[2];
  EXPECT_NE(lines[3].find("fingers.left.n_sgo: must be 0 (god-object) or 3..64"), std::string::npos) << lines[3];
  EXPECT_NE(lines[4].find("expected a number, got 'x'"), std::string::npos) << lines[4];
  EXPECT_NE(lines[5].find("no finger called 'thumb'"), std::string::npos) << lines[5];
  EXPECT_EQ(lines[6].rfind("ok {", 0), 0u) << lines[6];
}

// A bad line gets exactly one error reply and changes nothing: an out-of-range or fractional
// step count, extra words, a non-finite position, arguments to quit.
TEST(Live, BadLinesGetOneErrorAndChangeNothing) {
  const Answers a = runFig7SidePick(
      "step 99999999999999999999999\nstep 1.5\nstep 2 3\nmove left 0 0.03 0 1 extra\n"
      "move left 0 0.03 0 1e400\nquit now\nstep 2\nquit\n",
      "gf_live_bad_lines");
  ASSERT_EQ(a.lines.size(), 9u);  // "ok ready", six errors, the state after two steps, "ok bye"
  for (std::size_t i = 1; i <= 6; ++i) EXPECT_EQ(a.lines[i].rfind("error: <stdin>:" + std::to_string(i) + ":", 0), 0u) << a.lines[i];
  EXPECT_NE(a.lines[7].find("\"t\":0.002"), std::string::npos) << "only the good line stepped: " << a.lines[7];
  EXPECT_EQ(a.lines[8], "ok bye");
  EXPECT_EQ(a.exit_code, 1);
}

// `state` lists every dynamic body with its pose and velocities (the static ground is left out):
// the box of fig7-side-pick, resting where the scene puts it before the fingers arrive.
TEST(Live, StateListsEveryDynamicBody) {
  const Answers a = runFig7SidePick("step 100\nstate\n", "gf_live_state");
  ASSERT_EQ(a.lines.size(), 3u);
  ASSERT_EQ(a.lines[2].rfind("ok {", 0), 0u) << a.lines[2];
  const nlohmann::json state = nlohmann::json::parse(a.lines[2].substr(3));
  EXPECT_NEAR(state["t"].get<double>(), 0.1, 1e-12);
  ASSERT_EQ(state["bodies"].size(), 1u);
  const nlohmann::json& box = state["bodies"][0];
  EXPECT_EQ(box["name"], "box");
  EXPECT_NEAR(box["position"][0].get<double>(), 0.0, 1e-4);
  EXPECT_NEAR(box["position"][1].get<double>(), 0.04, 1e-3);  // half height 4 cm, on the ground
  double norm = 0.0;
  for (const nlohmann::json& c : box["orientation"]) norm += c.get<double>() * c.get<double>();
  EXPECT_NEAR(norm, 1.0, 1e-9);
  EXPECT_NEAR(box["orientation"][3].get<double>(), 1.0, 1e-4);  // w: upright
  EXPECT_EQ(box["velocity"].size(), 3u);
  EXPECT_EQ(box["angular_velocity"].size(), 3u);
  EXPECT_LT(std::abs(box["velocity"][1].get<double>()), 0.01);  // at rest
}

}  // namespace
}  // namespace gf::app

// A web experiment (app/experiment/web_participant.hpp) without a browser: the questionnaire's
// answers read and each bad one named, and the command line's checks of --participant. The page
// itself, a person's session and its resume are tests/browser/experiment_test.py.
#include "app/experiment/web_participant.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tests/app/run_helpers.hpp"

namespace gf::app {
namespace {

using test::exitStatus;
using test::freshFolder;
using test::kBin;
using test::readFile;

const std::string kPilot = std::string(GF_SOURCE_DIR) + "/tests/browser/experiment/pilot.toml";
const std::string kAll = "answers mental_demand=35 physical_demand=20 temporal_demand=55 performance=10 effort=40 frustration=5 realism=6";

std::string whyNot(const std::string& line) {
  std::string why;
  return parseAnswers(line, 1, why) ? "read" : why;
}

TEST(WebParticipant, AnswersAreReadAndEachBadOneNamed) {
  std::string why;
  const std::optional<BlockAnswers> a = parseAnswers(kAll, 2, why);
  ASSERT_TRUE(a) << why;
  EXPECT_EQ(a->block, 2);
  EXPECT_EQ(a->tlx, (std::array<int, 6>{35, 20, 55, 10, 40, 5}));
  EXPECT_EQ(a->realism, 6);
  EXPECT_DOUBLE_EQ(a->rawTlx(), (35.0 + 20 + 55 + 10 + 40 + 5) / 6.0);  // Raw TLX: the unweighted mean
  // Any order; the scales' ends are legal.
  EXPECT_EQ(whyNot("answers realism=1 frustration=100 effort=0 performance=0 temporal_demand=0 physical_demand=0 mental_demand=0"),
            "read");
  EXPECT_EQ(whyNot("ready"), "expected: answers mental_demand=0..100 ... frustration=0..100 realism=1..7");
  EXPECT_EQ(whyNot("answers mental_demand=35"), "answers: physical_demand is missing");
  EXPECT_EQ(whyNot(kAll.substr(0, kAll.find(" realism"))), "answers: realism is missing");
  EXPECT_EQ(whyNot(kAll + " effort=40"), "answers: effort given twice");
  EXPECT_EQ(whyNot(kAll + " comfort=3"), "answers: unknown scale 'comfort'");
  EXPECT_EQ(whyNot("answers mental_demand=101"), "answers: mental_demand must be a whole number in 0..100");
  EXPECT_EQ(whyNot("answers mental_demand=-5"), "answers: mental_demand must be a whole number in 0..100");
  EXPECT_EQ(whyNot("answers mental_demand=3.5"), "answers: mental_demand must be a whole number in 0..100");
  EXPECT_EQ(whyNot("answers mental_demand"), "answers: mental_demand must be a whole number in 0..100");
  EXPECT_EQ(whyNot("answers realism=8"), "answers: realism must be a whole number in 1..7");
  EXPECT_EQ(whyNot("answers realism=0"), "answers: realism must be a whole number in 1..7");
}

// A web experiment runs one participant a session, one the experiment has; a simulated one runs
// them all. Each refusal names the option, exits 1 and writes nothing.
TEST(WebParticipant, TheCommandLineNeedsAParticipantOfAWebExperiment) {
  const auto fs_out = freshFolder("gf_web_participant_cli");
  const std::string out = (fs_out / "out").string(), said = (fs_out / "said.txt").string();
  const auto refused = [&](const std::string& args, const std::string& text) {
    EXPECT_EQ(exitStatus(kBin + " experiment " + args + " --out " + out + " > " + said + " 2>&1"), 1) << args;
    EXPECT_NE(readFile(said).find(text), std::string::npos) << args << ": " << readFile(said);
    EXPECT_FALSE(std::filesystem::exists(out)) << args << ": wrote its folder";
  };
  refused(kPilot, "--participant: missing: an experiment of people (device = \"web\") runs one participant a session");
  refused(kPilot + " --participant 3", "--participant: 3: the experiment has 2 participants");
  refused(kPilot + " --participant 1 --serve 70000", "--serve");
  refused("noise-sweep --participant 1", "--participant: is for an experiment of people");
  refused("noise-sweep --serve 8081", "--serve: is for an experiment of people");
}

}  // namespace
}  // namespace gf::app

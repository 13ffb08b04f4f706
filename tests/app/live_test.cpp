// `godfinger live`: one answer per line, errors naming the input line.
#include "app/live.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

namespace gf::app {
namespace {

namespace fs = std::filesystem;

TEST(Live, AnswersEachLineAndReportsBadCommands) {
  LiveOptions o;
  o.scene_path = std::string(GF_SOURCE_DIR) + "/assets/scenes/fig7-side-pick.toml";
  o.out_dir = (fs::temp_directory_path() / "gf_live").string();
  std::istringstream in(
      "step 600\nset fingers.left.n_sgo=0\nmove right 0.05 0.05 0 0.1\nstep 10\nsnapshot s1\n"
      "jump\nset fingers.left.n_sgo=2\nquit\nstep\n");
  std::ostringstream out;
  EXPECT_EQ(runLive(o, in, out), 1) << "two bad lines";
  std::vector<std::string> lines;
  std::istringstream answers(out.str());
  for (std::string l; std::getline(answers, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9u) << out.str();  // ready + 8 answers; nothing after quit
  EXPECT_NE(lines[1].find("\"t\":0.6"), std::string::npos) << lines[1];
  EXPECT_EQ(lines[2], "ok fingers.left.n_sgo=0");
  EXPECT_EQ(lines[6].rfind("error: <stdin>:6: unknown command 'jump'", 0), 0u) << lines[6];
  EXPECT_NE(lines[7].find("<stdin>:7"), std::string::npos) << lines[7];
  EXPECT_NE(lines[7].find("fingers.left.n_sgo"), std::string::npos) << lines[7];
  EXPECT_TRUE(fs::exists(fs::path(o.out_dir) / "contacts" / "s1.json"));
}
}  // namespace
}  // namespace gf::app

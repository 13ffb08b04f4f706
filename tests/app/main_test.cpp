// The `godfinger` command line: bad input exits non-zero and keeps what an earlier run wrote.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace gf::app {
namespace {

// The command line: a bad scene or override exits non-zero and leaves an earlier run's files.
TEST(Command, BadInputExitsNonZeroAndKeepsEarlierOutputs) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / "gf_command_out";
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

}  // namespace
}  // namespace gf::app

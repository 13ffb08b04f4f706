// Inputs the fuzz targets (tests/fuzz) crashed on, in the scene, study and live readers: each
// now gives a clean result or a named error. Run by gf_app_tests (GCC); the inputs are inline or
// in tests/fuzz/corpus/.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "app/scene/scene_file.hpp"
#include "app/study/study.hpp"

namespace gf::app {
namespace {

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// fuzz_study: eight axes of ten values listed 1e8 runs, and loaded a scene for each, before the
// first ran: the expansion ran out of memory. A grid of more than 1000 runs is refused where its
// last axis names its field.
TEST(FuzzRegression, StudyGridBeyond1000RunsIsRefusedBeforeItIsListed) {
  const std::string text = fileText(GF_SOURCE_DIR "/tests/fuzz/corpus/fuzz_study/regression-grid-1e8-runs.toml");
  const StudyDesc study = parseStudyText(text, "grid.toml", GF_SOURCE_DIR "/assets/studies");
  try {
    expandStudy(study, false, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "grid.toml:33:9: axes.7.field: the grid has 100000001 runs with series 'a', more than 1000 (use fewer "
                 "values or split the study)");
  }
  // The --quick grid takes each axis' first value: one run and the reference.
  EXPECT_EQ(expandStudy(study, true, {}).runs.size(), 2u);
}

}  // namespace
}  // namespace gf::app

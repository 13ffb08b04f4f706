// Fuzzes the study-file reader (app::parseStudyText) and the expansion of a study into its runs
// (app::expandStudy: the --quick grid, then the full one), which loads every configuration's
// scene with its overrides. Scene paths resolve against assets/studies, as for the bundled
// studies. Bad input must give InputError.
#include <cstdint>
#include <string>

#include "app/scene/scene_file.hpp"
#include "app/study/study.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gf::app::StudyDesc study = gf::app::parseStudyText(text, "fuzz.toml", GF_SOURCE_DIR "/assets/studies");
    for (const bool quick : {true, false}) {
      const gf::app::StudyPlan plan = gf::app::expandStudy(study, quick, {});
      if (!quick && plan.runs.empty()) __builtin_trap();  // every series has a run
    }
  } catch (const gf::app::InputError&) {
    // Bad input, named: fine.
  }
  return 0;
}

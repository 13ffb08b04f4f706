// Parameterised tests print their parameters by name: the sim/ enums by their scene-file names
// (their operator<<, sim/patch/patch_settings.hpp, which every file printing them sees), and no test of
// this executable lists a byte dump as its parameter.
#include <gtest/gtest.h>

#include <string>

#include "sim/patch/patch_settings.hpp"

namespace gf::sim {
namespace {

TEST(Printers, SimEnumsPrintTheirSceneFileNames) {
  EXPECT_EQ(testing::PrintToString(SolverChoice::kWorld), "world");
  EXPECT_EQ(testing::PrintToString(SolverChoice::kAggregate), "aggregate");
  EXPECT_EQ(testing::PrintToString(ContactSolver::kPoints), "points");
  EXPECT_EQ(testing::PrintToString(ContactModel::kSoftFinger), "soft_finger");
  EXPECT_EQ(testing::PrintToString(PatchFill::kFilled), "filled");
  EXPECT_EQ(testing::PrintToString(static_cast<ContactModel>(7)), "?");
}

TEST(Printers, NoTestParameterPrintsAsBytes) {
  const testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  for (int s = 0; s < unit.total_test_suite_count(); ++s) {
    const testing::TestSuite& suite = *unit.GetTestSuite(s);
    for (int t = 0; t < suite.total_test_count(); ++t) {
      const testing::TestInfo& test = *suite.GetTestInfo(t);
      const std::string param = test.value_param() ? test.value_param() : "";
      EXPECT_EQ(param.find("object <"), std::string::npos)
          << suite.name() << "." << test.name() << ": add a PrintTo for its parameter (" << param << ")";
    }
  }
}

}  // namespace
}  // namespace gf::sim

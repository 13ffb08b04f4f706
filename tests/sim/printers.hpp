// How GoogleTest prints the sim/ enums a parameterised test takes: by their scene-file names,
// so test names and `--gtest_list_tests` say "points" instead of a byte dump. Found by
// argument-dependent lookup: they live in the enums' namespace.
#pragma once

#include <ostream>

#include "sim/patch_settings.hpp"

namespace gf::sim {

inline void PrintTo(SolverChoice c, std::ostream* os) {
  *os << (c == SolverChoice::kWorld ? "world" : c == SolverChoice::kPoints ? "points" : "aggregate");
}

inline void PrintTo(ContactSolver s, std::ostream* os) {
  *os << (s == ContactSolver::kPoints ? "points" : "aggregate");
}

inline void PrintTo(ContactModel m, std::ostream* os) {
  *os << (m == ContactModel::kGodObject    ? "god_object"
          : m == ContactModel::kSoftFinger ? "soft_finger"
                                           : "god_finger");
}

inline void PrintTo(PatchFill f, std::ostream* os) { *os << (f == PatchFill::kRing ? "ring" : "filled"); }

}  // namespace gf::sim

#include "sim/assert.hpp"

#include <cstdio>
#include <cstdlib>

namespace gf {

void assertFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "godfinger: assertion failed at %s:%d: %s\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

}  // namespace gf

// GF_ASSERT: checks of programmer errors, with the fix in the message:
//   GF_ASSERT(ownsThread() && "call World from the thread that built it (the haptic thread)");
// On in debug and sanitizer builds (GF_ENABLE_ASSERTS, set by CMake); compiled out otherwise,
// where the condition is not evaluated. A failure prints file, line and the condition (with its
// message) to stderr and aborts. Bad input is not a programmer error: it gets an exception.
#pragma once

namespace gf {

/// Prints the failed assertion and aborts. Used by GF_ASSERT only.
[[noreturn]] void assertFailed(const char* condition, const char* file, int line);

}  // namespace gf

#if defined(GF_ENABLE_ASSERTS)
#define GF_ASSERT(condition) \
  ((condition) ? static_cast<void>(0) : ::gf::assertFailed(#condition, __FILE__, __LINE__))
#else
// Not evaluated, but still compiled, so variables used only in asserts count as used.
#define GF_ASSERT(condition) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif

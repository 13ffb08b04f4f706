// The GL context: which thread may use GL.
#include "render/gl/context.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "render/gl/gpu.hpp"

namespace gf::render {
namespace {

TEST(GlContext, GlIsCurrentOnItsThreadOnly) {
  EXPECT_FALSE(onGlThread()) << "no context yet";
  {
    GlContext context;
    EXPECT_TRUE(onGlThread());
    EXPECT_NE(context.description().find("Core Profile"), std::string::npos) << context.description();
    bool other_has_gl = true;
    std::thread([&] { other_has_gl = onGlThread(); }).join();
    EXPECT_FALSE(other_has_gl);
  }
  EXPECT_FALSE(onGlThread()) << "released with the context";
}

#if defined(GF_ENABLE_ASSERTS)
// Debug and sanitizer builds: a GL object made off the render thread stops at once.
TEST(GlContextDeathTest, GlObjectsOffTheRenderThreadAssert) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        GlContext context;
        std::thread([] { GpuMesh mesh; }).join();
      },
      "render thread");
}
#endif

}  // namespace
}  // namespace gf::render

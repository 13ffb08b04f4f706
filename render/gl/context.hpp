// The OSMesa OpenGL context of the render thread. Frames are drawn into our own framebuffer
// objects; the context's own buffer is a 1x1 placeholder that OSMesa needs to make it current.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "sim/assert.hpp"

namespace gf::render {

/// Raised when no OpenGL 3.3 core context can be made (or GL reports an error we cannot
/// recover from); what() says which call failed.
class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An OSMesa core-profile context, current on the thread that created it for its whole life.
/// Only that thread may use GL while the context exists: every GL object and drawing call
/// asserts it (GF_ASSERT_GL_THREAD), and so does the context's destructor.
class GlContext {
 public:
  /// Creates the context (OpenGL 3.3 core or newer) and makes it current. Throws GlError.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// "4.5 (Core Profile) Mesa ..." and the renderer name, for reports.
  std::string description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// True when the calling thread has a current GL context: it is the render thread of a
/// GlContext (or a thread that made one for a still). Any thread.
bool onGlThread();

/// Every GL object and drawing call starts with this (debug and sanitizer builds).
#define GF_ASSERT_GL_THREAD() \
  GF_ASSERT(::gf::render::onGlThread() && "GL is used on the render thread only, while its GlContext exists (docs/threads.md)")

/// Throws GlError naming `what` when glGetError reports an error (clears all pending errors).
void checkGl(const char* what);

}  // namespace gf::render

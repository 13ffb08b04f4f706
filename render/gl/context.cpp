#include "render/gl/context.hpp"

#include <GL/osmesa.h>

#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "render/gl/gl.hpp"

namespace gf::render {

struct GlContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> placeholder = std::vector<unsigned char>(4);
  std::thread::id owner = std::this_thread::get_id();
};

bool onGlThread() { return OSMesaGetCurrentContext() != nullptr; }

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  impl_->context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!impl_->context) throw GlError("OSMesaCreateContextAttribs: no OpenGL 3.3 core context");
  if (!OSMesaMakeCurrent(impl_->context, impl_->placeholder.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(impl_->context);
    throw GlError("OSMesaMakeCurrent failed");
  }
}

GlContext::~GlContext() {
  GF_ASSERT(std::this_thread::get_id() == impl_->owner && OSMesaGetCurrentContext() == impl_->context &&
            "a GlContext is destroyed on the thread that made it, and last: declare it before the GL objects it serves");
  OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

std::string GlContext::description() const {
  GF_ASSERT_GL_THREAD();
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return std::string(version ? version : "?").append(" on ").append(renderer ? renderer : "?");
}

void checkGl(const char* what) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  char text[128];
  std::snprintf(text, sizeof text, "%s: OpenGL error 0x%04x", what, first);
  throw GlError(text);
}

}  // namespace gf::render

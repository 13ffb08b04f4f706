// Small owners of GL objects: shader programs, vertex buffers, the multisampled framebuffer a
// frame is drawn into. Render thread only; constructors allocate GL objects.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace gf::render {

/// A linked vertex + fragment shader program. Throws GlError with the compiler's log.
class Program {
 public:
  Program(const char* name, const char* vertex_source, const char* fragment_source);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  void use() const;
  /// Uniform location by name (-1 when the program does not use it).
  int uniform(const char* name) const;

 private:
  unsigned id_ = 0;
};

/// Interleaved vertex: position (m) and unit normal.
struct Vertex {
  float position[3];
  float normal[3];
};

/// A vertex from double-precision position and normal.
Vertex makeVertex(const Eigen::Vector3d& position, const Eigen::Vector3d& normal);

/// Triangles in a vertex buffer (attributes 0: position, 1: normal). `dynamic` buffers are
/// refilled each frame with upload().
class GpuMesh {
 public:
  explicit GpuMesh(const std::vector<Vertex>& vertices = {}, bool dynamic = false);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  /// Replaces the contents (grows the buffer when needed).
  void upload(const std::vector<Vertex>& vertices);
  /// Draws the vertices as `mode` (GL_TRIANGLES, GL_LINES, ...).
  void draw(unsigned mode) const;
  int size() const { return count_; }

 private:
  unsigned vao_ = 0, vbo_ = 0;
  int count_ = 0;
  std::size_t capacity_ = 0;
  bool dynamic_ = false;
};

/// A multisampled colour + depth framebuffer and the single-sampled one it resolves into.
class Framebuffer {
 public:
  /// width x height pixels (1..4096), `samples` 1 (no MSAA) .. 8. Throws GlError.
  Framebuffer(int width, int height, int samples);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
  /// Binds the multisampled buffer for drawing and sets the viewport.
  void bind() const;
  /// Resolves the samples and reads the frame into `out` (rows top to bottom).
  void read(Image& out) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_, samples_;
  unsigned msaa_fbo_ = 0, msaa_colour_ = 0, msaa_depth_ = 0;
  unsigned resolve_fbo_ = 0, resolve_colour_ = 0;
};

/// A depth-only framebuffer for the shadow map (texture unit given to bindTexture()).
class ShadowMap {
 public:
  explicit ShadowMap(int size);
  ~ShadowMap();
  ShadowMap(const ShadowMap&) = delete;
  ShadowMap& operator=(const ShadowMap&) = delete;
  void bindForDrawing() const;
  void bindTexture(int unit) const;
  int size() const { return size_; }

 private:
  int size_;
  unsigned fbo_ = 0, depth_ = 0;
};

}  // namespace gf::render

// Small owners of GL objects: shader programs, vertex buffers, the framebuffer a frame is drawn
// into and its anti-aliasing, the cached backdrop, the shadow map. Render thread only; constructors allocate GL objects.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/frames/image.hpp"
#include "render/gl/vertex.hpp"
#include "render/view/view_desc.hpp"

namespace gf::render {

/// A linked vertex + fragment shader program. Throws GlError with the compiler's log. Both
/// sources are compiled as GLSL 3.30 core with `defines` (lines such as "#define SHADOWS")
/// ahead of them; a source's own #version line is dropped.
class Program {
 public:
  Program(const char* name, const char* vertex_source, const char* fragment_source,
          const char* defines = "");
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;
  void use() const;
  /// Uniform location by name (-1 when the program does not use it).
  int uniform(const char* name) const;

 private:
  unsigned id_ = 0;
};

/// Triangles in a vertex buffer (attributes 0: position, 1: normal). Static meshes are given
/// their vertices once (equal vertices shared through an index buffer); `dynamic` ones are
/// refilled each frame with upload().
class GpuMesh {
 public:
  explicit GpuMesh(const std::vector<Vertex>& vertices = {}, bool dynamic = false);
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  /// Replaces the contents of a dynamic mesh (grows the buffer when needed).
  void upload(const std::vector<Vertex>& vertices);
  /// Draws the vertices as `mode` (GL_TRIANGLES, GL_LINES, ...).
  void draw(unsigned mode) const;
  /// Draws `count` vertices of a dynamic mesh from vertex `first` as `mode`.
  void draw(unsigned mode, int first, int count) const;

 private:
  unsigned vao_ = 0, vbo_ = 0, ebo_ = 0;
  int count_ = 0;  // vertices (dynamic) or indices (static) drawn
  std::size_t capacity_ = 0;
  bool dynamic_ = false;
};

/// A rectangle of pixels in GL's convention (origin bottom left): [x0, x1) x [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};
/// `r` with `by` pixels more on each side (an empty one stays empty).
PixelRect grow(const PixelRect& r, int by);
/// The pixels in both (empty when none).
PixelRect intersect(const PixelRect& a, const PixelRect& b);
/// The smallest rectangle holding both (an empty one adds nothing).
PixelRect unite(const PixelRect& a, const PixelRect& b);
/// Equal, or both empty.
bool sameRect(const PixelRect& a, const PixelRect& b);
/// The pixels of `outer` outside `hole`, as up to four rectangles that do not overlap.
std::vector<PixelRect> bandsAround(const PixelRect& outer, const PixelRect& hole);

/// A frame drawn over a kept bodies' layer (SceneRenderer::heldLayer): which layer (a number
/// given each time one is kept) and the pixels its contact overlay can cover.
struct HeldLayer {
  long layer = 0;
  PixelRect overlay;
};

/// Where a frame is drawn: the scene target (colour + depth, multisampled for kMsaa) and the
/// single-sampled output that resolve() fills, overlays are drawn onto and read() returns. For
/// kNone and kFxaa the two are one buffer: FXAA filters the scene in place, reading a copy of
/// the pixels it changes.
class Framebuffer {
 public:
  /// width x height pixels (1..4096); `msaa_samples` (2..8) is used by kMsaa only. Throws GlError.
  Framebuffer(int width, int height, view::Antialiasing aa, int msaa_samples = 4);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
  /// Binds the scene target for drawing and sets the viewport.
  void bind();
  /// Anti-aliases the scene into the output and binds the output (for 2D overlays). FXAA is
  /// applied inside `edges` only (where the scene has geometric edges); nullopt: everywhere.
  /// `held`: the scene was drawn over a kept layer. When the last resolve had the same layer
  /// and edges, the two frames differ only under their overlays, and FXAA runs only near them;
  /// the rest of `edges` is the last resolve's filtered pixels (the same values).
  void resolve(const std::optional<PixelRect>& edges = std::nullopt,
               const std::optional<HeldLayer>& held = std::nullopt);
  /// Resolves if that has not happened since bind(), then reads the output into `out` (rows
  /// top to bottom).
  void read(Image& out);
  /// Resolves if that has not happened since bind(), then copies the output into framebuffer
  /// `target` with its lower-left corner at (x, y) (GL pixels), and binds `target`.
  void copyInto(unsigned target, int x, int y);
  /// Keeps a copy of the output as it is now (a finished scene picture, before its labels).
  void keepPicture();
  /// Puts the kept picture back into the output and binds it, as resolve() leaves it (a frame
  /// that draws the same scene: only its labels go on top). False, doing nothing, when none is
  /// kept.
  bool restorePicture();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Fxaa;
  void copyForFilter(const PixelRect& r);
  void filterMarked(const PixelRect& r);
  int width_, height_;
  view::Antialiasing aa_;
  unsigned scene_fbo_ = 0, scene_colour_ = 0, scene_depth_ = 0;
  unsigned output_fbo_ = 0, output_colour_ = 0;  // kMsaa only; otherwise the scene is the output
  std::unique_ptr<Fxaa> fxaa_;
  unsigned kept_fbo_ = 0, kept_colour_ = 0;  // keepPicture()'s copy (made at its first call)
  std::vector<std::uint8_t> rgba_;  // read-back buffer
  bool resolved_ = false;
};

/// A copy of the part of a frame that does not move (the clear colour and the ground under a
/// fixed camera, or all the bodies of a still scene), kept in the scene target's colour format
/// and restored by one blit per frame. Colour only: what it holds is drawn in the frame and
/// taken from there, and the depth under it is drawn again (a 1280x720 depth buffer is 3.7 MB
/// a backdrop need not keep).
class Backdrop {
 public:
  Backdrop(int width, int height, int samples);
  ~Backdrop();
  Backdrop(const Backdrop&) = delete;
  Backdrop& operator=(const Backdrop&) = delete;
  bool fits(int width, int height, int samples) const {
    return width == width_ && height == height_ && samples == samples_;
  }
  /// Copies the colour into framebuffer `target` and binds it again. Depth is not copied: a
  /// depth blit costs llvmpipe about 2 ms even at 216 x 216 pixels, where drawing the depth
  /// again takes a fraction of that (SceneRenderer does).
  void restoreColourInto(unsigned target) const;
  /// Copies the colour of framebuffer `source` (of this size and samples) into the backdrop,
  /// and binds `source` again.
  void takeFrom(unsigned source) const;

 private:
  int width_, height_, samples_;
  unsigned fbo_ = 0, colour_ = 0;
};

/// A depth-only framebuffer for the shadow map (texture unit given to bindTexture()).
class ShadowMap {
 public:
  explicit ShadowMap(int size);
  ~ShadowMap();
  ShadowMap(const ShadowMap&) = delete;
  ShadowMap& operator=(const ShadowMap&) = delete;
  void bindForDrawing() const;
  /// Copies the depth of `other` (of the same size) into this map and binds it for drawing.
  void copyFrom(const ShadowMap& other) const;
  void bindTexture(int unit) const;
  int size() const { return size_; }

 private:
  int size_;
  unsigned fbo_ = 0, depth_ = 0;
};

}  // namespace gf::render

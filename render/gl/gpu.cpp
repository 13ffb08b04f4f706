#include "render/gl/gpu.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>
#include <unordered_map>

#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/shaders.hpp"

namespace gf::render {
namespace {

unsigned compile(const char* name, GLenum kind, const char* source, const char* defines) {
  if (std::strncmp(source, "#version", 8) == 0) source = std::strchr(source, '\n');
  const char* parts[] = {"#version 330 core\n", defines, "\n", source ? source : ""};
  const unsigned shader = glCreateShader(kind);
  glShaderSource(shader, 4, parts, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok) return shader;
  char log[2048] = {};
  glGetShaderInfoLog(shader, sizeof log, nullptr, log);
  glDeleteShader(shader);
  std::string message = name;
  throw GlError(message.append(kind == GL_VERTEX_SHADER ? " vertex" : " fragment")
                    .append(" shader: ").append(log));
}

}  // namespace

Program::Program(const char* name, const char* vertex_source, const char* fragment_source,
                 const char* defines) {
  GF_ASSERT_GL_THREAD();
  const unsigned vs = compile(name, GL_VERTEX_SHADER, vertex_source, defines);
  unsigned fs = 0;
  try {
    fs = compile(name, GL_FRAGMENT_SHADER, fragment_source, defines);
  } catch (const GlError&) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok) return;
  char log[2048] = {};
  glGetProgramInfoLog(id_, sizeof log, nullptr, log);
  glDeleteProgram(id_);
  std::string message = name;
  throw GlError(message.append(" program: ").append(log));
}

Program::~Program() {
  GF_ASSERT_GL_THREAD();
  glDeleteProgram(id_);
}

void Program::use() const {
  GF_ASSERT_GL_THREAD();
  glUseProgram(id_);
}

int Program::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

GpuMesh::GpuMesh(const std::vector<Vertex>& vertices, bool dynamic) : dynamic_(dynamic) {
  GF_ASSERT_GL_THREAD();
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<const void*>(offsetof(Vertex, normal)));
  if (!dynamic && !vertices.empty()) {
    // Static meshes share equal vertices through an index buffer: llvmpipe transforms each
    // distinct vertex once instead of three times per smooth-shaded corner.
    std::vector<Vertex> unique;
    std::vector<std::uint32_t> indices;
    indices.reserve(vertices.size());
    std::unordered_map<std::string_view, std::uint32_t> seen;
    seen.reserve(vertices.size());
    for (const Vertex& v : vertices) {
      const std::string_view key(reinterpret_cast<const char*>(&v), sizeof(Vertex));
      const auto [it, added] = seen.try_emplace(key, static_cast<std::uint32_t>(unique.size()));
      if (added) unique.push_back(v);
      indices.push_back(it->second);
    }
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(unique.size() * sizeof(Vertex)), unique.data(), GL_STATIC_DRAW);
    glGenBuffers(1, &ebo_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)),
                 indices.data(), GL_STATIC_DRAW);
    count_ = static_cast<int>(indices.size());
  }
  glBindVertexArray(0);
}

GpuMesh::~GpuMesh() {
  GF_ASSERT_GL_THREAD();
  glDeleteBuffers(1, &vbo_);
  if (ebo_) glDeleteBuffers(1, &ebo_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::upload(const std::vector<Vertex>& vertices) {
  GF_ASSERT_GL_THREAD();
  if (!dynamic_) throw GlError("upload() on a static mesh");
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const std::size_t bytes = vertices.size() * sizeof(Vertex);
  if (bytes > capacity_) {
    capacity_ = std::max<std::size_t>(bytes, 2 * capacity_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(capacity_), nullptr, GL_STREAM_DRAW);
  }
  if (bytes > 0) glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), vertices.data());
  count_ = static_cast<int>(vertices.size());
}

void GpuMesh::draw(unsigned mode) const {
  GF_ASSERT_GL_THREAD();
  if (count_ == 0) return;
  glBindVertexArray(vao_);
  if (ebo_) {
    glDrawElements(mode, count_, GL_UNSIGNED_INT, nullptr);
  } else {
    glDrawArrays(mode, 0, count_);
  }
  glBindVertexArray(0);
}

void GpuMesh::draw(unsigned mode, int first, int count) const {
  GF_ASSERT_GL_THREAD();
  GF_ASSERT(!ebo_ && first >= 0 && first + count <= count_ && "a range of a dynamic mesh's vertices");
  if (count <= 0) return;
  glBindVertexArray(vao_);
  glDrawArrays(mode, first, count);
  glBindVertexArray(0);
}

namespace {

unsigned renderbuffer(GLenum format, int width, int height, int samples) {
  unsigned id = 0;
  glGenRenderbuffers(1, &id);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  // Mesa rounds a request for one sample up to its smallest multisample count: ask for none.
  if (samples > 1) {
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  } else {
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  }
  return id;
}

// A single-level 2D texture with linear filtering and the given edge behaviour.
unsigned texture2D(GLenum internal_format, int width, int height, GLenum format, GLenum type, GLenum wrap) {
  unsigned id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internal_format), width, height, 0, format, type, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  return id;
}

void requireComplete(const char* what) {
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError(std::string(what) + " framebuffer incomplete");
  }
}

// A framebuffer with an RGBA8 colour and a 24-bit depth renderbuffer of `samples` each, with
// `stencil` 8 bits of stencil beside the depth (the same 32 bits a pixel llvmpipe gives 24-bit
// depth alone); returns the framebuffer and leaves it bound.
unsigned colourDepthTarget(int width, int height, int samples, bool stencil, unsigned& colour, unsigned& depth,
                           const char* what) {
  unsigned fbo = 0;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  colour = renderbuffer(GL_RGBA8, width, height, samples);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  depth = renderbuffer(stencil ? GL_DEPTH24_STENCIL8 : GL_DEPTH_COMPONENT24, width, height, samples);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                            GL_RENDERBUFFER, depth);
  requireComplete(what);
  return fbo;
}

// Copies the colour of framebuffer `from` into `to` (both width x height), then binds `bound`
// with the viewport over the picture.
void copyColour(unsigned from, unsigned to, int width, int height, unsigned bound) {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, bound);
  glViewport(0, 0, width, height);
}

// Copies rectangle `r` of framebuffer `from`'s colour to the same place in `to`.
void blitRect(unsigned from, unsigned to, const PixelRect& r) {
  if (r.empty()) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
  glBlitFramebuffer(r.x0, r.y0, r.x1, r.y1, r.x0, r.y0, r.x1, r.y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

}  // namespace

PixelRect grow(const PixelRect& r, int by) {
  if (r.empty()) return r;
  return {r.x0 - by, r.y0 - by, r.x1 + by, r.y1 + by};
}

PixelRect intersect(const PixelRect& a, const PixelRect& b) {
  const PixelRect r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  return r.empty() ? PixelRect{} : r;
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

bool sameRect(const PixelRect& a, const PixelRect& b) {
  return (a.empty() && b.empty()) || (a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1);
}

std::vector<PixelRect> bandsAround(const PixelRect& outer, const PixelRect& hole) {
  const PixelRect h = intersect(hole, outer);
  if (h.empty()) return outer.empty() ? std::vector<PixelRect>{} : std::vector<PixelRect>{outer};
  std::vector<PixelRect> out;
  for (const PixelRect& band : {PixelRect{outer.x0, outer.y0, outer.x1, h.y0}, PixelRect{outer.x0, h.y1, outer.x1, outer.y1},
                                PixelRect{outer.x0, h.y0, h.x0, h.y1}, PixelRect{h.x1, h.y0, outer.x1, h.y1}}) {
    if (!band.empty()) out.push_back(band);
  }
  return out;
}

// The FXAA passes: the edge marking and the filter, and a colour texture holding a copy of the
// pixels they read.
struct Framebuffer::Fxaa {
  Program mark{"fxaa mark", shaders::kFullScreenVertex, shaders::kFxaaFragment, "#define GF_FXAA_MARK"};
  Program program{"fxaa", shaders::kFullScreenVertex, shaders::kFxaaFragment};
  unsigned vao = 0, fbo = 0, copy = 0;
  int stencil_value = 0;  // this resolve's stencil value: marks of earlier ones differ, so none is cleared
  // The last resolve over a held layer: its filtered pixels (inside its edges), made at the first.
  unsigned filtered_fbo = 0, filtered_colour = 0;
  std::optional<HeldLayer> filtered_held;
  PixelRect filtered_edges;
  Fxaa(int width, int height) {
    glGenVertexArrays(1, &vao);
    copy = texture2D(GL_RGBA8, width, height, GL_RGBA, GL_UNSIGNED_BYTE, GL_CLAMP_TO_EDGE);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, copy, 0);
    requireComplete("fxaa copy");
  }
  ~Fxaa() {
    glDeleteFramebuffers(1, &filtered_fbo);
    glDeleteRenderbuffers(1, &filtered_colour);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &copy);
    glDeleteVertexArrays(1, &vao);
  }
};

Framebuffer::Framebuffer(int width, int height, view::Antialiasing aa, int msaa_samples)
    : width_(width), height_(height), aa_(aa) {
  GF_ASSERT_GL_THREAD();
  if (width < 1 || height < 1 || width > 4096 || height > 4096) {
    throw GlError("frame size must be 1..4096 pixels each way");
  }
  const int samples = aa == view::Antialiasing::kMsaa ? std::clamp(msaa_samples, 2, 8) : 1;
  scene_fbo_ = colourDepthTarget(width, height, samples, aa == view::Antialiasing::kFxaa, scene_colour_,
                                 scene_depth_, "scene");
  if (aa == view::Antialiasing::kMsaa) {
    glGenFramebuffers(1, &output_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, output_fbo_);
    output_colour_ = renderbuffer(GL_RGBA8, width, height, 1);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, output_colour_);
    requireComplete("output");
  }
  if (aa == view::Antialiasing::kFxaa) fxaa_ = std::make_unique<Fxaa>(width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("framebuffer");
}

Framebuffer::~Framebuffer() {
  GF_ASSERT_GL_THREAD();
  fxaa_.reset();
  const unsigned fbos[] = {scene_fbo_, output_fbo_, kept_fbo_};
  glDeleteFramebuffers(3, fbos);
  const unsigned buffers[] = {scene_colour_, scene_depth_, output_colour_, kept_colour_};
  glDeleteRenderbuffers(4, buffers);
}

void Framebuffer::bind() {
  GF_ASSERT_GL_THREAD();
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  glViewport(0, 0, width_, height_);
  resolved_ = false;
}

void Framebuffer::resolve(const std::optional<PixelRect>& edges, const std::optional<HeldLayer>& held) {
  GF_ASSERT_GL_THREAD();
  resolved_ = true;
  glViewport(0, 0, width_, height_);
  if (aa_ == view::Antialiasing::kMsaa) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, scene_fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, output_fbo_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, output_fbo_);
    return;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  if (aa_ == view::Antialiasing::kNone) return;
  const PixelRect whole{0, 0, width_, height_};
  const PixelRect r = intersect(grow(edges.value_or(whole), 2), whole);
  if (r.empty()) return;
  Fxaa& x = *fxaa_;
  // Over the same layer with the same edges as the last resolve, a pixel's filtered value can
  // differ only if its reach (the filter reads at most 5 pixels away) meets either overlay.
  PixelRect f = r;
  const bool reuse = held && x.filtered_held && x.filtered_held->layer == held->layer && sameRect(x.filtered_edges, r);
  if (reuse) f = intersect(grow(unite(held->overlay, x.filtered_held->overlay), 6), r);
  if (!f.empty()) copyForFilter(f);
  if (reuse) {
    for (const PixelRect& band : bandsAround(r, f)) blitRect(x.filtered_fbo, scene_fbo_, band);
  }
  if (!f.empty()) filterMarked(f);
  x.filtered_held.reset();
  if (held) {
    if (x.filtered_fbo == 0) {
      glGenFramebuffers(1, &x.filtered_fbo);
      glBindFramebuffer(GL_FRAMEBUFFER, x.filtered_fbo);
      x.filtered_colour = renderbuffer(GL_RGBA8, width_, height_, 1);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, x.filtered_colour);
      requireComplete("filtered picture");
    }
    blitRect(scene_fbo_, x.filtered_fbo, f);
    x.filtered_held = held;
    x.filtered_edges = r;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
}

// The scene's pixels FXAA reads for `r` (it reads at most 5 pixels away: a margin of 8) into its
// copy.
void Framebuffer::copyForFilter(const PixelRect& r) {
  blitRect(scene_fbo_, fxaa_->fbo, intersect(grow(r, 8), PixelRect{0, 0, width_, height_}));
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
}

// FXAA over `r` of the scene, reading the copy: first the pixels with an edge are marked in the
// stencil (colour untouched), then the filter runs on them alone. The same pixels as one pass,
// at a third of its cost on llvmpipe (docs/performance.md, "The filter on edges only").
void Framebuffer::filterMarked(const PixelRect& r) {
  glBindFramebuffer(GL_FRAMEBUFFER, scene_fbo_);
  GLboolean depth_test = GL_FALSE, blend = GL_FALSE;
  glGetBooleanv(GL_DEPTH_TEST, &depth_test);
  glGetBooleanv(GL_BLEND, &blend);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_SCISSOR_TEST);
  glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, fxaa_->copy);
  glBindVertexArray(fxaa_->vao);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0xff);
  if (++fxaa_->stencil_value > 0xff) {
    fxaa_->stencil_value = 1;
    glDisable(GL_SCISSOR_TEST);
    glClearStencil(0);
    glClear(GL_STENCIL_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
  }
  for (const Program* pass : {&fxaa_->mark, &fxaa_->program}) {
    const bool marking = pass == &fxaa_->mark;
    glColorMask(!marking, !marking, !marking, !marking);
    glStencilFunc(marking ? GL_ALWAYS : GL_EQUAL, fxaa_->stencil_value, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, marking ? GL_REPLACE : GL_KEEP);
    glStencilMask(marking ? 0xff : 0x00);
    pass->use();
    glUniform1i(pass->uniform("u_scene"), 0);
    glUniform2f(pass->uniform("u_texel"), 1.0f / width_, 1.0f / height_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glStencilMask(0xff);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_STENCIL_TEST);
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
  if (depth_test) glEnable(GL_DEPTH_TEST);
  if (blend) glEnable(GL_BLEND);
}

void Framebuffer::copyInto(unsigned target, int x, int y) {
  GF_ASSERT_GL_THREAD();
  if (!resolved_) resolve();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, aa_ == view::Antialiasing::kMsaa ? output_fbo_ : scene_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target);
  glBlitFramebuffer(0, 0, width_, height_, x, y, x + width_, y + height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
}

void Framebuffer::keepPicture() {
  GF_ASSERT_GL_THREAD();
  if (!resolved_) resolve();
  if (kept_fbo_ == 0) {
    glGenFramebuffers(1, &kept_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, kept_fbo_);
    kept_colour_ = renderbuffer(GL_RGBA8, width_, height_, 1);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, kept_colour_);
    requireComplete("kept picture");
  }
  const unsigned output = aa_ == view::Antialiasing::kMsaa ? output_fbo_ : scene_fbo_;
  copyColour(output, kept_fbo_, width_, height_, output);
}

bool Framebuffer::restorePicture() {
  GF_ASSERT_GL_THREAD();
  if (kept_fbo_ == 0) return false;
  const unsigned output = aa_ == view::Antialiasing::kMsaa ? output_fbo_ : scene_fbo_;
  copyColour(kept_fbo_, output, width_, height_, output);
  resolved_ = true;
  return true;
}

void Framebuffer::read(Image& out) {
  GF_ASSERT_GL_THREAD();
  if (!resolved_) resolve();
  glBindFramebuffer(GL_READ_FRAMEBUFFER, aa_ == view::Antialiasing::kMsaa ? output_fbo_ : scene_fbo_);
  out.width = width_;
  out.height = height_;
  const std::size_t w = static_cast<std::size_t>(width_), h = static_cast<std::size_t>(height_);
  // RGBA is Mesa's fast read path; dropping alpha while flipping is one pass of our own. Read in
  // bands of kReadBandBytes, not the whole picture: a 1280x720 RGBA copy is 3.7 MB held for
  // the frame's life, a band 256 kB, and the 8 reads cost what one does.
  constexpr std::size_t kReadBandBytes = 256 << 10;
  const std::size_t band = std::clamp<std::size_t>(kReadBandBytes / (4 * w), 1, h);
  std::vector<std::uint8_t>& rgba = rgba_;
  rgba.resize(4 * w * band);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  out.rgb.resize(3 * w * h);
  for (std::size_t y0 = 0; y0 < h; y0 += band) {  // GL rows y0 .. y0 + rows - 1, bottom up
    const std::size_t rows = std::min(band, h - y0);
    glReadPixels(0, static_cast<GLint>(y0), width_, static_cast<GLsizei>(rows), GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    for (std::size_t r = 0; r < rows; ++r) {  // GL's rows run bottom to top; images top to bottom
      const std::uint8_t* src = rgba.data() + 4 * w * r;
      std::uint8_t* dst = out.rgb.data() + 3 * w * (h - 1 - (y0 + r));
      // Four bytes per pixel stored 3 apart, each store's alpha overwritten by the next pixel;
      // the row's last pixel is copied bytewise so nothing is written past the row.
      for (std::size_t x = 0; x + 1 < w; ++x) std::memcpy(dst + 3 * x, src + 4 * x, 4);
      std::memcpy(dst + 3 * (w - 1), src + 4 * (w - 1), 3);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

Backdrop::Backdrop(int width, int height, int samples) : width_(width), height_(height), samples_(samples) {
  GF_ASSERT_GL_THREAD();
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  colour_ = renderbuffer(GL_RGBA8, width, height, samples);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  requireComplete("backdrop");
}

Backdrop::~Backdrop() {
  GF_ASSERT_GL_THREAD();
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &colour_);
}

void Backdrop::restoreColourInto(unsigned target) const {
  GF_ASSERT_GL_THREAD();
  copyColour(fbo_, target, width_, height_, target);
}

void Backdrop::takeFrom(unsigned source) const {
  GF_ASSERT_GL_THREAD();
  copyColour(source, fbo_, width_, height_, source);
}

ShadowMap::ShadowMap(int size) : size_(size) {
  GF_ASSERT_GL_THREAD();
  depth_ = texture2D(GL_DEPTH_COMPONENT24, size, size, GL_DEPTH_COMPONENT, GL_FLOAT, GL_CLAMP_TO_BORDER);
  const float white[] = {1, 1, 1, 1};
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, white);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("shadow framebuffer incomplete");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ShadowMap::~ShadowMap() {
  GF_ASSERT_GL_THREAD();
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &depth_);
}

void ShadowMap::bindForDrawing() const {
  GF_ASSERT_GL_THREAD();
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, size_, size_);
}

void ShadowMap::copyFrom(const ShadowMap& other) const {
  GF_ASSERT_GL_THREAD();
  GF_ASSERT(other.size_ == size_ && "shadow maps of one size");
  glBindFramebuffer(GL_READ_FRAMEBUFFER, other.fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
  glBlitFramebuffer(0, 0, size_, size_, 0, 0, size_, size_, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  bindForDrawing();
}

void ShadowMap::bindTexture(int unit) const {
  GF_ASSERT_GL_THREAD();
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, depth_);
}

}  // namespace gf::render

#include "render/gpu.hpp"

#include <algorithm>
#include <cstring>

#include "render/context.hpp"
#include "render/gl.hpp"

namespace gf::render {
namespace {

unsigned compile(const char* name, GLenum kind, const char* source) {
  const unsigned shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
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

Vertex makeVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  return {{static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())},
          {static_cast<float>(n.x()), static_cast<float>(n.y()), static_cast<float>(n.z())}};
}

Program::Program(const char* name, const char* vertex_source, const char* fragment_source) {
  const unsigned vs = compile(name, GL_VERTEX_SHADER, vertex_source);
  const unsigned fs = compile(name, GL_FRAGMENT_SHADER, fragment_source);
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

Program::~Program() { glDeleteProgram(id_); }
void Program::use() const { glUseProgram(id_); }
int Program::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

GpuMesh::GpuMesh(const std::vector<Vertex>& vertices, bool dynamic) : dynamic_(dynamic) {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<const void*>(offsetof(Vertex, normal)));
  glBindVertexArray(0);
  if (!vertices.empty()) upload(vertices);
}

GpuMesh::~GpuMesh() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::upload(const std::vector<Vertex>& vertices) {
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const std::size_t bytes = vertices.size() * sizeof(Vertex);
  if (bytes > capacity_) {
    capacity_ = std::max<std::size_t>(bytes, 2 * capacity_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(capacity_), nullptr,
                 dynamic_ ? GL_STREAM_DRAW : GL_STATIC_DRAW);
  }
  if (bytes > 0) glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), vertices.data());
  count_ = static_cast<int>(vertices.size());
}

void GpuMesh::draw(unsigned mode) const {
  if (count_ == 0) return;
  glBindVertexArray(vao_);
  glDrawArrays(mode, 0, count_);
  glBindVertexArray(0);
}

Framebuffer::Framebuffer(int width, int height, int samples)
    : width_(width), height_(height), samples_(std::clamp(samples, 1, 8)) {
  if (width < 1 || height < 1 || width > 4096 || height > 4096) {
    throw GlError("frame size must be 1..4096 pixels each way");
  }
  glGenFramebuffers(1, &msaa_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  glGenRenderbuffers(1, &msaa_colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_colour_);
  glGenRenderbuffers(1, &msaa_depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("multisampled framebuffer incomplete");
  }
  glGenFramebuffers(1, &resolve_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
  glGenRenderbuffers(1, &resolve_colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolve_colour_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("resolve framebuffer incomplete");
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  checkGl("framebuffer");
}

Framebuffer::~Framebuffer() {
  glDeleteFramebuffers(1, &msaa_fbo_);
  glDeleteFramebuffers(1, &resolve_fbo_);
  const unsigned buffers[] = {msaa_colour_, msaa_depth_, resolve_colour_};
  glDeleteRenderbuffers(3, buffers);
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, msaa_fbo_);
  glViewport(0, 0, width_, height_);
}

void Framebuffer::read(Image& out) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_);
  out.width = width_;
  out.height = height_;
  const std::size_t stride = 3 * static_cast<std::size_t>(width_);
  out.rgb.resize(stride * height_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  // GL's rows run bottom to top; images run top to bottom.
  std::vector<std::uint8_t> row(stride);
  for (int y = 0; y < height_ / 2; ++y) {
    std::uint8_t* a = out.rgb.data() + y * stride;
    std::uint8_t* b = out.rgb.data() + (height_ - 1 - y) * stride;
    std::memcpy(row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, row.data(), stride);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

ShadowMap::ShadowMap(int size) : size_(size) {
  glGenTextures(1, &depth_);
  glBindTexture(GL_TEXTURE_2D, depth_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
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
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &depth_);
}

void ShadowMap::bindForDrawing() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, size_, size_);
}

void ShadowMap::bindTexture(int unit) const {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, depth_);
}

}  // namespace gf::render

#include "render/gl/imgui_layer.hpp"

#include <imgui.h>

#include <Eigen/Core>
#include <cmath>

#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/shaders.hpp"
#include "sim/assert.hpp"

namespace gf::render {
namespace {

// Our key indices into io.KeysDown.
enum Key { kKeyEnter = 1, kKeyBackspace, kKeyA, kKeyTab, kKeyEscape };

}  // namespace

unsigned imguiColour(const Eigen::Vector3f& linear, float alpha) {
  const Eigen::Vector3f c = linear.cwiseMax(0.0f).cwiseMin(1.0f).cwiseSqrt();
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x(), c.y(), c.z(), alpha));
}

struct ImGuiLayer::Gl {
  Program program{"overlay", shaders::kOverlayVertex, shaders::kOverlayFragment};
  unsigned vao = 0, vbo = 0, ebo = 0, font = 0;

  Gl() {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glGenBuffers(1, &ebo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glEnableVertexAttribArray(0);
    glEnableVertexAttribArray(1);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(ImDrawVert),
                          reinterpret_cast<const void*>(offsetof(ImDrawVert, pos)));
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(ImDrawVert),
                          reinterpret_cast<const void*>(offsetof(ImDrawVert, uv)));
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(ImDrawVert),
                          reinterpret_cast<const void*>(offsetof(ImDrawVert, col)));
    glBindVertexArray(0);
  }
  ~Gl() {
    glDeleteTextures(1, &font);
    glDeleteBuffers(1, &vbo);
    glDeleteBuffers(1, &ebo);
    glDeleteVertexArrays(1, &vao);
  }
  void uploadFont(ImFontAtlas& atlas) {
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    atlas.GetTexDataAsRGBA32(&pixels, &w, &h);
    glGenTextures(1, &font);
    glBindTexture(GL_TEXTURE_2D, font);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    atlas.SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(font)));
  }
};

ImGuiLayer::ImGuiLayer(int width, int height, float font_px, const std::vector<float>& more_px)
    : width_(width), height_(height) {
  GF_ASSERT_GL_THREAD();
  ImGuiContext* previous = ImGui::GetCurrentContext();
  context_ = ImGui::CreateContext();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing read or written: sessions are reproducible
  io.LogFilename = nullptr;
  io.BackendPlatformName = "godfinger-headless";
  io.BackendRendererName = "godfinger-gl33";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
  io.KeyMap[ImGuiKey_Enter] = kKeyEnter;
  io.KeyMap[ImGuiKey_Backspace] = kKeyBackspace;
  io.KeyMap[ImGuiKey_A] = kKeyA;
  io.KeyMap[ImGuiKey_Tab] = kKeyTab;
  io.KeyMap[ImGuiKey_Escape] = kKeyEscape;
  std::vector<float> sizes{font_px};
  sizes.insert(sizes.end(), more_px.begin(), more_px.end());
  for (const float px : sizes) {
    ImFontConfig font;
    font.SizePixels = px;
    font.OversampleH = 2;
    io.Fonts->AddFontDefault(&font);
  }
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.Colors[ImGuiCol_WindowBg].w = 0.82f;
  gl_ = std::make_unique<Gl>();
  gl_->uploadFont(*io.Fonts);
  ImGui::SetCurrentContext(previous);
}

ImGuiLayer::~ImGuiLayer() {
  GF_ASSERT_GL_THREAD();
  gl_.reset();
  ImGui::DestroyContext(context_);
}

void ImGuiLayer::beginFrame(double dt_s, const InputState& input) {
  GF_ASSERT_GL_THREAD();
  ImGui::SetCurrentContext(context_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width_), static_cast<float>(height_));
  io.DeltaTime = static_cast<float>(dt_s > 0.0 ? dt_s : 1.0 / 60.0);
  io.MousePos = input.mouse_x < 0 ? ImVec2(-FLT_MAX, -FLT_MAX) : ImVec2(input.mouse_x, input.mouse_y);
  io.MouseDown[0] = input.mouse_down;
  io.KeyCtrl = input.ctrl || input.select_all;
  io.KeysDown[kKeyEnter] = input.enter;
  io.KeysDown[kKeyBackspace] = input.backspace;
  io.KeysDown[kKeyA] = input.select_all;
  if (!input.text.empty()) io.AddInputCharactersUTF8(input.text.c_str());
  ImGui::NewFrame();
}

void ImGuiLayer::render() {
  GF_ASSERT_GL_THREAD();
  ImGui::Render();
  drawLists(*ImGui::GetDrawData());
}

void ImGuiLayer::scaleSizes(float factor) {
  ImGuiContext* previous = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(context_);
  ImGui::GetStyle().ScaleAllSizes(factor);
  ImGui::SetCurrentContext(previous);
}

ImFont* ImGuiLayer::font(float px) const {
  ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
  GF_ASSERT(ImGui::GetCurrentContext() == context_ && "font() inside this layer's frame");
  ImFont* best = atlas.Fonts[0];
  for (ImFont* f : atlas.Fonts) {
    if (std::abs(f->FontSize - px) < std::abs(best->FontSize - px)) best = f;
  }
  return best;
}

void ImGuiLayer::drawLists(const ImDrawData& data) {
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_SCISSOR_TEST);
  glViewport(0, 0, width_, height_);
  // Pixels (origin top-left) to clip space.
  const float l = data.DisplayPos.x, r = l + data.DisplaySize.x;
  const float t = data.DisplayPos.y, b = t + data.DisplaySize.y;
  Eigen::Matrix4f projection;
  projection << 2 / (r - l), 0, 0, (r + l) / (l - r), 0, 2 / (t - b), 0, (t + b) / (b - t), 0, 0, -1, 0, 0,
      0, 0, 1;
  gl_->program.use();
  glUniformMatrix4fv(gl_->program.uniform("u_projection"), 1, GL_FALSE, projection.data());
  glUniform1i(gl_->program.uniform("u_texture"), 0);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(gl_->vao);
  glBindBuffer(GL_ARRAY_BUFFER, gl_->vbo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gl_->ebo);
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList* list = data.CmdLists[n];
    glBufferData(GL_ARRAY_BUFFER, list->VtxBuffer.Size * static_cast<GLsizeiptr>(sizeof(ImDrawVert)),
                 list->VtxBuffer.Data, GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, list->IdxBuffer.Size * static_cast<GLsizeiptr>(sizeof(ImDrawIdx)),
                 list->IdxBuffer.Data, GL_STREAM_DRAW);
    for (const ImDrawCmd& cmd : list->CmdBuffer) {
      if (cmd.UserCallback) continue;  // we add no callbacks
      const ImVec4 clip = cmd.ClipRect;
      if (clip.z <= clip.x || clip.w <= clip.y) continue;
      glScissor(static_cast<int>(clip.x - l), static_cast<int>(height_ - (clip.w - t)),
                static_cast<int>(clip.z - clip.x), static_cast<int>(clip.w - clip.y));
      glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(reinterpret_cast<std::uintptr_t>(cmd.GetTexID())));
      glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(cmd.ElemCount),
                               sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(cmd.IdxOffset * sizeof(ImDrawIdx)),
                               static_cast<GLint>(cmd.VtxOffset));
    }
  }
  glBindVertexArray(0);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
}

}  // namespace gf::render

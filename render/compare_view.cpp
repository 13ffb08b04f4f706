#include "render/compare_view.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdint>

#include "render/context.hpp"
#include "render/gl.hpp"
#include "render/gpu.hpp"
#include "render/imgui_layer.hpp"

namespace gf::render {
namespace {

constexpr float kFontPx = 17.0f;
constexpr double kMinChartShare = 0.3;  // of the frame's height

// One panel's picture as a GL texture, re-filled from an Image each frame.
class PanelTexture {
 public:
  PanelTexture() { glGenTextures(1, &id_); }
  ~PanelTexture() { glDeleteTextures(1, &id_); }
  PanelTexture(const PanelTexture&) = delete;
  PanelTexture& operator=(const PanelTexture&) = delete;

  void upload(const Image& image) {
    glBindTexture(GL_TEXTURE_2D, id_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (image.width != width_ || image.height != height_) {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
      width_ = image.width;
      height_ = image.height;
    } else {
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  }
  ImTextureID id() const { return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(id_)); }
  bool empty() const { return width_ == 0; }

 private:
  GLuint id_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace

CompareLayout compareLayout(int width, int height, int panels) {
  panels = std::clamp(panels, 1, 4);
  CompareLayout l;
  const double aspect = static_cast<double>(height) / width;
  l.panel_width = width / panels;
  l.panel_height = static_cast<int>(l.panel_width * aspect);
  const int most = static_cast<int>((1.0 - kMinChartShare) * height);
  if (l.panel_height > most) {  // too tall to leave the chart its share: narrower panels
    l.panel_height = most;
    l.panel_width = static_cast<int>(most / aspect);
  }
  l.panel_width = std::max(16, l.panel_width);
  l.panel_height = std::max(16, l.panel_height);
  l.panels_left = std::max(0, (width - panels * l.panel_width) / 2);
  l.chart_top = l.panel_height;
  l.chart_height = std::max(0, height - l.panel_height);
  return l;
}

struct CompareCompositor::Impl {
  int width, height;
  std::vector<ComparePanel> panels;
  ChartSpec chart;
  CompareLayout layout;
  Framebuffer frame;
  ImGuiLayer imgui;
  std::vector<std::unique_ptr<PanelTexture>> textures;

  Impl(int w, int h, std::vector<ComparePanel> p, ChartSpec c)
      : width(w),
        height(h),
        panels(std::move(p)),
        chart(std::move(c)),
        layout(compareLayout(w, h, static_cast<int>(panels.size()))),
        frame(w, h, sim::Antialiasing::kNone),
        imgui(w, h, kFontPx) {
    chart.width = w;
    chart.height = layout.chart_height;
    for (std::size_t i = 0; i < panels.size(); ++i) textures.push_back(std::make_unique<PanelTexture>());
  }

  // The label in the panel's top-left corner: a dark box, a swatch of the model's chart colour,
  // the model, then its settings and step time.
  // Text scales with the panel: 17 px on a 640-pixel panel, no smaller than 11.
  void label(ImDrawList& d, const ComparePanel& p, float left) const {
    ImFont* font = ImGui::GetFont();
    const float f = std::clamp(static_cast<float>(layout.panel_width) / 38.0f, 11.0f, kFontPx), pad = 0.4f * f;
    std::vector<const char*> lines = {p.title.c_str()};
    if (!p.detail.empty()) lines.push_back(p.detail.c_str());
    if (!p.timing.empty()) lines.push_back(p.timing.c_str());
    float w = 0.0f;
    for (const char* line : lines) w = std::max(w, font->CalcTextSizeA(f, FLT_MAX, 0.0f, line).x);
    const float swatch = f;
    w += swatch + pad;
    const float panel_right = left + static_cast<float>(layout.panel_width) - pad;
    const ImVec2 lo(left + pad, pad);
    const ImVec2 hi(std::min(panel_right, lo.x + w + 2 * pad), lo.y + static_cast<float>(lines.size()) * 1.2f * f + 2 * pad);
    d.AddRectFilled(lo, hi, IM_COL32(15, 18, 24, 190), 4.0f);
    d.PushClipRect(lo, hi, true);
    d.AddRectFilled(ImVec2(lo.x + pad, lo.y + pad + 0.1f * f), ImVec2(lo.x + pad + swatch, lo.y + pad + 0.9f * f),
                    imguiColour(p.colour));
    for (std::size_t k = 0; k < lines.size(); ++k) {
      d.AddText(font, f, ImVec2(lo.x + pad + swatch + pad, lo.y + pad + 1.2f * f * static_cast<float>(k)),
                k == 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(215, 220, 228, 255), lines[k]);
    }
    d.PopClipRect();
  }
};

CompareCompositor::CompareCompositor(int width, int height, std::vector<ComparePanel> panels, ChartSpec chart)
    : impl_(std::make_unique<Impl>(width, height, std::move(panels), std::move(chart))) {}

CompareCompositor::~CompareCompositor() = default;

const CompareLayout& CompareCompositor::layout() const { return impl_->layout; }

void CompareCompositor::compose(const std::vector<const Image*>& images, double time_s, Image& out) {
  GF_ASSERT_GL_THREAD();
  Impl& m = *impl_;
  m.frame.bind();
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m.frame.resolve(PixelRect{});
  for (std::size_t i = 0; i < m.textures.size() && i < images.size(); ++i) {
    if (images[i] && images[i]->width > 0) m.textures[i]->upload(*images[i]);
  }
  m.imgui.beginFrame(1.0 / 60.0, {});
  ImDrawList& d = *ImGui::GetBackgroundDrawList();
  const CompareLayout& l = m.layout;
  for (std::size_t i = 0; i < m.panels.size(); ++i) {
    const float left = static_cast<float>(l.panels_left + static_cast<int>(i) * l.panel_width);
    const ImVec2 lo(left, 0.0f), hi(left + static_cast<float>(l.panel_width), static_cast<float>(l.panel_height));
    if (i < m.textures.size() && !m.textures[i]->empty()) {
      d.AddImage(m.textures[i]->id(), lo, hi);
    } else {
      d.AddRectFilled(lo, hi, IM_COL32(60, 60, 60, 255));
    }
    m.label(d, m.panels[i], left);
    if (i > 0) d.AddLine(ImVec2(left, 0.0f), ImVec2(left, hi.y), IM_COL32(255, 255, 255, 255), 2.0f);
  }
  if (l.chart_height > 0) {
    m.chart.cursor_x = time_s;
    addChart(d, m.chart, 0.0f, static_cast<float>(l.chart_top));
  }
  m.imgui.render();
  m.frame.read(out);
}

}  // namespace gf::render

#include "render/chart/compare_view.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/imgui_layer.hpp"
#include "render/state/contact_load.hpp"
#include "render/scene/overlap_region.hpp"

namespace gf::render {
namespace {

constexpr float kFontPx = 17.0f;         // text of a 1280-pixel-wide frame
constexpr float kMinFontPx = 11.0f;      // the smallest text that stays readable
constexpr float kFontFrameWidth = 1280.0f;
constexpr double kMinChartShare = 0.3;  // of the frame's height
constexpr int kMinGridChartPx = 220;    // a 2 x 2 grid's chart: legend, ticks and a plot still fit

// The chart's text: 17 px in a 1280-pixel-wide frame, in proportion below, never under 11 px.
float chartFontPx(int frame_width) {
  return std::clamp(kFontPx * static_cast<float>(frame_width) / kFontFrameWidth, kMinFontPx, kFontPx);
}

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
  l.width = width;
  const double aspect = static_cast<double>(height) / width;
  if (panels >= 3) {  // 2 x 2 half-size panels over a chart as tall as one of them
    l.panel_width = std::max(16, width / 2);
    l.panel_height = std::max(16, static_cast<int>(std::lround(l.panel_width * aspect)));
    for (int i = 0; i < panels; ++i) l.panels.emplace_back((i % 2) * l.panel_width, (i / 2) * l.panel_height);
    if (panels == 3) l.key = Eigen::Vector2i(l.panel_width, l.panel_height);
    l.chart_top = 2 * l.panel_height;
    l.chart_height = std::max(l.panel_height, kMinGridChartPx);
    l.chart_height += l.chart_height % 2;  // H.264's 4:2:0 needs an even height
    l.height = l.chart_top + l.chart_height;
    return l;
  }
  l.height = height;
  l.panel_width = width / panels;
  l.panel_height = static_cast<int>(l.panel_width * aspect);
  const int most = static_cast<int>((1.0 - kMinChartShare) * height);
  if (l.panel_height > most) {  // too tall to leave the chart its share: narrower panels
    l.panel_height = most;
    l.panel_width = static_cast<int>(most / aspect);
  }
  l.panel_width = std::max(16, l.panel_width);
  l.panel_height = std::max(16, l.panel_height);
  const int left = std::max(0, (width - panels * l.panel_width) / 2);  // the row is centred
  for (int i = 0; i < panels; ++i) l.panels.emplace_back(left + i * l.panel_width, 0);
  l.chart_top = l.panel_height;
  l.chart_height = std::max(0, height - l.panel_height);
  return l;
}

// The lines of a panel's label: the model, its settings wrapped at their commas to `room`
// pixels of text `f` high, its step time.
std::vector<std::string> labelLines(const ComparePanel& p, float f, float room) {
  ImFont* font = ImGui::GetFont();
  std::vector<std::string> lines = {p.title};
  std::string line;
  for (std::size_t a = 0; a < p.detail.size();) {
    std::size_t b = p.detail.find(", ", a);
    b = b == std::string::npos ? p.detail.size() : b + 2;
    const std::string piece = p.detail.substr(a, b - a);
    if (!line.empty() && font->CalcTextSizeA(f, FLT_MAX, 0.0f, (line + piece).c_str()).x > room) {
      lines.push_back(line);
      line.clear();
    }
    line += piece;
    a = b;
  }
  if (!line.empty()) lines.push_back(line);
  if (!p.timing.empty()) lines.push_back(p.timing);
  return lines;
}

struct CompareCompositor::Impl {
  std::vector<ComparePanel> panels;
  ChartSpec chart;
  CompareLayout layout;
  Framebuffer frame;
  ImGuiLayer imgui;
  std::vector<std::unique_ptr<PanelTexture>> textures;

  Impl(int w, int h, std::vector<ComparePanel> p, ChartSpec c)
      : panels(std::move(p)),
        chart(std::move(c)),
        layout(compareLayout(w, h, static_cast<int>(panels.size()))),
        frame(layout.width, layout.height, view::Antialiasing::kNone),
        imgui(layout.width, layout.height, chartFontPx(layout.width)) {
    chart.width = layout.width;
    chart.height = layout.chart_height;
    for (std::size_t i = 0; i < panels.size(); ++i) textures.push_back(std::make_unique<PanelTexture>());
  }

  // The label in the panel's top-left corner: a dark box, a swatch of the model's chart colour,
  // the model, then its settings (wrapped to the panel) and step time.
  // Text scales with the panel: 17 px on a 640-pixel panel, no smaller than 11.
  void label(ImDrawList& d, const ComparePanel& p, ImVec2 corner) const {
    ImFont* font = ImGui::GetFont();
    const float f = std::clamp(static_cast<float>(layout.panel_width) / 38.0f, kMinFontPx, kFontPx), pad = 0.4f * f;
    const float swatch = f, panel_right = corner.x + static_cast<float>(layout.panel_width) - pad;
    const ImVec2 lo(corner.x + pad, corner.y + pad);
    const std::vector<std::string> lines = labelLines(p, f, panel_right - lo.x - 3 * pad - swatch);
    float w = 0.0f;
    for (const std::string& line : lines) w = std::max(w, font->CalcTextSizeA(f, FLT_MAX, 0.0f, line.c_str()).x);
    w += swatch + pad;
    const ImVec2 hi(std::min(panel_right, lo.x + w + 2 * pad), lo.y + static_cast<float>(lines.size()) * 1.2f * f + 2 * pad);
    d.AddRectFilled(lo, hi, IM_COL32(15, 18, 24, 190), 4.0f);
    d.PushClipRect(lo, hi, true);
    d.AddRectFilled(ImVec2(lo.x + pad, lo.y + pad + 0.1f * f), ImVec2(lo.x + pad + swatch, lo.y + pad + 0.9f * f),
                    imguiColour(p.colour));
    for (std::size_t k = 0; k < lines.size(); ++k) {
      d.AddText(font, f, ImVec2(lo.x + pad + swatch + pad, lo.y + pad + 1.2f * f * static_cast<float>(k)),
                k == 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(215, 220, 228, 255), lines[k].c_str());
    }
    d.PopClipRect();
  }
};

namespace {

// The key to the marks the panels draw, in the grid's empty cell at `lo` of `size`: one row each,
// a small drawing and what it means (draw_list.hpp and load_marks.hpp draw them in 3D).
void drawKey(ImDrawList& d, ImVec2 lo, ImVec2 size) {
  ImFont* font = ImGui::GetFont();
  const float f = std::clamp(size.x / 30.0f, kMinFontPx, kFontPx), row = 1.55f * f, pad = 0.8f * f;
  d.PushClipRect(lo, ImVec2(lo.x + size.x, lo.y + size.y), true);
  const ImU32 text = IM_COL32(235, 238, 242, 255), soft = IM_COL32(200, 205, 212, 255);
  d.AddText(font, f, ImVec2(lo.x + pad, lo.y + pad), text, "What the pictures show");
  const float icon = 2.2f * f;
  float y = lo.y + pad + 1.6f * row;
  const auto entry = [&](const char* what, auto&& draw) {
    const ImVec2 c(lo.x + pad + 0.5f * icon, y + 0.5f * f);
    draw(c);
    d.AddText(font, f, ImVec2(lo.x + 2.0f * pad + icon, y), soft, what);
    y += row;
  };
  const ImU32 amber = imguiColour(Eigen::Vector3f(1.0f, 0.75f, 0.1f));
  entry("force on the device (scale in each stamp)", [&](ImVec2 c) {
    d.AddLine(ImVec2(c.x - 0.5f * icon, c.y), ImVec2(c.x + 0.3f * icon, c.y), amber, 3.0f);
    d.AddTriangleFilled(ImVec2(c.x + 0.5f * icon, c.y), ImVec2(c.x + 0.2f * icon, c.y - 0.3f * f), ImVec2(c.x + 0.2f * icon, c.y + 0.3f * f), amber);
  });
  entry("twist the patch resists (M_n)", [&](ImVec2 c) {
    d.PathArcTo(c, 0.45f * f, 0.3f, 5.0f, 16);
    d.PathStroke(amber, 0, 2.5f);
  });
  entry("SGO load, low to high (each patch)", [&](ImVec2 c) {
    for (int k = 0; k < 3; ++k) {
      d.AddCircleFilled(ImVec2(c.x + (static_cast<float>(k) - 1.0f) * 0.35f * icon, c.y), 0.28f * f, imguiColour(viridis(0.5 * k)));
    }
  });
  entry("point slipping", [&](ImVec2 c) {
    d.AddCircleFilled(c, 0.25f * f, imguiColour(viridis(0.5)));
    d.AddCircle(c, 0.45f * f, IM_COL32(255, 255, 255, 255), 0, 2.0f);
  });
  entry("device, under the proxy", [&](ImVec2 c) {
    d.AddCircle(c, 0.45f * f, imguiColour(Eigen::Vector3f(0.10f, 0.35f, 0.95f)), 12, 2.0f);
  });
  entry("two patches overlap", [&](ImVec2 c) {
    d.AddRectFilled(ImVec2(c.x - 0.4f * f, c.y - 0.35f * f), ImVec2(c.x + 0.4f * f, c.y + 0.35f * f),
                    imguiColour(Eigen::Vector3f(kOverlapColour[0], kOverlapColour[1], kOverlapColour[2])));
  });
  entry("bands turn with their body", [&](ImVec2 c) {
    for (int k = 0; k < 4; ++k) {
      const float x0 = c.x - 0.5f * icon + 0.25f * icon * static_cast<float>(k);
      d.AddRectFilled(ImVec2(x0, c.y - 0.4f * f), ImVec2(x0 + 0.25f * icon, c.y + 0.4f * f),
                      k % 2 ? IM_COL32(150, 95, 55, 255) : IM_COL32(185, 125, 80, 255));
    }
  });
  d.PopClipRect();
}

}  // namespace

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
  // The panels' area is dark where no panel is (beside a third panel, under the key).
  d.AddRectFilled(ImVec2(0.0f, 0.0f), ImVec2(static_cast<float>(l.width), static_cast<float>(l.chart_top)),
                  IM_COL32(60, 60, 60, 255));
  for (std::size_t i = 0; i < m.panels.size() && i < l.panels.size(); ++i) {
    const ImVec2 lo(static_cast<float>(l.panels[i].x()), static_cast<float>(l.panels[i].y()));
    const ImVec2 hi(lo.x + static_cast<float>(l.panel_width), lo.y + static_cast<float>(l.panel_height));
    if (i < m.textures.size() && !m.textures[i]->empty()) d.AddImage(m.textures[i]->id(), lo, hi);
    m.label(d, m.panels[i], lo);
    d.AddRect(ImVec2(lo.x - 1.0f, lo.y - 1.0f), ImVec2(hi.x + 1.0f, hi.y + 1.0f), IM_COL32(255, 255, 255, 255), 0.0f, 0,
              2.0f);  // a white seam between panels
  }
  if (l.key.x() >= 0) {
    drawKey(d, ImVec2(static_cast<float>(l.key.x()), static_cast<float>(l.key.y())),
            ImVec2(static_cast<float>(l.panel_width), static_cast<float>(l.panel_height)));
  }
  if (l.chart_height > 0) {
    m.chart.cursor_x = time_s;
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "t = %.2f s", time_s);
    m.chart.cursor_label = stamp;
    addChart(d, m.chart, 0.0f, static_cast<float>(l.chart_top));
  }
  m.imgui.render();
  m.frame.read(out);
}

}  // namespace gf::render

#include "render/patch_insets.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/context.hpp"
#include "render/draw_list.hpp"
#include "render/gl.hpp"
#include "render/gpu.hpp"
#include "render/imgui_layer.hpp"

namespace gf::render {
namespace {

constexpr double kInsetShare = 0.3;    // of the frame's height
constexpr double kMarginShare = 0.015;  // of the frame's height
constexpr float kLabelFontPx = 15.0f;  // the largest label text; smaller insets get smaller text

const char* modelLabel(const sim::PatchSettings& p) {
  switch (sim::effectiveModel(p)) {
    case sim::ContactModel::kGodObject: return "god-object";
    case sim::ContactModel::kSoftFinger: return "soft finger";
    case sim::ContactModel::kGodFinger: return "god-finger";
  }
  return "";
}

}  // namespace

bool contactCloseUp(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, std::size_t finger,
                    sim::Snapshot& only, sim::Camera& camera) {
  if (finger >= snapshot.fingers.size() || snapshot.fingers[finger].contacts.empty()) return false;
  only = snapshot;
  for (std::size_t g = 0; g < only.fingers.size(); ++g) {
    if (g != finger) only.fingers[g].contacts.clear();
  }
  const sim::ContactSnapshot& c = snapshot.fingers[finger].contacts.front();
  const double half = std::max(1.5 * scene.fingers[finger].patch.r_max, 1.3 * c.radius) + 0.002;
  camera = closeUpCamera(c.point_world, c.outward_normal_world, half);
  return true;
}

std::vector<InsetRect> insetRects(int width, int height, int fingers, InsetCorner corner) {
  std::vector<InsetRect> out;
  if (fingers <= 0) return out;
  const int margin = std::max(2, static_cast<int>(std::lround(kMarginShare * height)));
  int size = static_cast<int>(std::lround(kInsetShare * height));
  size = std::min(size, (width - (fingers + 1) * margin) / fingers);
  size = std::max(size, 16);
  const int row = fingers * size + (fingers - 1) * margin;
  const int left = corner == InsetCorner::kBottomRight ? width - margin - row : margin;
  for (int i = 0; i < fingers; ++i) out.push_back({left + i * (size + margin), height - margin - size, size});
  return out;
}

struct PatchInsets::Impl {
  sim::SceneDesc scene;
  int width, height;
  std::vector<InsetRect> rects;
  Framebuffer frame;
  ImGuiLayer labels;
  sim::Snapshot only;  // one finger's contacts, reused from frame to frame

  Impl(const sim::SceneDesc& s, int w, int h, InsetCorner corner, sim::Antialiasing aa, int samples)
      : scene(s),
        width(w),
        height(h),
        rects(insetRects(w, h, static_cast<int>(s.fingers.size()), corner)),
        frame(rects.empty() ? 16 : rects.front().size, rects.empty() ? 16 : rects.front().size,
              aa == sim::Antialiasing::kMsaa ? aa : sim::Antialiasing::kNone, samples),  // FXAA: not worth a pass at this size
        labels(w, h, kLabelFontPx) {}

  // The label of finger f over the top of its inset, in three short lines: the finger and its
  // model; n_SGO and the radius; the normal force (or "no contact"). An inset under 120 pixels
  // (a comparison's panel) says only the finger and the force.
  void label(ImDrawList& d, std::size_t f, const sim::Snapshot& snap, bool touching) const {
    const InsetRect& r = rects[f];
    const sim::FingerDesc& desc = scene.fingers[f];
    const bool small = r.size < 120;
    char lines[3][64];
    int count = 0;
    if (small) {
      std::snprintf(lines[count++], sizeof lines[0], "%s", desc.name.c_str());
    } else {
      std::snprintf(lines[count++], sizeof lines[0], "%s: %s", desc.name.c_str(), modelLabel(desc.patch));
    }
    if (!touching) {
      std::snprintf(lines[count++], sizeof lines[0], "no contact");
    } else {
      const sim::FingerSnapshot& fs = snap.fingers[f];
      const sim::ContactSnapshot& c = fs.contacts.front();
      if (!small && fs.sgo_count > 0) {
        std::snprintf(lines[count++], sizeof lines[0], "%d SGOs, r %.1f mm", fs.sgo_count, 1000.0 * c.radius);
      } else if (!small) {
        std::snprintf(lines[count++], sizeof lines[0], "one point");
      }
      std::snprintf(lines[count++], sizeof lines[0], "F_n %.2f N", std::max(0.0, fs.feedback_force.dot(c.outward_normal_world)));
    }
    ImFont* font = ImGui::GetFont();
    const float px = std::clamp(0.07f * static_cast<float>(r.size), 9.0f, kLabelFontPx), pad = 0.3f * px;
    const ImVec2 lo(static_cast<float>(r.x), static_cast<float>(r.y));
    const ImVec2 hi(lo.x + static_cast<float>(r.size), lo.y + static_cast<float>(r.size));
    if (!touching) d.AddRectFilled(lo, hi, IM_COL32(40, 44, 52, 150));
    d.AddRectFilled(lo, ImVec2(hi.x, lo.y + static_cast<float>(count) * 1.15f * px + 2.0f * pad), IM_COL32(15, 18, 24, 150));
    d.PushClipRect(lo, hi, true);
    for (int k = 0; k < count; ++k) {
      d.AddText(font, px, ImVec2(lo.x + pad + 2.0f, lo.y + pad + 1.15f * px * static_cast<float>(k)),
                k == 0 ? IM_COL32(255, 255, 255, 255) : IM_COL32(215, 220, 228, 255), lines[k]);
    }
    d.PopClipRect();
    d.AddRect(lo, hi, imguiColour(fingerColour(static_cast<int>(f))), 0.0f, 0, std::max(2.0f, 0.012f * static_cast<float>(r.size)));
  }
};

PatchInsets::PatchInsets(const sim::SceneDesc& scene, int frame_width, int frame_height, InsetCorner corner,
                         sim::Antialiasing antialiasing, int msaa_samples)
    : impl_(std::make_unique<Impl>(scene, frame_width, frame_height, corner, antialiasing, msaa_samples)) {}

PatchInsets::~PatchInsets() = default;

void PatchInsets::draw(SceneRenderer& renderer, const sim::Snapshot& snapshot, unsigned target) {
  GF_ASSERT_GL_THREAD();
  Impl& m = *impl_;
  const RenderSettings saved = renderer.settings();
  RenderSettings close = saved;
  close.fingers = false;  // the proxy would hide the patch it stands on
  close.ground = false;   // a camera under a lifted body is under the ground
  close.patch_highlight = true;
  renderer.setSettings(close);
  std::vector<bool> touching(m.rects.size(), false);
  for (std::size_t f = 0; f < m.rects.size(); ++f) {
    sim::Camera camera;
    if (!contactCloseUp(m.scene, snapshot, f, m.only, camera)) continue;
    touching[f] = true;
    const InsetRect& r = m.rects[f];
    m.frame.bind();
    m.frame.resolve(renderer.draw(m.only, camera, r.size, r.size));
    m.frame.copyInto(target, r.x, m.height - r.y - r.size);
  }
  renderer.setSettings(saved);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  m.labels.beginFrame(1.0 / 60.0, {});
  ImDrawList& d = *ImGui::GetForegroundDrawList();
  for (std::size_t f = 0; f < m.rects.size(); ++f) m.label(d, f, snapshot, touching[f]);
  m.labels.render();
  glBindFramebuffer(GL_FRAMEBUFFER, target);
}

}  // namespace gf::render

#include "render/overlay/patch_insets.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/gl/context.hpp"
#include "render/scene/draw_list.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/imgui_layer.hpp"
#include "render/overlay/labels.hpp"
#include "render/scene/overlap_region.hpp"

namespace gf::render {
namespace {

constexpr double kInsetShare = 0.3;    // of the frame's height
constexpr double kMarginShare = 0.015;  // of the frame's height

}  // namespace

bool contactCloseUp(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, std::size_t finger,
                    sim::Snapshot& only, view::Camera& camera) {
  if (finger >= snapshot.fingers.size() || snapshot.fingers[finger].contacts.empty()) return false;
  only = snapshot;
  const sim::ContactSnapshot& c = snapshot.fingers[finger].contacts.front();
  // Other fingers' contacts leave the close-up, but for patches overlapping this one: they stay
  // with the region both cover (docs/overlap.md).
  for (std::size_t g = 0; g < only.fingers.size(); ++g) {
    if (g == finger) continue;
    std::vector<sim::ContactSnapshot>& others = only.fingers[g].contacts;
    others.erase(std::remove_if(others.begin(), others.end(),
                                [&](const sim::ContactSnapshot& o) { return !patchesOverlap(c, o); }),
                 others.end());
  }
  const double half = std::max(1.5 * scene.fingers[finger].patch.r_max, 1.3 * c.radius) + 0.002;
  camera = closeUpCamera(c.point_world, c.outward_normal_world, half);
  return true;
}

namespace {

int insetMargin(int height) { return std::max(2, static_cast<int>(std::lround(kMarginShare * height))); }

int insetSize(int width, int height, int fingers) {
  const int margin = insetMargin(height);
  const int size = std::min(static_cast<int>(std::lround(kInsetShare * height)), (width - (fingers + 1) * margin) / fingers);
  return std::max(size, 16);
}

}  // namespace

std::vector<InsetRect> insetRects(int width, int height, int fingers, InsetCorner corner, bool column) {
  std::vector<InsetRect> out;
  if (fingers <= 0) return out;
  const int margin = insetMargin(height), size = insetSize(width, height, fingers);
  const int reserve = static_cast<int>(std::ceil(insetCaptionReserve(contactLabelPx(size))));
  const bool right = corner == InsetCorner::kBottomRight || corner == InsetCorner::kTopRight;
  const bool bottom = corner == InsetCorner::kBottomRight || corner == InsetCorner::kBottomLeft;
  if (column) {  // each square under its caption, the first at the top
    const int left = right ? width - margin - size : margin;
    const int first = bottom ? height - margin - fingers * (size + reserve) + reserve : margin + reserve;
    for (int i = 0; i < fingers; ++i) out.push_back({left, first + i * (size + reserve), size});
    return out;
  }
  const int row = fingers * size + (fingers - 1) * margin;
  const int left = right ? width - margin - row : margin;
  const int top = bottom ? height - margin - size : margin + reserve;
  for (int i = 0; i < fingers; ++i) out.push_back({left + i * (size + margin), top, size});
  return out;
}

LabelSizes insetBlock(int width, int height, int fingers) {
  LabelSizes s;
  s.margin = static_cast<float>(insetMargin(height));
  if (fingers <= 0) return s;
  const int size = insetSize(width, height, fingers);
  const float reserve = std::ceil(insetCaptionReserve(contactLabelPx(size)));
  s.insets_w = static_cast<float>(fingers * size + (fingers - 1) * insetMargin(height));
  s.insets_h = static_cast<float>(size) + reserve;
  const float column_h = static_cast<float>(fingers) * (static_cast<float>(size) + reserve);
  if (fingers > 1 && column_h <= static_cast<float>(height) - 2.0f * s.margin) {
    s.column_w = static_cast<float>(size);
    s.column_h = column_h;
  }
  return s;
}

struct PatchInsets::Impl {
  sim::SceneDesc scene;
  int width, height;
  std::vector<InsetRect> rects;
  Framebuffer frame;
  sim::Snapshot only;  // one finger's contacts, reused from frame to frame
  // Per finger, as last drawn: whether it touched something, and the inset's camera.
  std::vector<char> touching;
  std::vector<view::Camera> cameras;
  double arrow_m_per_n = RenderSettings{}.force_arrow_m_per_n;  // the frame's, as last drawn

  Impl(const sim::SceneDesc& s, int w, int h, InsetCorner corner, view::Antialiasing aa, int samples)
      : scene(s),
        width(w),
        height(h),
        rects(insetRects(w, h, static_cast<int>(s.fingers.size()), corner)),
        frame(rects.empty() ? 16 : rects.front().size, rects.empty() ? 16 : rects.front().size,
              aa == view::Antialiasing::kMsaa ? aa : view::Antialiasing::kNone, samples),  // FXAA: not worth a pass at this size
        touching(rects.size(), 0),
        cameras(rects.size()) {}
};

PatchInsets::PatchInsets(const sim::SceneDesc& scene, int frame_width, int frame_height, InsetCorner corner,
                         view::Antialiasing antialiasing, int msaa_samples)
    : impl_(std::make_unique<Impl>(scene, frame_width, frame_height, corner, antialiasing, msaa_samples)) {}

PatchInsets::~PatchInsets() = default;

void PatchInsets::place(InsetCorner corner, bool column) {
  impl_->rects = insetRects(impl_->width, impl_->height, static_cast<int>(impl_->rects.size()), corner, column);
}

void PatchInsets::draw(SceneRenderer& renderer, const sim::Snapshot& snapshot, unsigned target) {
  GF_ASSERT_GL_THREAD();
  Impl& m = *impl_;
  const RenderSettings saved = renderer.settings();
  m.arrow_m_per_n = saved.force_arrow_m_per_n;
  RenderSettings close = saved;
  close.fingers = false;         // the proxy would hide the patch it stands on (and so would its shadow)
  close.ground = false;          // a camera under a lifted body is under the ground
  close.contact_arrows = false;  // they point at the camera: the labels draw the forces in 2D
  close.patch_highlight = true;
  close.targets = nullptr;          // a target's ghost would cover the patch
  renderer.setSettings(close);
  for (std::size_t f = 0; f < m.rects.size(); ++f) {
    m.touching[f] = contactCloseUp(m.scene, snapshot, f, m.only, m.cameras[f]);
    if (!m.touching[f]) continue;
    const InsetRect& r = m.rects[f];
    m.frame.bind();
    m.frame.resolve(renderer.draw(m.only, m.cameras[f], r.size, r.size));
    m.frame.copyInto(target, r.x, m.height - r.y - r.size);
  }
  renderer.setSettings(saved);
  glBindFramebuffer(GL_FRAMEBUFFER, target);
}

float PatchInsets::labelPx() const { return impl_->rects.empty() ? kMinLabelPx : contactLabelPx(impl_->rects.front().size); }

void PatchInsets::drawLabels(const ImGuiLayer& layer, const sim::Snapshot& snapshot) const {
  const Impl& m = *impl_;
  const float px = labelPx();
  ImFont* font = layer.font(px);
  ImDrawList& d = *ImGui::GetForegroundDrawList();
  for (std::size_t f = 0; f < m.rects.size() && f < snapshot.fingers.size(); ++f) {
    const InsetRect& r = m.rects[f];
    ContactLabel label;
    label.finger = &m.scene.fingers[f];
    label.finger_index = static_cast<int>(f);
    label.state = &snapshot.fingers[f];
    label.contact = m.touching[f] && !snapshot.fingers[f].contacts.empty() ? &snapshot.fingers[f].contacts.front() : nullptr;
    label.camera = m.cameras[f];
    label.time = snapshot.time;
    label.arrow_m_per_n = m.arrow_m_per_n;
    drawContactLabel(d, font, px, {static_cast<float>(r.x), static_cast<float>(r.y), static_cast<float>(r.size)}, label);
  }
}

}  // namespace gf::render

#include "render/overlay/layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/overlay/labels.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/draw_list.hpp"
#include "render/scene/finger_marks.hpp"
#include "render/scene/pad_mesh.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

constexpr double kNearM = 0.002;  // m: the renderer's near plane

// Projects world points onto the picture and grows a box around those in front of the camera.
struct Projector {
  Eigen::Matrix4d view_proj;
  int width, height;

  Projector(const view::Camera& c, int w, int h) : width(w), height(h) {
    const Eigen::Matrix4d view = lookAt(c.position, c.target, upFor(c.target - c.position)).cast<double>();
    view_proj = perspective(c.fov_deg, double(w) / h, kNearM, 1000.0).cast<double>() * view;
  }

  // Grows `box` by `p` (m) and a sphere of `radius` about it; false when behind the camera.
  bool add(ScreenBox& box, bool& any, const Vec3& p, double radius) const {
    const Eigen::Vector4d c = view_proj * p.homogeneous();
    if (c.w() <= kNearM) return false;
    const double x = (0.5 + 0.5 * c.x() / c.w()) * width, y = (0.5 - 0.5 * c.y() / c.w()) * height;
    const double r = radius * view_proj(1, 1) * 0.5 * height / c.w();  // the sphere's radius in pixels
    const ScreenBox b{static_cast<float>(x - r), static_cast<float>(y - r), static_cast<float>(x + r),
                      static_cast<float>(y + r)};
    if (!any) {
      box = b;
      any = true;
    } else {
      box = {std::min(box.x0, b.x0), std::min(box.y0, b.y0), std::max(box.x1, b.x1), std::max(box.y1, b.y1)};
    }
    return true;
  }

  // `box` cut to the picture; false when nothing of it is inside.
  bool clip(ScreenBox& box) const {
    box = {std::max(box.x0, 0.0f), std::max(box.y0, 0.0f), std::min(box.x1, float(width)), std::min(box.y1, float(height))};
    return box.x1 > box.x0 && box.y1 > box.y0;
  }
};

// What the box of `c` covers of `subjects` (pixels^2).
float covered(const ScreenBox& box, const std::vector<ScreenBox>& subjects) {
  float sum = 0.0f;
  for (const ScreenBox& s : subjects) sum += box.overlap(s);
  return sum;
}

// One place a block may take: a corner, in a row or a column, of a w x h box.
struct Slot {
  Corner corner;
  bool column;
  float w, h;
};

// The slot for a block among `slots`: `keep` (its index) while clear, else the first covering the
// least of `subjects` (a clear one when there is one).
std::size_t pick(const std::vector<ScreenBox>& subjects, const std::vector<Slot>& slots, std::size_t keep, int width,
                 int height, float margin) {
  const auto cover = [&](const Slot& s) { return covered(cornerBox(s.corner, s.w, s.h, width, height, margin), subjects); };
  if (keep < slots.size() && cover(slots[keep]) == 0.0f) return keep;
  std::size_t best = 0;
  float least = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const float a = cover(slots[i]);
    if (a < least) least = a, best = i;
  }
  return best;
}

}  // namespace

float ScreenBox::overlap(const ScreenBox& o) const {
  const float w = std::min(x1, o.x1) - std::max(x0, o.x0), h = std::min(y1, o.y1) - std::max(y0, o.y0);
  return w > 0.0f && h > 0.0f ? w * h : 0.0f;
}

std::vector<ScreenBox> subjectBoxes(const sim::SceneDesc& scene, const std::vector<std::shared_ptr<const sim::Mesh>>& surfaces,
                                    const sim::Snapshot& snap, const view::Camera& camera, int width, int height,
                                    double arrow_m_per_n, view::ProxyLook look) {
  const Projector project(camera, width, height);
  std::vector<ScreenBox> out;
  const auto keep = [&](ScreenBox box, bool any) {
    if (any && project.clip(box)) out.push_back(box);
  };
  std::vector<char> soft(snap.bodies.size(), 0);
  for (const sim::SoftBodySnapshot& s : snap.soft_bodies) {  // where their nodes are now
    ScreenBox box;
    bool any = false;
    for (const Vec3& p : s.nodes) project.add(box, any, p, 0.0);
    keep(box, any);
    if (s.body >= 0 && static_cast<std::size_t>(s.body) < soft.size()) soft[static_cast<std::size_t>(s.body)] = 1;
  }
  for (std::size_t b = 0; b < surfaces.size() && b < snap.bodies.size(); ++b) {
    if (!surfaces[b] || surfaces[b]->vertexCount() == 0 || soft[b]) continue;
    const Vec3 &lo = surfaces[b]->boundsMin(), &hi = surfaces[b]->boundsMax();
    ScreenBox box;
    bool any = false;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 local((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(), (corner & 4) ? hi.z() : lo.z());
      project.add(box, any, snap.bodies[b].toWorld(local), 0.0);
    }
    keep(box, any);
  }
  for (std::size_t f = 0; f < snap.fingers.size() && f < scene.fingers.size(); ++f) {
    const sim::FingerSnapshot& finger = snap.fingers[f];
    ScreenBox box;
    bool any = false;
    const double reach = std::max(fingerReach(finger, proxySphereRadius(finger, scene.fingers[f].proxy.radius), look),
                                  padReach(finger.pad, finger.proxy));
    project.add(box, any, finger.proxy, reach);
    const double force = finger.feedback_force.norm();
    if (!finger.contacts.empty() && arrow_m_per_n > 0.0 && force > 1e-9) {  // DrawSettings::max_arrow_m at most
      const double length = std::min(DrawSettings{}.max_arrow_m, force * arrow_m_per_n);
      project.add(box, any, finger.proxy + (length / force) * finger.feedback_force, 0.0);
    }
    keep(box, any);
    for (const sim::ContactSnapshot& c : finger.contacts) {
      const double r = std::max(c.radius, scene.fingers[f].patch.r_max);
      ScreenBox patch;
      bool seen = false;
      const Vec3 u = c.outward_normal_world.unitOrthogonal(), v = c.outward_normal_world.cross(u);
      for (const Vec3& d : {u, Vec3(-u), v, Vec3(-v)}) project.add(patch, seen, c.point_world + r * d, 0.0);
      keep(patch, seen);
    }
  }
  return out;
}

ScreenBox cornerBox(Corner c, float w, float h, int width, int height, float margin) {
  const bool right = c == Corner::kBottomRight || c == Corner::kTopRight;
  const bool bottom = c == Corner::kBottomRight || c == Corner::kBottomLeft;
  const float x0 = right ? float(width) - margin - w : margin;
  const float y0 = bottom ? float(height) - margin - h : margin;
  return {x0, y0, x0 + w, y0 + h};
}

LabelSizes frameLabelSizes(int width, int height, int fingers, bool insets, bool stamp, double time,
                           double arrow_m_per_n) {
  LabelSizes sizes = insets ? insetBlock(width, height, fingers) : LabelSizes{};
  sizes.margin = std::max(2.0f, std::round(0.015f * static_cast<float>(height)));
  if (stamp) {
    const StampSize size = stampSize(stampLabelPx(height), time, arrow_m_per_n);
    sizes.stamp_w = size.w, sizes.stamp_h = size.h;
  }
  return sizes;
}

LabelPlacement placeLabels(const std::vector<ScreenBox>& subjects, const LabelSizes& sizes, int width, int height,
                           const LabelPlacement& previous, const std::array<bool, 4>& insets_allowed,
                           const std::array<bool, 4>& stamp_allowed) {
  LabelPlacement out;
  std::vector<ScreenBox> taken = subjects;
  std::vector<Slot> slots;
  if (sizes.insets_w > 0.0f && sizes.insets_h > 0.0f) {
    for (const bool column : {false, true}) {
      if (column && !(sizes.column_w > 0.0f && sizes.column_h > 0.0f)) continue;
      for (const Corner c : kCorners) {
        if (!insets_allowed[static_cast<std::size_t>(c)]) continue;
        slots.push_back({c, column, column ? sizes.column_w : sizes.insets_w, column ? sizes.column_h : sizes.insets_h});
      }
    }
  }
  if (!slots.empty()) {
    std::size_t keep = slots.size();
    for (std::size_t i = 0; i < slots.size(); ++i) {
      if (slots[i].corner == previous.insets && slots[i].column == previous.column) keep = i;
    }
    const Slot& s = slots[pick(subjects, slots, keep, width, height, sizes.margin)];
    out.insets = s.corner;
    out.column = s.column;
    taken.push_back(cornerBox(s.corner, s.w, s.h, width, height, sizes.margin));
  }
  static constexpr std::array<Corner, 4> kStampOrder = {Corner::kBottomLeft, Corner::kTopLeft, Corner::kBottomRight,
                                                        Corner::kTopRight};
  std::vector<Slot> stamps;
  std::size_t keep = 4;
  for (const Corner c : kStampOrder) {
    if ((!slots.empty() && c == out.insets) || !stamp_allowed[static_cast<std::size_t>(c)]) continue;
    if (c == previous.stamp) keep = stamps.size();
    stamps.push_back({c, false, sizes.stamp_w, sizes.stamp_h});
  }
  if (!stamps.empty()) out.stamp = stamps[pick(taken, stamps, keep, width, height, sizes.margin)].corner;
  return out;
}

std::array<ScreenBox, 2> placedBoxes(const LabelPlacement& p, const LabelSizes& s, int width, int height) {
  return {cornerBox(p.insets, p.column ? s.column_w : s.insets_w, p.column ? s.column_h : s.insets_h, width, height, s.margin),
          cornerBox(p.stamp, s.stamp_w, s.stamp_h, width, height, s.margin)};
}

}  // namespace gf::render

#include "render/scene/screen_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gf::render {

SphereBounds::SphereBounds(const Eigen::Matrix4d& view, double fov_deg, int width, int height)
    : view_(view), fy_(1.0 / std::tan(0.5 * fov_deg * std::numbers::pi / 180.0)), width_(width), height_(height) {
  fx_ = fy_ * height / width;
}

void SphereBounds::add(const Eigen::Vector3d& centre_world, double r) {
  const Eigen::Vector3d c = (view_ * centre_world.homogeneous()).head<3>();
  const double d = -c.z();
  if (d - r < 1e-3) {
    everywhere_ = true;  // reaches behind the camera
    return;
  }
  for (const double z : {d - r, d + r}) {
    x0_ = std::min(x0_, fx_ * (c.x() - r) / z), x1_ = std::max(x1_, fx_ * (c.x() + r) / z);
    y0_ = std::min(y0_, fy_ * (c.y() - r) / z), y1_ = std::max(y1_, fy_ * (c.y() + r) / z);
  }
}

PixelRect SphereBounds::pixels() const {
  if (everywhere_) return {0, 0, width_, height_};
  const auto px = [](double ndc, int size) { return static_cast<int>(std::clamp((0.5 * ndc + 0.5) * size, 0.0, double(size))); };
  return {px(x0_, width_), px(y0_, height_), px(x1_, width_) + 1, px(y1_, height_) + 1};
}

Eigen::AlignedBox3f boundsOf(const std::vector<Vertex>& vertices) {
  Eigen::AlignedBox3f box;
  for (const Vertex& v : vertices) box.extend(Eigen::Map<const Eigen::Vector3f>(v.position));
  return box;
}

PixelRect overlayPixels(const DrawList& list, const std::array<Eigen::AlignedBox3f, 4>& shape_boxes,
                        const Eigen::Matrix4f& view_proj, int width, int height) {
  if (list.items.empty()) return {};
  double x0 = 1, x1 = -1, y0 = 1, y1 = -1;  // NDC
  bool everywhere = false;
  const auto add = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector4f c = view_proj * p.homogeneous();
    if (c.w() < 1e-3f) {
      everywhere = true;
      return;
    }
    x0 = std::min(x0, double(c.x() / c.w())), x1 = std::max(x1, double(c.x() / c.w()));
    y0 = std::min(y0, double(c.y() / c.w())), y1 = std::max(y1, double(c.y() / c.w()));
  };
  for (const DrawItem& item : list.items) {
    if (item.shape == DrawShape::kTriangles || item.shape == DrawShape::kLines) {
      for (int v = item.first; v < item.first + item.count; ++v) {
        add(Eigen::Map<const Eigen::Vector3f>(list.vertices[static_cast<std::size_t>(v)].position));
      }
    } else {
      const Eigen::AlignedBox3f& box = shape_boxes[static_cast<std::size_t>(item.shape)];
      for (int k = 0; k < 8; ++k) {
        add((item.model * box.corner(static_cast<Eigen::AlignedBox3f::CornerType>(k)).homogeneous()).head<3>());
      }
    }
    if (everywhere) return {0, 0, width, height};
  }
  const auto px = [](double ndc, int size, int pad) {
    return static_cast<int>(std::clamp(std::floor((0.5 * ndc + 0.5) * size) + pad, 0.0, double(size)));
  };
  return {px(x0, width, -2), px(y0, height, -2), px(x1, width, 3), px(y1, height, 3)};
}

}  // namespace gf::render

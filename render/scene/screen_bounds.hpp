// The pixels that parts of a frame can cover: its moving things' bounding spheres (what FXAA
// filters; outside them a frame is the smooth backdrop), and its contact overlay from the draw
// list alone (what a restored bodies' layer needs depth under: the rest of such a frame is not
// depth-tested again).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "render/gl/gpu.hpp"
#include "render/gl/vertex.hpp"
#include "render/scene/draw_list.hpp"

namespace gf::render {

/// The pixels of a width x height frame that spheres can cover, seen by a camera with view
/// matrix `view` and vertical field of view `fov_deg`; each sphere projected conservatively.
class SphereBounds {
 public:
  SphereBounds(const Eigen::Matrix4d& view, double fov_deg, int width, int height);
  void add(const Eigen::Vector3d& centre_world, double radius);
  /// The whole frame once a sphere reached the eye's plane or behind it.
  PixelRect pixels() const;

 private:
  Eigen::Matrix4d view_;
  double fx_, fy_;
  int width_, height_;
  double x0_ = 1, x1_ = -1, y0_ = 1, y1_ = -1;  // NDC
  bool everywhere_ = false;
};

/// The bounding box of a mesh's vertices.
Eigen::AlignedBox3f boundsOf(const std::vector<Vertex>& vertices);

/// The pixels of a width x height frame seen through `view_proj` that `list` can draw on: its
/// vertex ranges and its unit shapes' boxes (`shape_boxes`, in DrawShape order: sphere, dot,
/// cylinder, cone) placed by their models, projected, with 2 pixels to spare for lines and
/// rounding. Empty for an empty list; the whole frame when a point is not in front of the eye.
PixelRect overlayPixels(const DrawList& list, const std::array<Eigen::AlignedBox3f, 4>& shape_boxes,
                        const Eigen::Matrix4f& view_proj, int width, int height);

}  // namespace gf::render

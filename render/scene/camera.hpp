// Cameras and the matrices they give. Units are metres; y is up.
#pragma once

#include <Eigen/Geometry>

#include "render/view/view_desc.hpp"

namespace gf::render {

/// World-to-camera matrix (right-handed, camera looks down -z). `up` must not be parallel to
/// the viewing direction.
Eigen::Matrix4f lookAt(const sim::Vec3& eye, const sim::Vec3& target, const sim::Vec3& up);
/// OpenGL perspective projection; fov in degrees, near/far in m.
Eigen::Matrix4f perspective(double fov_deg, double aspect, double near_m, double far_m);
/// OpenGL orthographic projection of the box [-half, half]^2 x [near, far] (m).
Eigen::Matrix4f orthographic(double half_width, double half_height, double near_m, double far_m);
/// A world up vector usable with lookAt for this viewing direction (+y unless nearly vertical).
sim::Vec3 upFor(const sim::Vec3& direction);

/// A camera that looks at `point` straight down `-outward_normal` from `distance` m, showing
/// about a square of 2 * half_extent m: the contact-area close-up.
view::Camera closeUpCamera(const sim::Vec3& point, const sim::Vec3& outward_normal, double half_extent);

}  // namespace gf::render

#include "sim/scene/coupling.hpp"

namespace gf::sim {

Vec3 couplingForce(const CouplingSettings& s, const Vec3& device_pos, const Vec3& device_vel,
                   const Vec3& proxy_pos, const Vec3& proxy_vel) {
  const Vec3 f = s.stiffness * (device_pos - proxy_pos) + s.damping * (device_vel - proxy_vel);
  if (!f.allFinite()) return Vec3::Zero();
  const double norm = f.norm();
  return norm > s.max_force ? Vec3(f * (s.max_force / norm)) : f;
}

}  // namespace gf::sim

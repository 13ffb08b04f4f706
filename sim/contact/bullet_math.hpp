// Eigen vectors to Bullet's and back: the one conversion the Bullet-speaking files of sim/
// (contact/, world/) share. Internal to sim/.
#pragma once

#include <btBulletDynamicsCommon.h>

#include "sim/math.hpp"

namespace gf::sim {

inline btVector3 toBt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 toEigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace gf::sim

#include "sim/about.hpp"

#include <LinearMath/btScalar.h>
#include <assimp/version.h>

#include <Eigen/Core>

namespace gf::sim {

std::string libraryVersion() { return GF_VERSION; }

std::string bulletVersion() {
  const int v = btGetVersion();  // 324: 3.24
  return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
         (sizeof(btScalar) == 8 ? " (double precision)" : " (single precision)");
}

std::string assimpVersion() {
  return "assimp " + std::to_string(aiGetVersionMajor()) + "." + std::to_string(aiGetVersionMinor()) + "." +
         std::to_string(aiGetVersionPatch());
}

std::string eigenVersion() {
  return "Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
         std::to_string(EIGEN_MINOR_VERSION);
}

}  // namespace gf::sim

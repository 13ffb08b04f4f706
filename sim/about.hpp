// What this build of the library is and what it was built on, for reports and `--version`.
#pragma once

#include <string>

namespace gf::sim {

/// The library's version ("0.1.0").
std::string libraryVersion();
/// The physics engine: "Bullet 3.24 (double precision)".
std::string bulletVersion();
/// The mesh importer: "assimp 5.2.5".
std::string assimpVersion();
/// The linear algebra: "Eigen 3.4.0".
std::string eigenVersion();

}  // namespace gf::sim

// Convex decompositions kept on disk between runs: HACD takes seconds and most of a run's
// memory on a mesh of a few thousand triangles (bunny: 3.1 s, about 130 MB), and gives the same
// parts for the same mesh and settings every time. Internal to sim/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/mesh/mesh.hpp"

namespace gf::sim {

/// The convex parts of a decomposition, each as its hull's points, in the body frame.
using HullParts = std::vector<std::vector<Vec3>>;

/// Folder of the cache: $GF_CACHE_DIR, else $XDG_CACHE_HOME/godfinger, else
/// $HOME/.cache/godfinger; empty when none is set or GF_CACHE_DIR is "off".
std::string decompositionCacheDir();

/// Key of a decomposition: the mesh's vertices and triangles, bit for bit, and the
/// decomposition's settings (`settings`, any bytes that change its result).
std::uint64_t decompositionKey(const Mesh& mesh, const std::string& settings);

/// The parts stored under `key` in `dir`, or nothing when there is no such file or it is not
/// a whole one (a wrong header or key, sizes that do not match the file): the caller
/// decomposes again.
std::optional<HullParts> loadDecomposition(const std::string& dir, std::uint64_t key);

/// Stores `parts` under `key` in `dir` (created if missing) through a temporary file renamed
/// into place, so readers see a whole file or none. Best effort: false when it could not.
bool storeDecomposition(const std::string& dir, std::uint64_t key, const HullParts& parts);

}  // namespace gf::sim

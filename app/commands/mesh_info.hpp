// `godfinger mesh-info`: what a mesh file holds and what it would be as a body, before a scene
// uses it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace gf::app {

struct MeshInfoOptions {
  std::string path;
  double scale = 1.0;     ///< file units to metres, as a body's `scale`
  double mass = 0.0;      ///< kg; 0: use density
  double density = 1000;  ///< kg/m^3 when no mass is given
};

/// Parts and node transforms, counts, bounds (as read and in metres), the unit and up axis the
/// file declares, closed / manifold / outward checks with the offending edges' counts, volume,
/// centre of mass and inertia (for the mass or density), and a suggested scale when the size
/// looks like millimetres or centimetres. Throws sim::MeshLoadError (naming the file).
nlohmann::json meshInfoJson(const MeshInfoOptions& options);

/// The same as text for a terminal.
std::string meshInfoText(const nlohmann::json& info);

}  // namespace gf::app

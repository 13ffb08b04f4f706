// JSON pictures of contact areas: one computed patch (`godfinger patch`) and every contact of a
// world snapshot (contacts/ of a session, `snapshot` of a live session).
#pragma once

#include <nlohmann/json.hpp>

#include "sim/scene_desc.hpp"
#include "sim/snapshot.hpp"

namespace gf::app {

/// A patch in the mesh's own frame: radius, radial vectors, distances, stops, SGOs with their
/// faces, and the walked paths (one polyline per SGO).
nlohmann::json patchJson(const sim::Patch& patch, const sim::PatchSettings& settings);

/// Every finger of a snapshot in world coordinates: device, proxy, coupling force and each
/// contact with its radius, SGOs and walked paths.
nlohmann::json contactsJson(const sim::Snapshot& snapshot, const sim::SceneDesc& scene);

}  // namespace gf::app

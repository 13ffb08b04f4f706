// JSON pictures of contact areas: one computed patch (`godfinger patch`) and every contact of a
// world snapshot (contacts/ of a session, `snapshot` of a live session).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "sim/patch/god_finger.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::app {

/// A finger's settings as JSON, named as fingerSettings() names them with their unit
/// ("r_max_m", "tau_a_deg"), in the unit users give them: every one, or only the live
/// (god-finger) ones.
nlohmann::json fingerSettingsJson(const sim::FingerDesc& finger, bool live_only);

/// The scene-wide settings (sceneSettings()) as JSON: "duration_s", "haptic_rate_hz",
/// "world_solver_iterations", ...
nlohmann::json sceneSettingsJson(const sim::SceneDesc& scene);

/// A patch in the mesh's own frame ("frame": "mesh"): press depth, radius, radial vectors with
/// their d_i and stops, SGOs with their faces, and the walked paths (one polyline per SGO).
nlohmann::json patchJson(const sim::Patch& patch, const sim::PatchSettings& settings);

/// Why a patch has the SGOs it has, in a sentence: no press (radius 0), radial vectors dropped at
/// an edge or vertex hit (paper Fig. 3b), and how many walks stopped early and where (a sharp
/// edge past tau_a, outside the friction cone, a boundary, ...). Empty when every radial vector
/// walked its full d_i.
std::string patchExplanation(const sim::Patch& patch, const sim::PatchSettings& settings);

/// The solver's forces at a contact's points (world frame, N), as fields of the contact's
/// object: "force_n" (the contact's force on the body, what the points' loads add up to),
/// "normal_force_n" and "tangential_force_n" (its normal and tangential magnitudes),
/// "rolling_moment_nm" (the patch's rolling rows' moment on the body), "torsion_moment_nm" (the
/// moment about the normal its points do not carry: a soft finger's torsion), "sliding",
/// "point_load" (the true contact point's) and "sgo_loads" (one per SGO and filled point, in
/// the order of "sgos"), each {"normal_n", "tangential_n": [x, y, z], "slipping"}.
void addLoadsJson(const sim::ContactSnapshot& contact, nlohmann::json& out);

/// Every finger of a snapshot in the world frame ("frame": "world"): device, proxy, coupling
/// force and each contact with its separation, press depth, radius, SGOs, walked paths and
/// the loads on its points (addLoadsJson).
nlohmann::json contactsJson(const sim::Snapshot& snapshot, const sim::SceneDesc& scene);

}  // namespace gf::app

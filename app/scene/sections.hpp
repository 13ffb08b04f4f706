// The scene reader's parts (internal to app/scene): one reader per section of a scene file, the
// field vocabularies the readers and the schema share, and the --set overrides.
#pragma once

#include <toml++/toml.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/scene/session_desc.hpp"
#include "app/scene/toml_reader.hpp"
#include "sim/mesh/mesh_import.hpp"

namespace gf::app {

/// `p` relative to `base_dir` (the scene file's folder) unless it is absolute.
std::string resolvePath(const std::string& base_dir, const std::string& p);

/// A device's `interpolation` names, in sim::Interpolation order.
inline constexpr const char* kInterpolations[] = {"linear", "smooth"};
/// A mesh body's `up_axis` names (the axis turned onto +y).
inline constexpr const char* kUpAxes[] = {"y", "z", "-z", "x", "-x", "-y"};
/// The fields of a UDP device besides `udp` itself.
inline constexpr const char* kUdpFields[] = {"channel",     "workspace_scale", "workspace_offset",  "start",
                                             "force_scale", "stale_after",     "force_ramp", "velocity_smoothing"};
/// A body's `density` may lie in this range (kg/m^3: from aerogel to osmium, twice over).
inline constexpr double kMinDensity = 1.0, kMaxDensity = 50000.0;

/// Every effect name a scene may list: the physics' (sim::effectSwitches()), then the view's.
std::vector<std::string_view> effectNames();

/// `effects`: every effect listed is on, every other one off.
void readEffects(Reader& r, sim::EffectSet& e, ViewSettings& view);
/// [render]: frame size, anti-aliasing, body pattern, proxy look and scripted overlay input (after
/// the fingers are read).
void readView(Reader& parent, SessionDesc& s);
/// [targets.NAME]: a ghost of a body at a pose, a zone, or both (after the bodies are read).
void readTargets(Reader& parent, SessionDesc& s);
/// [cameras.NAME].
view::Camera readCamera(const std::string& name, const toml::table& t, const Reader& parent);
/// [record]: what a run writes besides summary.json.
void readRecord(Reader& parent, SessionDesc& s);
/// [expect]: invariants of the run (app/scene/expect_desc.hpp).
void readExpect(Reader& parent, SessionDesc& s);

/// [bodies.NAME]: shape, mesh (loaded once per path and scale into `meshes`), mass, settings.
sim::BodyDesc readBody(const std::string& name, const toml::table& t, const Reader& parent,
                       const std::string& base_dir, sim::MeshCache& meshes);
/// Rejects a dynamic body lighter than 1/100 of the heaviest proxy, naming its mass or density.
void checkMassRatios(Reader& r, const sim::SceneDesc& scene);

/// [fingers.NAME]: settings and device; `udp` is set when a live UDP device drives it, `web`
/// when the browser view's pointer does.
sim::FingerDesc readFinger(const std::string& name, const toml::table& t, const Reader& parent,
                           const std::string& base_dir, double haptic_rate_hz, std::optional<UdpDeviceDesc>& udp,
                           std::optional<WebDeviceDesc>& web);

/// `[[loads]]`: known external loads, named `loads.INDEX` in errors and --set.
void readLoads(Reader& parent, sim::SceneDesc& scene);
/// `[[changes]]`: scripted changes of a finger's live settings, in time order.
void readChanges(Reader& parent, sim::SceneDesc& scene);

/// Applies one "--set a.b.c=VALUE" to the parsed file before it is read. Throws InputError.
void applyOverride(toml::table& root, const std::string& text);

}  // namespace gf::app

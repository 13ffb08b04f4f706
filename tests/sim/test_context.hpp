// The fixture of sim-level tests: a World built from a bundled scene file (the one table of
// scenes, assets/scenes/), stepped offline at the scene's haptic rate with its devices, as a
// session would. Links gf_sim and gf_scene (the scene reader) only.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "sim/loop/haptic_loop.hpp"
#include "sim/world/world.hpp"

namespace gf::test_support {

/// Keeps every finger's n_sgo as the scene file gives it.
inline constexpr int kSceneSgo = -1;

/// Index of the body or finger called `name` in `items` (-1 when there is none).
template <class Items>
int indexOf(const Items& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

class TestContext {
 public:
  /// Loads bundled scene `name` with `overrides` (--set syntax) and, unless n_sgo is
  /// kSceneSgo, every finger at `n_sgo` (0: god-objects); builds its World.
  explicit TestContext(const std::string& name, int n_sgo = kSceneSgo,
                       const std::vector<std::string>& overrides = {})
      : scene_(load(name, n_sgo, overrides)), world_(scene_), devices_(sim::deviceTracks(scene_)) {}

  sim::World& world() { return world_; }
  const sim::SceneDesc& scene() const { return scene_; }

  /// Steps `seconds` of simulated time on from the world's time; `observe(world)` after each
  /// step. Deterministic (the offline clock).
  sim::LoopStats simulate(double seconds, const std::function<void(const sim::World&)>& observe = {}) {
    return sim::runHapticLoop(world_, devices_, {scene_.world.haptic_rate_hz, seconds}, observe);
  }

  /// Index of the body or finger called `name` (-1 when there is none).
  int body(const std::string& name) const { return indexOf(scene_.bodies, name); }
  int finger(const std::string& name) const { return indexOf(scene_.fingers, name); }

  /// The scene `name` with overrides, every finger at n_sgo unless kSceneSgo (checked by the
  /// World when it is built).
  static sim::SceneDesc load(const std::string& name, int n_sgo, const std::vector<std::string>& overrides) {
    sim::SceneDesc scene = app::loadSceneFile(app::resolveScenePath(name), overrides).scene;
    if (n_sgo != kSceneSgo) {
      for (sim::FingerDesc& f : scene.fingers) f.patch.n_sgo = n_sgo;
    }
    return scene;
  }

 private:
  sim::SceneDesc scene_;
  sim::World world_;
  std::vector<sim::DeviceTrack> devices_;
};

}  // namespace gf::test_support

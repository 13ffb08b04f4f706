// Helpers for scenario tests: load a bundled scene with overrides and run it offline.
#pragma once

#include <string>
#include <vector>

#include "app/scene_file.hpp"
#include "sim/haptic_loop.hpp"
#include "sim/world.hpp"

namespace gf::app::testing {

inline SessionDesc bundled(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/" + name + ".toml", overrides);
}

/// Sets n_sgo of every finger (0: god-object).
inline std::vector<std::string> allFingers(const SessionDesc& s, int n_sgo) {
  std::vector<std::string> out;
  for (const sim::FingerDesc& f : s.scene.fingers) {
    out.push_back("fingers." + f.name + ".n_sgo=" + std::to_string(n_sgo));
  }
  return out;
}

/// Loads `name` with every finger at n_sgo and runs it offline for `duration` (0: the scene's),
/// calling `observe(world)` after each step. Returns the world's body index of `body`.
template <class Observer>
sim::LoopStats runScene(const std::string& name, int n_sgo, double duration, Observer&& observe) {
  SessionDesc s = bundled(name);
  s = bundled(name, allFingers(s, n_sgo));
  if (duration > 0.0) s.scene.duration = duration;
  sim::World world(s.scene);
  std::vector<sim::DeviceTrack> devices;
  for (const sim::FingerDesc& f : s.scene.fingers) devices.push_back(f.device);
  return sim::runHapticLoop(world, devices, {s.scene.world.haptic_rate_hz, s.scene.duration},
                            [&](const sim::World& w) { observe(w); });
}

inline int bodyIndex(const sim::World& w, const std::string& name) {
  for (std::size_t i = 0; i < w.desc().bodies.size(); ++i) {
    if (w.desc().bodies[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace gf::app::testing

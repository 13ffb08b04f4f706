// Scene-file text for the scene reader's tests (scene_file_test.cpp, scene_file_loads_test.cpp,
// scene_file_render_test.cpp): a minimal scene, the error a text gives, and the minimal scene
// with one piece replaced.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "app/scene/input_error.hpp"
#include "app/scene/scene_file.hpp"

namespace gf::app {

inline const std::string kMinimal = R"(name = "mini"
duration = 0.2
effects = ["gravity", "friction", "god_finger"]
[bodies.ground]
shape = "plane"
[bodies.ball]
shape = "sphere"
radius = 0.03
mass = 0.1
position = [0, 0.03, 0]
[fingers.left]
n_sgo = 8
[fingers.left.device]
keyframes = [ { t = 0.0, p = [0, 0.1, 0] }, { t = 0.2, p = [0, 0.06, 0] } ]
)";

// The error parseSceneText gives for `text` (fails the test when there is none).
inline InputError errorOf(const std::string& text, std::vector<std::string> overrides = {}) {
  try {
    parseSceneText(text, "scene.toml", "", overrides);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", 0, 0, "", "");
}

inline std::string replaced(const std::string& from, const std::string& to) {
  std::string s = kMinimal;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

}  // namespace gf::app

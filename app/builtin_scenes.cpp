#include "app/builtin_scenes.hpp"

#include <stdexcept>

namespace gf::app {
namespace {

using sim::BodyDesc;
using sim::FingerDesc;
using sim::SceneDesc;
using sim::ShapeKind;
using sim::Vec3;

BodyDesc ground() {
  BodyDesc g;
  g.name = "ground";
  g.shape = ShapeKind::kPlane;
  g.mass = 0.0;
  g.friction = 0.8;
  g.colour = Vec3(0.55, 0.57, 0.6);
  return g;
}

FingerDesc finger(const std::string& name, const SceneOptions& o) {
  FingerDesc f;
  f.name = name;
  f.patch.n_sgo = o.n_sgo;
  return f;
}

void applyDuration(SceneDesc& s, const SceneOptions& o) {
  if (o.duration > 0.0) s.duration = o.duration;
}

}  // namespace

SceneDesc pinchScene(const SceneOptions& o) {
  SceneDesc s;
  s.name = "pinch";
  s.duration = 6.0;
  s.bodies.push_back(ground());
  BodyDesc cyl;
  cyl.name = "cylinder";
  cyl.shape = ShapeKind::kCylinder;
  cyl.radius = 0.03;
  cyl.half_height = 0.05;
  cyl.mass = 0.15;
  cyl.position = Vec3(0, 0.05, 0);
  cyl.colour = Vec3(0.85, 0.45, 0.2);
  s.bodies.push_back(cyl);
  // Devices: close in along x to 5 mm inside the proxy's resting place (about 4 N of squeeze),
  // 1 cm under the centre of mass and 3 mm off the centre line in z (no hand pinches exactly
  // through the axis; this is what makes the god-object swing), then lift 5 cm in 2 s and hold.
  const double pinch_y = 0.04, pinch_z = 0.003, outside = 0.07, inside = 0.03 + 0.008 - 0.005;
  const double lift = 0.05;
  for (int side : {-1, 1}) {
    FingerDesc f = finger(side < 0 ? "left" : "right", o);
    f.device.keyframes = {{0.0, Vec3(side * outside, pinch_y, pinch_z)},
                          {0.5, Vec3(side * inside, pinch_y, pinch_z)},
                          {1.0, Vec3(side * inside, pinch_y, pinch_z)},
                          {3.0, Vec3(side * inside, pinch_y + lift, pinch_z)}};
    s.fingers.push_back(f);
  }
  applyDuration(s, o);
  return s;
}

SceneDesc pressBoxScene(const SceneOptions& o) {
  SceneDesc s;
  s.name = "press-box";
  s.duration = 1.5;
  BodyDesc table = ground();
  table.friction = 0.02;
  s.bodies.push_back(table);
  BodyDesc box;
  box.name = "box";
  box.shape = ShapeKind::kBox;
  box.half_extents = Vec3(0.05, 0.02, 0.05);
  box.mass = 0.2;
  box.friction = 1.0;
  box.position = Vec3(0, 0.02, 0);
  box.colour = Vec3(0.3, 0.5, 0.8);
  s.bodies.push_back(box);
  // The device comes down onto the top face and presses 6 mm in (about 5 N).
  FingerDesc f = finger("index", o);
  f.device.keyframes = {{0.0, Vec3(0.0, 0.06, 0.0)}, {0.5, Vec3(0.0, 0.04 + 0.008 - 0.006, 0.0)}};
  s.fingers.push_back(f);
  applyDuration(s, o);
  return s;
}

std::span<const BuiltinScene> builtinScenes() {
  static constexpr BuiltinScene kScenes[] = {
      {"pinch", "two fingers pick a cylinder under its centre of mass, lift and hold (Fig. 8)", pinchScene},
      {"press-box", "one finger presses a box on a slippery table from above", pressBoxScene},
  };
  return kScenes;
}

SceneDesc makeBuiltinScene(const std::string& name, const SceneOptions& options) {
  std::string known;
  for (const BuiltinScene& b : builtinScenes()) {
    if (name == b.name) return b.make(options);
    known += known.empty() ? b.name : std::string(", ") + b.name;
  }
  throw std::invalid_argument("unknown scene '" + name + "' (built-in scenes: " + known + ")");
}

}  // namespace gf::app

// A two-finger pinch run by an application's own loop: the scene is built in code, each step
// takes the device positions from a callback (here a scripted hand; a device SDK in practice),
// and the program reads back what the devices should render, the contacts and their patches.
// Halfway it switches both fingers to god-objects between two steps, and the cylinder, no longer
// held against the torque of its weight, starts to swing about the pinch axis.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <vector>

#include "sim/scene/snapshot.hpp"
#include "sim/world/world.hpp"

using gf::sim::Vec3;

namespace {

// The hand: closes in to 5 mm inside the cylinder's surface in 0.5 s, lifts 5 cm from 1 s to 3 s.
Vec3 devicePosition(double side, double t) {
  const auto smooth = [](double u) { u = std::clamp(u, 0.0, 1.0); return u * u * (3.0 - 2.0 * u); };
  const double x = side * (0.07 - 0.037 * smooth(t / 0.5));
  return Vec3(x, 0.04 + 0.05 * smooth((t - 1.0) / 2.0), 0.003);
}

// A cylinder on the ground, picked by two fingers 1 cm under its centre of mass.
gf::sim::SceneDesc pinchScene() {
  gf::sim::SceneDesc scene;
  scene.name = "embedded pinch";
  scene.world.solver_iterations = 20;
  gf::sim::BodyDesc ground;
  ground.name = "ground";
  ground.shape = gf::sim::ShapeKind::kPlane;
  ground.mass = 0.0;
  gf::sim::BodyDesc cylinder;
  cylinder.name = "cylinder";
  cylinder.shape = gf::sim::ShapeKind::kCylinder;
  cylinder.radius = 0.03;
  cylinder.half_height = 0.05;
  cylinder.mass = 0.15;
  cylinder.position = Vec3(0.0, 0.05, 0.0);
  scene.bodies = {ground, cylinder};
  for (const char* name : {"left", "right"}) {
    gf::sim::FingerDesc finger;
    finger.name = name;
    finger.patch.n_sgo = 8;  // a god-finger: eight sub-god-objects around each contact
    finger.device.keyframes = {{0.0, devicePosition(name[0] == 'l' ? -1.0 : 1.0, 0.0)}};  // the proxy starts here
    scene.fingers.push_back(finger);
  }
  return scene;
}

}  // namespace


int main() {
  gf::sim::World world(pinchScene());  // throws gf::sim::DescriptionError naming a bad field
  const double dt = 0.001;             // any rate: the caller's loop decides
  std::vector<gf::sim::DeviceSample> devices(2);
  gf::sim::Snapshot snapshot;
  for (int k = 0; k <= 5000; ++k) {
    const double t = k * dt;
    // The caller's device loop: positions (and velocities, for the coupling's damping).
    for (int i = 0; i < 2; ++i) {
      const double side = i == 0 ? -1.0 : 1.0;
      devices[i].position = devicePosition(side, t);
      devices[i].velocity = (devicePosition(side, t + dt) - devicePosition(side, t)) / dt;
    }
    world.step(dt, devices);
    if (k == 3500) {  // between two steps: both fingers become god-objects
      for (int i = 0; i < 2; ++i) {
        gf::sim::PatchSettings god_object = world.desc().fingers[i].patch;
        god_object.n_sgo = 0;
        world.setPatchSettings(i, god_object);
      }
      std::printf("t = %.2f s: both fingers switched to god-objects\n", world.time());
    }
    if (k % 500 != 0) continue;
    world.snapshot(snapshot);  // plain data: poses, proxies, contacts with their patches
    const gf::sim::Pose cylinder = world.bodyPose(1);
    const double tilt = 2.0 * std::acos(std::min(1.0, std::abs(cylinder.orientation.w()))) * 180.0 / std::numbers::pi;
    const gf::sim::FingerSnapshot& left = snapshot.fingers[0];
    const double radius = left.contacts.empty() ? 0.0 : left.contacts[0].radius;
    std::printf("t = %.2f s  feedback left %6.3f N right %6.3f N  left patch r = %.2f mm, %d SGOs  "
                "cylinder height %.3f m, tilt %5.2f deg\n",
                world.time(), world.feedbackForce(0).norm(), world.feedbackForce(1).norm(), radius * 1e3,
                world.sgoCount(0), cylinder.position.y(), tilt);
  }
  return 0;
}

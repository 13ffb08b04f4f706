// Scripted haptic devices: the device position as a function of simulated time.
#pragma once

#include <vector>

#include "sim/mesh/mesh.hpp"

namespace gf::sim {

/// How a device moves between two keyframes.
enum class Interpolation {
  kLinear,  ///< constant velocity between keyframes
  kSmooth,  ///< smoothstep: zero velocity at every keyframe
};

/// The device at one time.
struct DeviceSample {
  Vec3 position = Vec3::Zero();  ///< m
  Vec3 velocity = Vec3::Zero();  ///< m/s
  /// s: how long the device took to move to `position` from the position it gave before (a
  /// sender's time between its last two packets); 0 for one step, a source sampled every step.
  double interval = 0.0;
  /// The device's orientation (a 6-DOF device): rotates the device frame into the scene frame.
  /// Identity for a 3-DOF device, which has none; a god-finger with a pad model reads its pad
  /// axis through it (PatchSettings::pad_model).
  Quat orientation = Quat::Identity();
  /// The first sample of a live device's stream after a dropout or a takeover: the hand is now
  /// wherever it went meanwhile. The World does not jump there: it keeps the device where it
  /// was and washes the difference out no faster than the port's energy allows (World::step).
  bool resumed = false;
};

/// A device path through keyframes (time in s, position in m), held at both ends.
struct DeviceTrack {
  struct Keyframe {
    double time = 0.0;
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();  ///< unit; identity unless the track gives one
  };
  std::vector<Keyframe> keyframes;  ///< strictly increasing times
  Interpolation interpolation = Interpolation::kSmooth;

  /// Position, velocity and orientation at time t (s); the orientation is slerped with the
  /// position's interpolation parameter (shortest arc). Before the first keyframe, at the first; after the
  /// last, at the last; with no keyframe, at the origin. Any thread; does not allocate.
  DeviceSample sample(double t) const;
};

/// What a finger did in a step, handed back to its device.
struct DeviceFeedback {
  Vec3 force = Vec3::Zero();  ///< N: the force the device is to render (World::feedbackForce)
  double radius = 0.0;        ///< m: mean Eq. 1 radius of the finger's patches; 0 without one
  int sgo_count = 0;          ///< SGOs the finger fed to the solver
  bool touching = false;      ///< the proxy touched a body
};

/// A device the haptic loop reads at the start of each step and hands the step's feedback to
/// afterwards: a live transport (app/ bridges one to a UDP socket). Both calls come from the
/// haptic thread and must neither block nor allocate.
class DeviceSource {
 public:
  virtual ~DeviceSource() = default;
  /// The device for the step starting at simulated time t (s).
  virtual DeviceSample sample(double t) = 0;
  /// The finger's state after that step, at simulated time t (s), the step's end. Returns the
  /// force the device was told to render (scene frame, N: what it renders until the next
  /// reply), which the port's passivity observer and trace.csv take (World::setToldForce).
  virtual Vec3 feedback(double t, const DeviceFeedback& feedback) = 0;
};

}  // namespace gf::sim

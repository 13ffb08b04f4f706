// The god-object proxy and its spring-damper virtual coupling to the device.
#pragma once

#include "sim/mesh/mesh.hpp"

namespace gf::sim {

/// m/s: faster than a hand moves a haptic device (arm movements peak at 2 to 5 m/s).
inline constexpr double kDefaultMaxDeviceSpeed = 10.0;

/// Spring-damper between device and proxy (Colgate et al. 1995 virtual coupling).
struct CouplingSettings {
  double stiffness = 800.0;  ///< N/m
  double damping = 10.0;     ///< N s/m, on the device-proxy relative velocity (zeta ~ 0.56)
  double max_force = 40.0;   ///< N: the coupling force is clamped to this magnitude
  /// N/s: how fast the force sent to the device may change (World::feedbackForce), whatever the
  /// device or the contact does; 0: max_force / kDefaultForceRamp
  double max_force_rate = 0.0;
  /// m/s: a device sample further from the last than this times the step is a jump (a new
  /// sender, a tracking glitch, a scripted move), not a hand's motion: the passivity observer
  /// counts its work apart (World::portObserver)
  double max_device_speed = kDefaultMaxDeviceSpeed;
};

/// The passivity observer of a device port (Hannaford and Ryu 2002): the work the hand has done
/// on the device against the force sent (J), -sent . dx summed over the steps where the device
/// moved as a hand can. A move faster than max_device_speed is a jump (a tracking glitch, a
/// sender taking over, a scripted move): no hand did that work, and the force sent, which may
/// not jump, would mis-price it (a jump away from a press at the clamp "returns" F D in one
/// step), so its work is summed apart. What a jump into a body stores in the coupling is
/// energy the hand did not put in: when the hand then takes it back moving out, `energy` shows
/// it, by at most that stored energy.
struct PortObserver {
  double energy = 0.0;       ///< J; a passive simulation keeps it at or above zero
  double min_energy = 0.0;   ///< J: the lowest `energy` was
  long jumps = 0;            ///< steps the device jumped
  double jump_energy = 0.0;  ///< J: the work of those steps, -sent . dx

  void observe(double work, bool jump) {
    if (jump) {
      ++jumps;
      jump_energy += work;
      return;
    }
    energy += work;
    min_energy = energy < min_energy ? energy : min_energy;
  }
};

/// s: the default max_force_rate takes this long from zero to max_force.
inline constexpr double kDefaultForceRamp = 0.1;

/// The force sent to the device may change by at most this much a second (N/s).
inline double maxForceRate(const CouplingSettings& s) {
  return s.max_force_rate > 0.0 ? s.max_force_rate : s.max_force / kDefaultForceRamp;
}

/// The proxy: a small sphere, rotation locked and gravity compensated.
struct ProxySettings {
  double radius = 0.008;             ///< m
  /// kg. Light proxies converge slowly against heavy objects in Bullet's iterative solver
  /// (the god-finger then creeps under a sustained torque); 0.1 kg holds the pinch within 1 deg.
  double mass = 0.1;
  double contact_stiffness = 20000;  ///< N/m: total over the true contact and its SGOs
  double contact_damping = 1000.0;   ///< N s/m: total over the true contact and its SGOs
};

/// Force (N) the coupling applies to the proxy; the device feels its opposite. Clamped to
/// max_force; zero for non-finite input. Any thread; does not allocate.
Vec3 couplingForce(const CouplingSettings& s, const Vec3& device_pos, const Vec3& device_vel,
                   const Vec3& proxy_pos, const Vec3& proxy_vel);

}  // namespace gf::sim

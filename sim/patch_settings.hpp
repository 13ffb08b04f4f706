// The god-finger settings of one finger: plain data shared by the patch function, the scene
// description and the overlay. Their legal ranges and validators are in sim/settings.hpp.
#pragma once

namespace gf::sim {

/// Fewest and most SGOs a god-finger patch has (the paper asks for at least 3).
inline constexpr int kMinSgo = 3;
inline constexpr int kMaxSgo = 64;

/// God-finger settings. Defaults suit a fingertip on objects of a few centimetres. Their legal
/// ranges are in sim/settings.hpp (fingerSettings()).
struct PatchSettings {
  int n_sgo = 8;                    ///< number of radial vectors / SGOs (kMinSgo..kMaxSgo)
  double r_max = 0.010;             ///< r_max of Eq. 1: largest contact radius (m)
  double d0 = 0.004;                ///< D'_0 of Eq. 1: press depth scale (m)
  double alpha = 2.0;               ///< alpha of Eq. 2: stretch base (>= 1; 1 = no stretch)
  double stretch_length = 0.004;    ///< length making Eq. 2's exponent dimensionless (m)
  double max_stretch_exponent = 3;  ///< |exponent| of Eq. 2 is clamped to this (dimensionless)
  double tau_a = 1.0471975511965976;  ///< tau_a: angular threshold (rad; default 60 deg)
  double friction = 1.0;            ///< theta: friction coefficient of the finger pad
  bool tangential_stretch = true;   ///< effect switch: Eq. 2 stretch (off: d_i = r)
  bool angular_threshold = true;    ///< effect switch: stop at faces beyond tau_a
  bool friction_cone = true;        ///< effect switch: stop at faces beyond atan(theta)
  int max_face_crossings = 256;     ///< bound on edges one walk may cross
  double feature_tolerance = 1e-7;  ///< distance (m) within which a hit is an edge/vertex hit
};

}  // namespace gf::sim

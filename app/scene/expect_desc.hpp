// What a scene file's [expect] table asks of a run: limits the session checks after every step
// and at its end (app/session/expectations.hpp). Read-only data, filled by the scene reader.
#pragma once

#include <map>
#include <optional>
#include <string>

namespace gf::app {

/// [expect.bodies.NAME]: limits on one dynamic body.
struct BodyExpect {
  std::optional<double> max_speed;          ///< m/s
  std::optional<double> max_angular_speed;  ///< rad/s
  std::optional<double> stays_above;        ///< m: the body's centre y never below this
  std::optional<double> ends_above;         ///< m: the body's centre y at the end at least this
  std::optional<double> max_rotation_deg;   ///< deg: rotation from its pose at `after`
  /// m: the centre's largest distance from where it was at `after` (a held body stays put)
  std::optional<double> max_drift;
  /// deg: the largest tilt from its orientation at `after`: how far its turn since then moves the
  /// vertical (a spin about the vertical is no tilt)
  std::optional<double> max_tilt_deg;
  double after = 0.0;                       ///< s: when max_rotation_deg, max_drift and max_tilt_deg start counting
  /// s: the body rests from then on: no later step with a speed above rest_speed or a tilt rate
  /// (angular speed about a horizontal axis) above rest_tilt_rate
  std::optional<double> rests_after;
  double rest_speed = 1e-3;      ///< m/s
  double rest_tilt_rate = 0.05;  ///< rad/s
  /// A sphere's roll ratio over roll_window: the angle it turned times its radius over the
  /// distance it went along the ground (1 rolling, 0 sliding; app/measures/roll_ratio.hpp, as the
  /// studies' roll_ratio measure takes it). A ball that went less than 1 % of its radius has none
  /// and fails.
  std::optional<double> max_roll_ratio;
  double roll_from = 0.0, roll_to = 1e300;  ///< s: roll_window
};

/// [expect.fingers.NAME]: limits on one finger.
struct FingerExpect {
  std::optional<int> min_sgo;       ///< fewest SGOs (all its contacts) at any step of the window
  double from = 0.0, to = 1e300;    ///< s: the window of min_sgo
  std::optional<double> max_force;  ///< N: largest coupling force
  /// N: the coupling force's largest change over the window from its value at the window's
  /// start (a still finger feels a still force); needs the window
  std::optional<double> max_force_change;
  std::optional<double> max_penetration;  ///< m: deepest the proxy goes into a body (else [expect]'s)
};

/// [expect]: every field optional except `finite` (default true).
struct ExpectDesc {
  bool finite = true;                   ///< no NaN or inf in any state, no step rolled back
  std::optional<double> max_speed;      ///< m/s: any dynamic body
  std::optional<double> max_angular_speed;  ///< rad/s: any dynamic body
  /// J: the largest rise of mechanical energy over any 1 s window in which no device moved and
  /// no load acted
  std::optional<double> energy_growth;
  /// m: deepest any proxy goes into a body (the contact's separation)
  std::optional<double> max_penetration;
  /// No proxy ends on the far side of a body it was pressing: its centre never behind the plane
  /// of its last contact (when the contact ends, when its normal turns over, while it presses)
  bool no_tunnelling = false;
  /// J: the lowest each finger's device port energy (World::portEnergy) may go: a passive
  /// simulation returns no more energy than it was given
  double min_port_energy = -1e-3;
  std::map<std::string, BodyExpect> bodies;
  std::map<std::string, FingerExpect> fingers;
  /// True when nothing is checked.
  bool empty() const {
    return !finite && !max_speed && !max_angular_speed && !energy_growth && !max_penetration && !no_tunnelling &&
           bodies.empty() && fingers.empty();
  }
};

}  // namespace gf::app

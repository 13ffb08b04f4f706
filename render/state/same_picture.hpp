// Whether two snapshots draw the same scene picture (or the same bodies and shadows): a frame whose bodies, fingers, contacts and
// soft shapes have not moved since the last drawn one reuses that picture (the labels, time
// stamp and overlay are drawn again over it). Render thread and tests.
#pragma once

#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// How far a drawn length (m) or a unit vector's or quaternion's component may move and still
/// draw the same picture: a pixel of a 1280x720 frame of a bundled scene spans 0.1-0.4 mm. A
/// resting world's solver jitter moves them by 1e-20 to 4e-12 between frames (the Fig. 8 hold).
inline constexpr double kSamePictureTolerance = 1e-9;
/// How far a drawn force or moment may move, as a share of its size (plus kSameLoadFloor): a
/// tenth of a load-colour level on the narrowest load scale (render/state/contact_load.hpp: at
/// least 10 % of the contact's mean point load over 255 levels, 3.9e-4 of the mean), 3 um on the
/// longest force arrow (8 cm). In the Fig. 8 hold the solver keeps shifting the normal load
/// between the SGOs (about 3.3e-6 of an SGO's load a frame over the first 20 s, while the body and
/// the fingers stay within 1e-12 m): its picture is drawn again about every 12 frames.
inline constexpr double kSameLoadShare = 4e-5, kSameLoadFloor = 1e-12;

/// True when `a` and `b` draw the same scene picture: every length, direction and orientation of
/// every body, finger, contact, pad and soft body within kSamePictureTolerance, every force and
/// moment within kSameLoadShare of itself (a contact's torsion, of its force times its radius
/// when that is larger: the arc shows it against mu F_n r), and every count, flag, feature and
/// setting equal. Each point's friction is compared with `load_arrows` (drawn as arrows, [render]
/// load_arrows); without them only through the contact's torsion about its normal
/// (contactTorsion, the torsion arc's), as the picture shows it: in a hold the aggregate solver
/// shifts friction between the points (0.2 % of an SGO's a frame in the Fig. 8 hold) while their
/// sum and moment stay. The time, the step, the NaN roll-backs, the bodies' velocities and the haptic
/// timings are not compared: the scene does not draw them (the labels over it draw the time). Any thread; allocates nothing.
bool drawsTheSame(const sim::Snapshot& a, const sim::Snapshot& b, bool load_arrows);

/// True when `a` and `b` place every body, soft body, proxy, device and pad alike (within
/// kSamePictureTolerance), whatever their contacts and forces: what a shadow map and the bodies'
/// layer of a picture show (SceneRenderer). Any thread; allocates nothing.
bool samePlaces(const sim::Snapshot& a, const sim::Snapshot& b);

}  // namespace gf::render

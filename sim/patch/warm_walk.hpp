// Warm-started walks (issue 33): consecutive patches of one finger on one body differ by
// micrometres, so each radial vector's Algorithm 1 walk is not redone from the contact point but
// carried from the last step's path: the same faces, unfolded into the start face's plane, with
// the path's edge crossings and its end moved by the difference. A walk is redone from the
// contact when the contact's face or feature or n_sgo changed, or when the carried path no longer
// holds: a crossing left its edge, the end left its face, a face on the way left the thresholds,
// or the walk had stopped short of d_i. A full check of a carried path also leaves its slack:
// while the line of the walk (start, direction, length) and the contact normal move less than
// that from the line it checked, every check holds without being made, and the crossings are
// only placed on their edges.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "sim/mesh/mesh.hpp"

namespace gf::sim {

/// Crossings of one radial vector's path a cache keeps; longer paths are walked from the contact.
inline constexpr int kWarmCrossingsPerSgo = 16;

/// One edge crossing of a carried path.
struct WalkCrossing {
  Vec3 point = Vec3::Zero();           ///< where the path crosses the edge (body frame, m)
  Vec3 edge = Vec3::Zero();            ///< the edge's unit direction (body frame)
  double to_first = 0.0;               ///< from `point` along `edge` to the edge's first end (m, <= 0)
  double to_second = 0.0;              ///< and to its second end (m, >= 0)
  double x = 0.0, y = 0.0;             ///< `point` unfolded into the start face's plane (m)
  double ux = 0.0, uy = 0.0;           ///< `edge` unfolded into the start face's plane
  Vec3 entered_normal = Vec3::Zero();  ///< oriented unit normal of the face entered
};

/// One radial vector's carried path.
struct WalkPath {
  bool cached = false;   ///< the last walk ended at d_i inside a face, with few enough crossings
  int start_face = -1;   ///< its start face and winding sign there
  double side = 1.0;
  int end_face = -1;     ///< the face its end lies on
  int crossings = 0;     ///< edges crossed (the first `crossings` of its slot)
  Vec3 end = Vec3::Zero();  ///< its end, the SGO (body frame, m)
  double end_x = 0.0, end_y = 0.0;  ///< the end unfolded into the start face's plane (m)
  /// Images on the end face of the start plane's axes: a start-plane offset (x, y) moves the
  /// end by x * axis_x + y * axis_y.
  Vec3 axis_x = Vec3::Zero(), axis_y = Vec3::Zero();
  /// The line of the last full check (its reference) and how far the line may move from it with
  /// every check still holding; `slack` false until a full check leaves one.
  bool slack = false;
  double ref_hx = 0.0, ref_hy = 0.0;  ///< its start in the start plane (m)
  double ref_dx = 0.0, ref_dy = 0.0;  ///< its unit direction there
  double ref_d = 0.0;                 ///< its length (m)
  Vec3 ref_normal = Vec3::Zero();     ///< the contact normal it was checked against
  double ref_cos_limit = 0.0, ref_cos_facing = 0.0;  ///< and the thresholds (WalkLimits)
  bool ref_has_limit = false;
  double turn_slack = 0.0;    ///< largest turn of the direction (|difference of unit vectors|)
  double move_slack = 0.0;    ///< largest |start moved| + ref_d * turn (m): crossings, start side
  double end_slack = 0.0;     ///< largest move + |length changed| (m): the end in its face
  double normal_slack = 0.0;  ///< largest |normal turned|: the faces on the way within thresholds
  /// The last carry was within the slack and left its crossings unplaced (WalkStart::place);
  /// they lie where this line (start, unit direction in the start plane, m) meets their edges.
  bool pending = false;
  double line_hx = 0.0, line_hy = 0.0, line_dx = 0.0, line_dy = 0.0;
};

/// The start face's plane: origin at its corner 0, x along its edge 0, y = oriented normal x x.
struct StartPlane {
  Vec3 origin = Vec3::Zero();
  Vec3 x_axis = Vec3::Zero(), y_axis = Vec3::Zero();
};

/// What one finger's contact with one body carries between steps for its walks. Storage is
/// sized by reserve() for the most radial vectors the finger will use; after that nothing
/// allocates (a patch with more radial vectors sizes it again, once).
struct WalkCache {
  bool valid = false;           ///< holds the paths of a patch computed with the key below
  const Mesh* mesh = nullptr;   ///< key: the mesh walked,
  int n_sgo = 0;                ///< the radial vectors,
  int hit_face = -1;            ///< and the contact's face and feature
  Feature feature = Feature::kFace;
  int feature_index = -1;
  std::vector<WalkPath> paths;           ///< by radial index
  std::vector<WalkCrossing> crossings;   ///< radial i's in [i, i + 1) * kWarmCrossingsPerSgo
  /// The face and winding of this patch's start plane (carryPlane; -1: none this patch).
  int plane_face = -1;
  double plane_side = 1.0;
  double from_x = 0.0, from_y = 0.0;  ///< the walks' start (the contact) in that plane (m)
  /// This patch's contact normal's turn from the reference normal a path was last checked
  /// against, |normal - turn_ref|: worked out again only when the next path's reference differs
  /// (most paths share one). keyWalkCache resets the key to NaN each patch.
  Vec3 turn_ref = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  double turn_of_ref = 0.0;
  long warm_walks = 0;  ///< walks carried from the last step (cumulative)
  long slack_walks = 0;  ///< of which carried within their slack, unchecked (cumulative)
  long cold_walks = 0;  ///< walks done from the contact (cumulative)
  /// Sizes the storage for `radials` radial vectors (at most kMaxSgo), when it holds fewer.
  /// Allocates then.
  void reserve(int radials);
};

/// The plane of face f with winding sign `side`. Any thread; no allocation.
StartPlane startPlane(const Mesh& mesh, int f, double side);

/// The walk's angular limits (god_finger.cpp's WalkContext) a carried path must still meet.
struct WalkLimits {
  Vec3 normal = Vec3::UnitY();  ///< outward contact normal (unit)
  double cos_limit = -1.0;      ///< a face is within the thresholds while n_f . normal >= this
  bool has_limit = false;
  double cos_facing = 0.0;      ///< a face with n_f . normal <= this faces away
};

/// The start of a walk: its face, winding sign, unit direction in the start face's plane
/// (carryPlane's axes), the point and length.
struct WalkStart {
  int face = -1;
  double side = 1.0;
  double dx = 1.0, dy = 0.0;
  Vec3 from = Vec3::Zero();  ///< the same for every walk of a patch (the contact)
  double d = 0.0;
  long budget = 0;  ///< edge crossings allowed (or any bound below it the path keeps within)
  /// Within the slack, place the crossings into the path points; false: leave them pending
  /// (pendingCrossings places them when they are read).
  bool place = true;
};

/// Keys `cache` to a patch on `mesh` with n_sgo radial vectors and contact `hit` (face and
/// feature): its paths stay if `was_valid` and the key is the same, else they start uncached.
/// Sizes its storage when it holds fewer than n_sgo radial vectors (allocates then).
void keyWalkCache(const Mesh* mesh, int n_sgo, const SurfacePoint& hit, bool was_valid, WalkCache& cache);

/// Radial i's path is not carried (nor its crossings pending) until a walk records it again.
inline void uncachePath(WalkCache& cache, int i) {
  WalkPath& p = cache.paths[static_cast<std::size_t>(i)];
  p.cached = p.pending = false;
}

/// Records one walk from the contact into a cache as it goes: its crossings and end unfolded
/// into the start face's plane, so the next step can carry it. Null cache: records nothing.
class WalkRecorder {
 public:
  /// Radial i's walk from `from` on face `face` (winding sign `side`) along unit `dir`.
  WalkRecorder(WalkCache* cache, int i, const Mesh& m, int face, double side, const Vec3& from, const Vec3& dir);
  /// The walk, `walked` metres along, direction `dir` on face f (winding `side`), crossed edge
  /// k at `point` into a face of oriented normal `entered`.
  void crossing(const Mesh& m, int f, int k, double side, const Vec3& dir, const Vec3& point, double walked,
                const Vec3& entered);
  /// The walk ended at `point` inside face f after d metres: the cache may carry it.
  void end(const Mesh& m, double side, const Vec3& dir, int f, const Vec3& point, double d);

 private:
  WalkPath* path_ = nullptr;  // null: not recording
  WalkCrossing* crossings_ = nullptr;
  double hx_ = 0.0, hy_ = 0.0, dx_ = 0.0, dy_ = 0.0;  // start and direction in the start plane
};

/// The plane of face f (winding `side`) the walks of this patch start in; keeps its face, side
/// and `from` (the contact) in it (cache.from_x, from_y) in `cache`, once a patch after
/// keyWalkCache (which clears them): carryWalk carries nothing from another face or side.
StartPlane carryPlane(const Mesh& mesh, int f, double side, const Vec3& from, WalkCache& cache);

/// A face hit's ring axes (unit, on the start face) in a start plane's axes, each of unit length
/// there: radial i's direction in the plane is c_i (x1, y1) + s_i (x2, y2), what projecting and
/// normalizing it would give (to rounding on a well-shaped face, whose plane axes are
/// orthonormal), without a square root per radial.
struct PlaneAxes {
  bool ok = false;  ///< false: an axis has no length in the plane (the walks go from the contact)
  double x1 = 1.0, y1 = 0.0, x2 = 0.0, y2 = 1.0;
};
/// f1 and f2 in `plane`'s axes; not ok when either has no length there or is not finite.
PlaneAxes ringInPlane(const StartPlane& plane, const Vec3& f1, const Vec3& f2);

/// Carries radial `i`'s path of `cache` to the start `s`, whose face and side carryPlane set this
/// patch (else false): on success appends the path (from, crossings, end) to `path_points`,
/// updates the cache and returns true with the end's face in
/// `end_face`; on failure leaves `path_points` as it was (and the path to be walked from the
/// contact). Within the path's slack its crossings are placed without checks (they hold), or
/// with `s.place` false left pending (their points unset), else each is checked and the slack
/// renewed. Any thread; no allocation once `path_points` has its
/// capacity.
bool carryWalk(const Mesh& mesh, const WalkLimits& limits, const WalkStart& s, int i, WalkCache& cache,
               std::vector<Vec3>& path_points, Vec3& end, int& end_face);

/// Radial i's crossings its last carried walk left pending, placed into out[0 .. crossings)
/// (body frame, m), bitwise where carryWalk would have placed them; false (out untouched) when
/// none are pending. Any thread; no allocation.
bool pendingCrossings(const WalkCache& cache, int i, Vec3* out);

}  // namespace gf::sim

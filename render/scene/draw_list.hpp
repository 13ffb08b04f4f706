// What the contact overlay of a frame draws, as plain data: the highlighted patches with their
// walked paths, SGO dots coloured by load (slipping ones ringed), normals and force arrows, the
// proxies (a fem_pad finger's bone, under its deformed pad), the device ghosts (dashed outlines)
// and the coupling springs of one Snapshot, in drawing order. Built without GL (testable
// anywhere, no allocation per frame once its arrays have grown); SceneRenderer's GL pass draws
// it, in the manner of an abstract scene handed to a renderer.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/scene/pad_mesh.hpp"
#include "render/scene/patch_mesh.hpp"
#include "render/gl/vertex.hpp"
#include "render/view/view_desc.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// Colour of finger i (linear RGB), shared by every view and the overlay.
Eigen::Vector3f fingerColour(int finger);

/// The placement of a unit shape: translate * rotate * scale (float, for GL).
Eigen::Matrix4f modelMatrix(const sim::Vec3& position, const sim::Quat& orientation, const sim::Vec3& scale);

/// The unit shapes an item may stand for, or a range of DrawList::vertices.
enum class DrawShape : std::uint8_t {
  kSphere,     ///< unit sphere (proxies, bones)
  kDot,        ///< coarse unit sphere (contact points, SGOs: a few pixels each)
  kCylinder,   ///< unit cylinder along +y from 0 to 1 (arrow shafts)
  kCone,       ///< unit cone along +y (arrow heads)
  kTriangles,  ///< vertices [first, first + count) as triangles
  kLines,      ///< vertices [first, first + count) as line segments
};

/// How an item is drawn; consecutive items of one pass share the GL state.
enum class DrawPass : std::uint8_t {
  kPatchFill,   ///< translucent, lit like the body under it, pulled towards the eye, no depth writes
  kPatchRim,    ///< the band along a patch's edge: as kPatchFill but flat (unlit), so it reads in shade
  kPatchLines,  ///< flat colour, depth-tested: walked paths and the rim
  kMarks,       ///< lit, opaque, depth-tested: the contact point, the SGOs, slip rings
  kArrows,      ///< lit, opaque, through everything: contact normals, force arrows
  kPads,        ///< lit and shadowed like the bodies, opaque (drawn first): fem_pad fingers' skins
  kProxies,     ///< lit, translucent, front faces, no depth writes: the god-objects (a pad's bone)
  kTargets,     ///< as kProxies, pulled towards the eye (a ghost on its body's faces): targets' ghosts and zones
  kGhosts,      ///< flat, translucent triangles through everything: the devices' dashed outlines
  kSprings,     ///< flat, translucent lines through everything (drawn before the patches): the couplings
};

struct DrawItem {
  DrawPass pass = DrawPass::kMarks;
  DrawShape shape = DrawShape::kDot;
  Eigen::Vector3f colour = Eigen::Vector3f::Ones();  ///< linear RGB
  float alpha = 1.0f;
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();  ///< a unit shape's placement (identity for ranges)
  int first = 0, count = 0;                              ///< kTriangles, kLines: the vertex range
};

/// An item drawing unit shape `shape` placed by `model` in `pass`.
DrawItem shapeItem(DrawPass pass, DrawShape shape, const Eigen::Matrix4f& model, const Eigen::Vector3f& colour,
                   float alpha = 1.0f);

/// One frame's overlay. clear() keeps the arrays' storage.
struct DrawList {
  std::vector<Vertex> vertices;  ///< world frame (m)
  std::vector<DrawItem> items;   ///< in drawing order
  void clear() {
    vertices.clear();
    items.clear();
  }
};

/// Linear RGB of the targets a scene draws: a green apart from the fingers' and bodies' colours.
inline const Eigen::Vector3f kTargetColour(0.15f, 0.85f, 0.35f);

/// The camera a list is built for: arrows are kept inside its frame, outlines face it.
struct DrawView {
  Eigen::Matrix4d view_proj = Eigen::Matrix4d::Identity();  ///< world to clip space (perspective)
  sim::Vec3 eye = sim::Vec3::Zero();                       ///< the camera's position (m)
  double tan_half_fov = 1.0;                               ///< tangent of half the vertical field of view
  int height_px = 720;                                     ///< the frame's height (pixels)
};

/// What the overlay shows, and its scales.
struct DrawSettings {
  bool patch_highlight = true;        ///< patches, SGO dots, normals, force arrows
  bool fingers = true;                ///< proxies, pads, device ghosts, springs
  /// Contact normals and force arrows; off in close-ups, whose camera looks down the normal (an
  /// arrow towards the camera is a disc over the patch; their labels draw the forces in 2D).
  bool contact_arrows = true;
  /// The twist each contact resists, as an arc around its patch (load_marks.hpp); close-ups too.
  bool torsion_arcs = true;
  /// Each point's load split into its normal part and its friction, as arrows (load_marks.hpp);
  /// in close-ups the friction only. Off unless asked for (`[render] load_arrows`).
  bool load_arrows = false;
  double force_arrow_m_per_n = 0.01;  ///< arrow length per newton of coupling force (m/N)
  double max_arrow_m = 0.08;          ///< longest force arrow (m)
  double max_arrow_view_share = 0.25; ///< longest force arrow as a share of the view's height at its proxy
  std::optional<DrawView> view;       ///< the camera; none: arrows capped by max_arrow_m only
  /// The scene's targets, drawn translucent (a ghost, lit) with the zone's edges; null: none
  const std::vector<view::Target>* targets = nullptr;
  /// Proxies as spheres, or as fingertips (finger_marks.hpp; a fem_pad finger keeps its pad)
  view::ProxyLook proxy = view::ProxyLook::kSphere;
};

/// Linear RGB of a fem_pad finger's skin: warm, apart from the bodies' and fingers' colours.
inline const Eigen::Vector3f kPadColour(0.80f, 0.50f, 0.38f);

/// The radius of the sphere a finger's proxy is drawn (and casts its shadow) as, given its
/// proxy's `proxy_radius` (m): a fem_pad finger's bone (its proxy radius is its skin's).
double proxySphereRadius(const sim::FingerSnapshot& finger, double proxy_radius);

/// The force arrow of a finger (m), drawn from its proxy: the force rendered to the device (away
/// from the surface touched) at the settings' scale, capped at max_arrow_m and, with a view, at
/// max_arrow_view_share of the view's height at the proxy and where its tip would leave the
/// frame (less a margin of 4 % of the frame each side); zero without a force.
sim::Vec3 forceArrow(const sim::FingerSnapshot& finger, const DrawSettings& settings);

/// The longest an arrow from `from` along unit `direction` may be in `view` (m): `share` of the
/// view's height at `from`, and no further than its tip stays inside the frame less a margin of
/// 4 % each side; 0 when `from` is not in front of the camera. An arrow starting outside that
/// frame is limited by the share only.
double longestArrowInView(const DrawView& view, const sim::Vec3& from, const sim::Vec3& direction, double share);

/// Appends an arrow from `from` along `vector` (m) of shaft radius `radius`, drawn through
/// everything (DrawPass::kArrows): a shaft and a head of at most 5 radii, whichever is nearer
/// the camera at `eye` last (none: the head last).
void addArrowItems(DrawList& out, const sim::Vec3& from, const sim::Vec3& vector, double radius,
                   const Eigen::Vector3f& colour, const std::optional<sim::Vec3>& eye);

/// Builds draw lists of one scene. Any thread (one at a time); build() allocates only while its
/// arrays and the list's grow to the largest frame.
class DrawListBuilder {
 public:
  /// `surfaces`: each body's render surface in its description frame (null: no patch is drawn
  /// on it, e.g. a plane's).
  DrawListBuilder(const sim::SceneDesc& scene, std::vector<std::shared_ptr<const sim::Mesh>> surfaces);

  /// Replaces `out` with the overlay of `snapshot`.
  void build(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out);

 private:
  void addPatches(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out);
  void addOverlaps(const sim::Snapshot& snapshot, DrawList& out);
  void addMarks(const sim::ContactSnapshot& contact, const Eigen::Vector3f& colour, double dot, DrawList& out);
  void addPads(const sim::Snapshot& snapshot, DrawList& out);
  void addSoftBodies(const sim::Snapshot& snapshot, DrawList& out);
  void addTargets(const std::vector<view::Target>& targets, DrawList& out);
  void addProxies(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out);
  void addSprings(const sim::Snapshot& snapshot, DrawList& out);
  void addGhosts(const sim::Snapshot& snapshot, const DrawSettings& settings, DrawList& out);
  void addSpring(const sim::Vec3& a, const sim::Vec3& b, double coil_radius);

  std::vector<double> proxy_radius_, r_max_, friction_;  // per finger (m, m, pad friction)
  std::vector<Eigen::Vector3f> body_colour_;  // per body
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces_;
  PatchMeshBuilder patch_builder_;
  PadMeshBuilder pad_builder_;
  std::vector<Vertex> fill_, rim_, lines_;  // one finger's patch (or the springs), before joining the list
  std::optional<sim::Vec3> view_eye_;       // the camera of the list being built, if any
};

}  // namespace gf::render

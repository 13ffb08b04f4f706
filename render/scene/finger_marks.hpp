// What the overlay draws at a finger beyond its proxy sphere, as plain data (draw_list.hpp): the
// device's orientation (the pad's outline, a tilt marker and a twist bead) and, on request, the
// proxy as a fingertip. GL-free; any thread.
#pragma once

#include <optional>
#include <vector>

#include "render/gl/vertex.hpp"
#include "render/scene/draw_list.hpp"
#include "render/view/view_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// The pad's outline lies on the proxy sphere this far (rad, 40 degrees) from its pad axis: the
/// rim of a fingertip's flat pad (fem_pad's cap angle).
inline constexpr double kPadOutlineAngle = 0.6981317007977318;

/// The marks' radius (the outline's tube, the stalk), in proxy radii: at least about a pixel
/// where a view is given.
inline constexpr double kMarkWidthShare = 0.06;

/// How far the tilt marker reaches beyond the proxy sphere, in proxy radii.
inline constexpr double kTiltMarkerShare = 1.3;

/// A fingertip's body: its length from the pad's centre to its top's, in proxy radii.
inline constexpr double kFingertipLengthShare = 2.5;

/// The way a finger's device points away from its pad (world, unit): the device's orientation
/// applied to the pad axis, reversed (a fem_pad finger's pad axis is in the world frame already).
/// World up for a finger whose device is not turned and whose pad faces down (the default).
sim::Vec3 deviceUp(const sim::FingerSnapshot& finger);

/// The device's +x axis (world, unit): the twist bead's side of the pad outline.
sim::Vec3 deviceSide(const sim::FingerSnapshot& finger);

/// Whether the overlay draws the pad's outline and its twist bead at `finger`: for an oriented
/// pad (pad_model "oriented", the 6-DOF pad whose contact turns with the device), not a fem_pad
/// finger's (its skin is drawn).
bool drawsPadOutline(const sim::FingerSnapshot& finger);

/// Whether the overlay draws the tilt marker at `finger`: with the pad's outline, and for any
/// other finger but a fem_pad one while its device is turned more than half a degree from the
/// identity (a disc pad's contact ignores the turn; the marker shows what it ignores).
bool drawsTiltMarker(const sim::FingerSnapshot& finger);

/// How far from the proxy centre what is drawn at `finger` reaches (m), proxy, marks and a
/// fingertip's body included, for a proxy of `proxy_radius` (m) drawn as `look`.
double fingerReach(const sim::FingerSnapshot& finger, double proxy_radius, view::ProxyLook look);

/// Appends the triangles of `finger` drawn as a fingertip to `out` (world, wound outward): one
/// closed capsule, the proxy sphere of `proxy_radius` (m) its pad's end, its body going
/// deviceUp() for kFingertipLengthShare radii to a round top. Nothing for a fem_pad finger (its
/// skin is its pad). Allocates only while `out` grows.
void appendFingertip(const sim::FingerSnapshot& finger, double proxy_radius, std::vector<Vertex>& out);

/// Appends the marks of finger `index` to `out`: a fingertip's nail (kProxies, on its back, the
/// device's -z side: on top when the device leans forward about +x) when `look` is a
/// fingertip; then, as drawsPadOutline() and drawsTiltMarker() say, the pad's outline (a lit
/// ring on the proxy sphere around the device's pad axis, at kPadOutlineAngle: seen from the
/// side it narrows), a bead on it towards deviceSide() (a twist about the pad axis turns it) and
/// the tilt marker (a stalk with a head along deviceUp() out of the sphere; a fingertip's body
/// is its marker), opaque and depth-tested (kMarks), in the finger's colour, at least about a
/// pixel thick in `view` when one is given. `scratch` is overwritten.
void addFingerMarks(const sim::FingerSnapshot& finger, int index, double proxy_radius, view::ProxyLook look,
                    const std::optional<DrawView>& view, std::vector<Vertex>& scratch, DrawList& out);

}  // namespace gf::render

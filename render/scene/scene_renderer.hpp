// Draws one Snapshot of a scene: shaded bodies, the ground grid with soft shadows, each finger
// (proxy, or a fem_pad finger's bone under its deformed pad; device ghost, coupling spring), and
// each contact's highlighted patch with its SGOs, normal and force arrow. Render thread only.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "render/scene/camera.hpp"
#include "render/scene/draw_list.hpp"
#include "render/gl/gpu.hpp"
#include "sim/scene/scene_desc.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// What a scene draws and how. The switches are effects: what is off is not built.
struct RenderSettings {
  bool shadows = true;               ///< shadow map from the key light (soft: 2 bilinear taps)
  bool patch_highlight = true;       ///< contact patches, SGO dots, normals, force arrows
  bool fingers = true;               ///< proxies, pads, device ghosts, springs; off: no proxy or pad shadows either
  bool contact_arrows = true;        ///< contact normals and force arrows (off in close-ups down the normal)
  bool ground = true;                ///< ground planes (close-ups from under a lifted body hide them)
  bool load_arrows = false;          ///< each point's normal load and friction as arrows (load_marks.hpp)
  int shadow_map_size = 1024;        ///< texels per side (the map covers 3 scene radii)
  double force_arrow_m_per_n = 0.01; ///< arrow length per newton of coupling force (m/N)
  double max_arrow_m = 0.08;         ///< longest force arrow (m)
  double max_arrow_view_share = 0.25; ///< longest force arrow, as a share of the view's height at its proxy
  view::BodyPattern body_pattern = view::BodyPattern::kStripes;  ///< rigid bodies' stripes, fixed in their frames
  view::ProxyLook proxy = view::ProxyLook::kSphere;  ///< proxies as spheres, or as fingertips
  /// The scene's targets (ghost poses and zones, draw_list.hpp); null or empty: none. Shared, so
  /// that settings are copied without allocating.
  std::shared_ptr<const std::vector<view::Target>> targets;
};

/// Draws snapshots of one scene. Construction builds every body's render surface (meshes come
/// from the description, loaded once per run) and makes the GL objects (allocates; throws
/// sim::MeshLoadError or GlError). draw() reuses its vertex and scratch buffers from frame to
/// frame; they grow to the largest patch drawn.
class SceneRenderer {
 public:
  SceneRenderer(const sim::SceneDesc& scene, const RenderSettings& settings);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  /// Draws `snapshot` seen from `camera` into the bound framebuffer of `width` x `height`.
  /// Returns the pixels where it drew anything but the backdrop (what anti-aliasing must see).
  /// The shadow map is drawn again only when something that casts a shadow moved (samePlaces,
  /// same_picture.hpp): further views of the same instant, such as the patch insets, and later
  /// frames of a still scene reuse it. It is kept twice, with and without the proxies: a view
  /// without fingers casts no proxy shadows. Each view (camera and size; up to four) also keeps
  /// its bodies' layer (backdrop, bodies, ground shadows) while nothing moves, so a still scene
  /// draws only its contact overlay again.
  PixelRect draw(const sim::Snapshot& snapshot, const view::Camera& camera, int width, int height);
  /// The last draw's kept bodies' layer, when it restored one (its number and the pixels of its
  /// contact overlay, for Framebuffer::resolve); nullopt when it drew its bodies.
  std::optional<HeldLayer> heldLayer() const;
  /// Changes the switches for the next draw (close-ups hide the fingers).
  void setSettings(const RenderSettings& settings);
  /// The next draw draws the shadow map again, even for the instant it was last drawn for: a
  /// view whose map differs from the frame's (a close-up's, without the fingers) neither reuses
  /// nor leaves one for a frame of the same instant.
  void redrawShadows();
  const RenderSettings& settings() const;
  /// Each body's render surface in its description frame (null for a plane), as the overlay
  /// and the label layout (render/overlay/layout.hpp) take them.
  const std::vector<std::shared_ptr<const sim::Mesh>>& surfaces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::render

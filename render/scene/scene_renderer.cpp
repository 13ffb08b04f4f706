#include "render/scene/scene_renderer.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>

#include "render/gl/context.hpp"
#include "render/scene/draw_list.hpp"
#include "render/scene/finger_marks.hpp"
#include "render/scene/geometry.hpp"
#include "render/scene/pad_mesh.hpp"
#include "render/scene/screen_bounds.hpp"
#include "render/state/same_picture.hpp"
#include "render/state/view_layers.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/shaders.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

const Eigen::Vector3f kBackground(0.62f, 0.68f, 0.76f);  // linear RGB
const Eigen::Vector3f kGround(0.55f, 0.55f, 0.53f);
constexpr int kRoundSegments = 24;
constexpr double kLightHalf = 1.5;  // half side of the key light's view, in scene radii

// One body as the GPU sees it.
struct BodyDraw {
  std::shared_ptr<const sim::Mesh> mesh;  // render surface, description frame; null for planes
  std::unique_ptr<GpuMesh> gpu;
  Eigen::Vector3f colour;
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // of its bounds, description frame: its stripes' centre
  bool ground = false;
  bool closed = false;  // closed and wound outwards: back faces are hidden and need not be drawn
};

// A mesh whose back faces can never be seen: no boundary, no non-manifold or inconsistently
// wound edge, positive volume.
bool closedOutward(const sim::Mesh& m) {
  const sim::MeshBuildReport& r = m.report();
  return r.boundary_edges == 0 && r.non_manifold_edges == 0 && r.inconsistent_edges == 0 && m.signedVolume() > 0.0;
}

// Centre and radius (m) of everything the scene starts with: sizes the shadow map and fog.
std::pair<Vec3, double> sceneBounds(const sim::SceneDesc& scene, const std::vector<BodyDraw>& bodies) {
  Eigen::AlignedBox3d box;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].mesh) continue;
    const double r = 0.5 * bodies[b].mesh->diagonal();
    box.extend(scene.bodies[b].position + Vec3::Constant(r));
    box.extend(scene.bodies[b].position - Vec3::Constant(r));
  }
  for (const sim::FingerDesc& f : scene.fingers) {
    for (const auto& k : f.device.keyframes) box.extend(k.position);
  }
  if (box.isEmpty()) return {Vec3::Zero(), 0.1};
  return {box.center(), std::max(0.05, 0.5 * box.diagonal().norm())};
}

// Corner k (0..7) of a mesh's bounding box, placed by `pose` (world, m).
Vec3 boxCorner(const sim::Mesh& m, const sim::Pose& pose, int k) {
  const Vec3 corner((k & 1 ? m.boundsMax() : m.boundsMin()).x(), (k & 2 ? m.boundsMax() : m.boundsMin()).y(),
                    (k & 4 ? m.boundsMax() : m.boundsMin()).z());
  return pose.position + pose.orientation * corner;
}


}  // namespace

struct SceneRenderer::Impl {
  sim::SceneDesc scene;
  RenderSettings settings;
  // One program per kind of surface: llvmpipe would run every side of a uniform branch.
  Program lit{"lit", shaders::kSurfaceVertex, shaders::kLitFragment.c_str()};
  Program lit_shadowed{"lit+shadow", shaders::kSurfaceVertex, shaders::kLitFragment.c_str(), "#define SHADOWS"};
  Program striped{"lit+pattern", shaders::kSurfaceVertex, shaders::kLitFragment.c_str(), "#define PATTERN"};
  Program striped_shadowed{"lit+shadow+pattern", shaders::kSurfaceVertex, shaders::kLitFragment.c_str(),
                           "#define SHADOWS\n#define PATTERN"};
  Program ground{"ground", shaders::kSurfaceVertex, shaders::kGroundFragment.c_str()};
  Program receiver{"shadow receiver", shaders::kSurfaceVertex, shaders::kShadowReceiverFragment.c_str()};
  Program flat{"flat", shaders::kSurfaceVertex, shaders::kFlatFragment};
  Program depth{"depth", shaders::kDepthVertex, shaders::kDepthFragment};
  const Program* current = &lit;  // the program drawShape() feeds
  // The key light's depth with the proxies and pads (`shadow`) and without them (`body_shadow`,
  // drawn first and copied into `shadow` before the fingers are added): views without fingers,
  // such as the patch insets, show no shadow of a proxy they do not show.
  std::unique_ptr<ShadowMap> shadow, body_shadow;
  // The state the shadow maps were last drawn for: a second view of the same instant (the patch
  // insets), and every later one while nothing that casts a shadow moved (samePlaces), reuses
  // them.
  sim::Snapshot shadow_state;
  bool shadow_valid = false;
  bool shadow_has_fingers = false;  // `shadow` holds the proxies of that instant
  std::vector<BodyDraw> bodies;
  // Proxies and ghosts are large on screen; contact dots are a few pixels (and many).
  GpuMesh sphere{unitSphere(3)}, dot_sphere{unitSphere(1)}, cylinder{unitCylinder(kRoundSegments)}, cone{unitCone(kRoundSegments)};
  // Their bounding boxes, in the order of DrawShape (for the pixels an overlay can cover).
  const std::array<Eigen::AlignedBox3f, 4> shape_bounds{boundsOf(unitSphere(3)), boundsOf(unitSphere(1)),
                                                       boundsOf(unitCylinder(kRoundSegments)),
                                                       boundsOf(unitCone(kRoundSegments))};
  std::unique_ptr<GpuMesh> ground_quad;
  GpuMesh receiver_quad{{}, true};  // where shadows can fall on one ground plane
  std::vector<Vertex> receiver_vertices;
  // Clear colour and ground for the last camera of each frame size, restored each frame instead
  // of redrawn (a frame and its patch insets are two sizes).
  ViewLayers views;  // each view's backdrop and bodies' layer (view_layers.hpp)
  // The contact overlay: built as plain data (draw_list.hpp), its vertices in one buffer.
  std::vector<std::shared_ptr<const sim::Mesh>> surfaces;  // per body, null for a plane
  std::optional<DrawListBuilder> overlay_builder;  // made once the bodies' surfaces are
  DrawList overlay;
  GpuMesh overlay_vertices{{}, true};
  // The fem_pad fingers' skins for the shadow map, built as the overlay builds them.
  PadMeshBuilder pad_builder;
  std::vector<Vertex> pad_vertices;
  GpuMesh pad_mesh{{}, true};
  std::vector<Vertex> soft_vertices;  // the soft bodies' surfaces for the shadow map
  GpuMesh soft_mesh{{}, true};
  Vec3 centre = Vec3::Zero();
  double extent = 0.1;
  Eigen::Matrix4f view, view_proj, light_view_proj;  // view, view_proj: this frame's camera
  std::optional<HeldLayer> held;  // the last draw restored a kept layer: which, and its overlay's pixels
  DrawView draw_view;  // this frame's camera as the overlay's builder sees it
  Vec3 light_dir = Vec3(0.25, 1.0, 0.3).normalized();

  Impl(const sim::SceneDesc& s, const RenderSettings& r) : scene(s), settings(r) {
    for (const sim::BodyDesc& b : scene.bodies) {
      BodyDraw d;
      d.mesh = bodyRenderMesh(b);
      d.colour = b.colour.cast<float>();
      d.ground = b.shape == sim::ShapeKind::kPlane;
      if (d.mesh) {
        d.gpu = std::make_unique<GpuMesh>(shadedTriangles(*d.mesh, 35.0));
        d.closed = closedOutward(*d.mesh);
        d.centre = (0.5 * (d.mesh->boundsMin() + d.mesh->boundsMax())).cast<float>();
      }
      bodies.push_back(std::move(d));
    }
    for (const BodyDraw& d : bodies) surfaces.push_back(d.mesh);
    overlay_builder.emplace(scene, surfaces);
    std::tie(centre, extent) = sceneBounds(scene, bodies);
    // The ground: a square of 40 scene radii, fading into the background.
    const float h = static_cast<float>(40.0 * extent);
    const Vertex corners[4] = {{{-h, 0, -h}, {0, 1, 0}}, {{h, 0, -h}, {0, 1, 0}},
                               {{h, 0, h}, {0, 1, 0}}, {{-h, 0, h}, {0, 1, 0}}};
    ground_quad = std::make_unique<GpuMesh>(
        std::vector<Vertex>{corners[0], corners[2], corners[1], corners[0], corners[3], corners[2]});
    // The key light is fixed: its view covers the scene's starting bounds.
    const Vec3 eye = centre + 3.0 * extent * light_dir;
    light_view_proj = orthographic(kLightHalf * extent, kLightHalf * extent, 0.5 * extent, 6.0 * extent) *
                      lookAt(eye, centre, upFor(-light_dir));
  }

  void use(const Program& p) {
    current = &p;
    p.use();
  }

  void setMatrices(const Eigen::Matrix4f& model) const {
    glUniformMatrix4fv(current->uniform("u_model"), 1, GL_FALSE, model.data());
    const Eigen::Matrix3f normal = model.topLeftCorner<3, 3>().inverse().transpose();
    glUniformMatrix3fv(current->uniform("u_normal_matrix"), 1, GL_FALSE, normal.data());
  }

  void setColour(const Eigen::Vector3f& colour, float alpha) const {
    glUniform4f(current->uniform("u_colour"), colour.x(), colour.y(), colour.z(), alpha);
  }

  // `mesh` with the current program.
  void drawShape(const GpuMesh& mesh, const Eigen::Matrix4f& model, const Eigen::Vector3f& colour,
                 float alpha) const {
    setMatrices(model);
    setColour(colour, alpha);
    mesh.draw(GL_TRIANGLES);
  }

  // Each body's model matrix from the snapshot (ground planes included).
  Eigen::Matrix4f bodyModel(const sim::Snapshot& snap, std::size_t b) const {
    const sim::Pose& p = snap.bodies[b];
    return modelMatrix(p.position, p.orientation, Vec3::Ones());
  }

  // The bodies into `body_shadow`; with the fingers on, that copied into `shadow` and the proxies
  // (a pad's bone) and pads added there.
  void shadowPass(const sim::Snapshot& snap) {
    body_shadow->bindForDrawing();
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(2.0f, 4.0f);
    depth.use();
    glUniformMatrix4fv(depth.uniform("u_light_view_proj"), 1, GL_FALSE, light_view_proj.data());
    const auto cast = [&](const GpuMesh& mesh, const Eigen::Matrix4f& model) {
      glUniformMatrix4fv(depth.uniform("u_model"), 1, GL_FALSE, model.data());
      mesh.draw(GL_TRIANGLES);
    };
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (!bodies[b].gpu) continue;
      if (bodies[b].closed) glEnable(GL_CULL_FACE);
      cast(*bodies[b].gpu, bodyModel(snap, b));
      glDisable(GL_CULL_FACE);
    }
    if (!snap.soft_bodies.empty()) {  // soft bodies as they are, rebuilt each frame
      soft_vertices.clear();
      for (const sim::SoftBodySnapshot& s : snap.soft_bodies) {
        if (s.surface) pad_builder.build(s.nodes, *s.surface, soft_vertices);
      }
      soft_mesh.upload(soft_vertices);
      cast(soft_mesh, Eigen::Matrix4f::Identity());
    }
    shadow_has_fingers = settings.fingers;
    if (settings.fingers) {
      shadow->copyFrom(*body_shadow);
      glEnable(GL_CULL_FACE);  // spheres are closed
      pad_vertices.clear();
      for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
        const double r = proxySphereRadius(snap.fingers[i], scene.fingers[i].proxy.radius);
        cast(sphere, modelMatrix(snap.fingers[i].proxy, Eigen::Quaterniond::Identity(), Vec3::Constant(r)));
        pad_builder.build(snap.fingers[i].pad, pad_vertices);
        if (settings.proxy == view::ProxyLook::kFingertip) appendFingertip(snap.fingers[i], r, pad_vertices);
      }
      glDisable(GL_CULL_FACE);  // a pad's skin is open on its bone's side
      if (!pad_vertices.empty()) {
        pad_mesh.upload(pad_vertices);
        cast(pad_mesh, Eigen::Matrix4f::Identity());
      }
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  // Camera, light and ground uniforms of every surface program for this frame.
  void beginSurfacePass(const view::Camera& camera, int width, int height) {
    const double far_m = 60.0 * extent + (camera.position - centre).norm();
    view = lookAt(camera.position, camera.target, upFor(camera.target - camera.position));
    view_proj = perspective(camera.fov_deg, double(width) / height, 0.002, far_m) * view;
    draw_view.view_proj = view_proj.cast<double>();
    draw_view.eye = camera.position;
    draw_view.tan_half_fov = std::tan(0.5 * camera.fov_deg * std::numbers::pi / 180.0);
    draw_view.height_px = height;
    const Eigen::Vector3f l = light_dir.cast<float>(), c = camera.position.cast<float>();
    // Grid: 1 cm minor, 10 cm major lines for table-top scenes; scaled up for larger ones.
    const float minor = static_cast<float>(std::pow(10.0, std::floor(std::log10(extent * 0.5))));
    if (shadow) (settings.fingers ? shadow : body_shadow)->bindTexture(0);
    for (const Program* p : {&lit, &lit_shadowed, &striped, &striped_shadowed, &ground, &receiver, &flat}) {
      p->use();
      glUniformMatrix4fv(p->uniform("u_view_proj"), 1, GL_FALSE, view_proj.data());
      glUniformMatrix4fv(p->uniform("u_light_view_proj"), 1, GL_FALSE, light_view_proj.data());
      glUniform3f(p->uniform("u_light_dir"), l.x(), l.y(), l.z());
      glUniform3f(p->uniform("u_camera"), c.x(), c.y(), c.z());
      glUniform3f(p->uniform("u_background"), kBackground.x(), kBackground.y(), kBackground.z());
      glUniform1i(p->uniform("u_shadow"), 0);
      if (shadow) glUniform1f(p->uniform("u_shadow_texel"), 1.0f / shadow->size());
      glUniform2f(p->uniform("u_grid"), minor, 10.0f * minor);
      glUniform2f(p->uniform("u_fog"), static_cast<float>(4.0 * extent), static_cast<float>(25.0 * extent));
    }
    use(lit);
  }

  // Background colour and ground: drawn in the frame and taken into the backdrop when the view
  // changed, else copied from the backdrop into the frame. Ground planes are static bodies, so
  // only the camera and the frame size change what the backdrop holds. Then the bodies and the
  // ground's shadows, or their layer when nothing has moved since it was kept (ViewSlot).
  void drawBase(const sim::Snapshot& snap, const view::Camera& camera, int width, int height) {
    GLint target = 0, samples = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
    glGetIntegerv(GL_SAMPLES, &samples);
    samples = std::max(samples, 1);
    bool stale = false;
    ViewSlot* slot = &views.slotFor(camera, width, height, samples, settings.ground, stale);
    if (stale) {
      glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));  // a new backdrop binds its own
      const Eigen::Vector3f bg = kBackground.cwiseSqrt();  // the shaders' display gamma
      glClearColor(bg.x(), bg.y(), bg.z(), 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);  // stencil: see below
      use(ground);
      for (std::size_t b = 0; b < bodies.size() && settings.ground; ++b) {
        if (bodies[b].ground) drawShape(*ground_quad, bodyModel(snap, b), kGround.cwiseProduct(bodies[b].colour / 0.7f), 1.0f);
      }
      slot->backdrop->takeFrom(static_cast<unsigned>(target));
    }
    const LayerSwitches switches{shadow != nullptr, settings.ground, settings.fingers, settings.body_pattern, settings.proxy};
    const bool still =
        slot->layer_state_valid && slot->layer_switches == switches && samePlaces(snap, slot->layer_state);
    if (still && slot->layer_kept) {
      slot->layer->restoreColourInto(static_cast<unsigned>(target));
      // Depth only where the overlay can draw: nothing else is depth-tested after the layer.
      const PixelRect r = overlayPixels(overlay, shape_bounds, view_proj, width, height);
      held = HeldLayer{slot->layer_number, r};
      if (r.empty()) return;
      glEnable(GL_SCISSOR_TEST);
      glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
      drawDepth(snap, true);
      glDisable(GL_SCISSOR_TEST);
      return;
    }
    if (!stale) slot->backdrop->restoreColourInto(static_cast<unsigned>(target));
    drawDepth(snap, false);
    drawBodies(snap);
    if (shadow && settings.ground) drawGroundShadows(snap);
    slot->layer_kept = still;
    if (still) {
      if (!slot->layer) slot->layer = std::make_unique<Backdrop>(width, height, samples);
      slot->layer->takeFrom(static_cast<unsigned>(target));
      static std::atomic<long> layers_taken{0};
      slot->layer_number = ++layers_taken;
    } else {
      slot->layer_state = snap;
      slot->layer_switches = switches;
      slot->layer_state_valid = true;
    }
  }

  // The depth of the ground planes and, with `bodies_too`, the bodies of `snap`, colour untouched:
  // what a restored backdrop or bodies' layer needs under what is drawn on it. The same vertex
  // shader as their colour pass, so the same depths.
  void drawDepth(const sim::Snapshot& snap, bool bodies_too) {
    // The stencil too, when the target has one (FXAA's edge marks): llvmpipe clears packed depth
    // and stencil together in one fill, depth alone pixel by pixel.
    glClear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    use(flat);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (bodies[b].ground) {
        if (settings.ground) drawShape(*ground_quad, bodyModel(snap, b), Eigen::Vector3f::Ones(), 1.0f);
      } else if (bodies_too && bodies[b].gpu) {
        if (bodies[b].closed) glEnable(GL_CULL_FACE);
        drawShape(*bodies[b].gpu, bodyModel(snap, b), Eigen::Vector3f::Ones(), 1.0f);
        glDisable(GL_CULL_FACE);
      }
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  }

  // Pixels that the bodies, fingers and contact marks of `snap` can cover: each drawn thing's
  // bounding sphere, projected conservatively. Outside it the frame is the smooth backdrop.
  PixelRect dynamicRect(const sim::Snapshot& snap, const view::Camera& camera, int width, int height) const {
    SphereBounds bounds(view.cast<double>(), camera.fov_deg, width, height);  // view: set by beginSurfacePass()
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (bodies[b].ground || !bodies[b].mesh) continue;
      for (int k = 0; k < 8; ++k) bounds.add(boxCorner(*bodies[b].mesh, snap.bodies[b], k), 0.0);
    }
    for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
      const sim::FingerSnapshot& f = snap.fingers[i];
      const double r = scene.fingers[i].proxy.radius;
      bounds.add(f.proxy, std::max(fingerReach(f, r, settings.proxy), padReach(f.pad, f.proxy)));
      bounds.add(f.device, r);
      if (!f.contacts.empty()) bounds.add(f.proxy + forceArrow(f, drawSettings()), r);
      for (const sim::ContactSnapshot& c : f.contacts) bounds.add(c.point_world, std::max(c.radius, scene.fingers[i].patch.r_max));
    }
    return bounds.pixels();
  }

  // The rectangle of ground plane b (its own frame) that the shadows of `snap` can darken:
  // every body's bounding box and every proxy (and pad), projected along the key light. Empty when the
  // light grazes the plane.
  void receiverQuad(const sim::Snapshot& snap, std::size_t b) {
    receiver_vertices.clear();
    const sim::Pose& g = snap.bodies[b];
    const Vec3 normal = g.orientation * Vec3::UnitY();
    const double facing = light_dir.dot(normal);
    if (facing < 0.05) return;
    Eigen::AlignedBox2d rect;
    const auto add = [&](const Vec3& p, double r) {
      const Vec3 on_ground = p - ((p - g.position).dot(normal) / facing) * light_dir;
      const Vec3 local = g.orientation.conjugate() * (on_ground - g.position);
      const Eigen::Vector2d xz(local.x(), local.z());
      rect.extend(xz - Eigen::Vector2d::Constant(r / facing));
      rect.extend(xz + Eigen::Vector2d::Constant(r / facing));
    };
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      if (bodies[k].ground || !bodies[k].mesh) continue;
      for (int c = 0; c < 8; ++c) add(boxCorner(*bodies[k].mesh, snap.bodies[k], c), 0.0);
    }
    if (settings.fingers) {
      for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
        const sim::FingerSnapshot& f = snap.fingers[i];
        add(f.proxy, std::max(fingerReach(f, scene.fingers[i].proxy.radius, settings.proxy), padReach(f.pad, f.proxy)));
      }
    }
    if (rect.isEmpty()) return;
    rect.extend(rect.min() - Eigen::Vector2d::Constant(0.01 * extent));  // the soft edge
    rect.extend(rect.max() + Eigen::Vector2d::Constant(0.01 * extent));
    const auto corner = [&](double x, double z) { return makeVertex(Vec3(x, 0, z), Vec3::UnitY()); };
    const Vertex a = corner(rect.min().x(), rect.min().y()), b2 = corner(rect.max().x(), rect.min().y()),
                 c = corner(rect.max().x(), rect.max().y()), d = corner(rect.min().x(), rect.max().y());
    receiver_vertices = {a, c, b2, a, d, c};
  }

  // Darkens the ground where the key light is blocked (multiplies the backdrop's colour). Drawn
  // after the bodies, so the depth test spares the pixels they cover.
  void drawGroundShadows(const sim::Snapshot& snap) {
    use(receiver);
    glEnable(GL_BLEND);
    glBlendFunc(GL_DST_COLOR, GL_ZERO);
    glDepthMask(GL_FALSE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0f, -2.0f);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (!bodies[b].ground) continue;
      receiverQuad(snap, b);
      receiver_quad.upload(receiver_vertices);
      drawShape(receiver_quad, bodyModel(snap, b), Eigen::Vector3f::Ones(), 1.0f);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthMask(GL_TRUE);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_BLEND);
  }

  // The rigid bodies, striped in their own frames unless the pattern is off.
  void drawBodies(const sim::Snapshot& snap) {
    const bool pattern = settings.body_pattern == view::BodyPattern::kStripes;
    use(pattern ? (shadow ? striped_shadowed : striped) : (shadow ? lit_shadowed : lit));
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (bodies[b].ground || !bodies[b].gpu) continue;
      if (bodies[b].closed) glEnable(GL_CULL_FACE);
      const Eigen::Vector3f& c = bodies[b].centre;
      if (pattern) glUniform3f(current->uniform("u_pattern_centre"), c.x(), c.y(), c.z());
      drawShape(*bodies[b].gpu, bodyModel(snap, b), bodies[b].colour, 1.0f);
      glDisable(GL_CULL_FACE);
    }
  }

  // The GL state of each pass of the overlay (draw_list.hpp), set on entering and undone on
  // leaving: depth test on, blending, culling, polygon offset off, depth writes on between passes.
  void enterPass(DrawPass pass) {
    switch (pass) {
      case DrawPass::kPatchFill:
      case DrawPass::kPatchRim:
        glEnable(GL_BLEND);
        glDepthMask(GL_FALSE);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(-2.0f, -4.0f);
        // The fill is lit like the body under it; the rim band is flat, so it reads in shade.
        if (pass == DrawPass::kPatchRim) use(flat);
        else use(shadow ? lit_shadowed : lit);
        break;
      case DrawPass::kPatchLines: use(flat); break;
      case DrawPass::kMarks: use(lit); break;
      case DrawPass::kPads: use(shadow ? lit_shadowed : lit); break;  // opaque, like the bodies
      case DrawPass::kArrows:
        use(lit);
        glDisable(GL_DEPTH_TEST);  // arrows read through the proxy and the body
        // Without depth, an arrow's back faces and the cone's base would be drawn over its front
        // (a beaded shaft, a sawtooth cone seen end-on): shafts and heads are closed and convex.
        glEnable(GL_CULL_FACE);
        break;
      case DrawPass::kProxies:
        use(lit);
        glEnable(GL_BLEND);
        glDepthMask(GL_FALSE);   // the patch under the proxy, drawn next, shows through it
        glEnable(GL_CULL_FACE);  // spheres are closed: the back half would only be blended twice
        break;
      case DrawPass::kTargets:
        use(lit);
        glEnable(GL_BLEND);
        glDepthMask(GL_FALSE);
        glEnable(GL_CULL_FACE);  // ghosts and zones are closed, wound outward
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(-2.0f, -4.0f);  // a ghost's face on its body's face: in front, no flicker
        break;
      case DrawPass::kGhosts:
      case DrawPass::kSprings:
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        use(flat);
        break;
    }
  }

  void leavePass(DrawPass pass) {
    switch (pass) {
      case DrawPass::kPatchFill:
      case DrawPass::kPatchRim:
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        break;
      case DrawPass::kPatchLines:
      case DrawPass::kMarks:
      case DrawPass::kPads: break;
      case DrawPass::kArrows:
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        break;
      case DrawPass::kTargets:
        glDisable(GL_POLYGON_OFFSET_FILL);
        [[fallthrough]];
      case DrawPass::kProxies:
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        glDisable(GL_BLEND);
        break;
      case DrawPass::kGhosts:
      case DrawPass::kSprings:
        glDisable(GL_BLEND);
        glEnable(GL_DEPTH_TEST);
        break;
    }
  }

  // What the overlay draws, seen from this frame's camera (set by beginSurfacePass()).
  DrawSettings drawSettings() const {
    DrawSettings d;
    d.patch_highlight = settings.patch_highlight;
    d.fingers = settings.fingers;
    d.contact_arrows = settings.contact_arrows;
    d.load_arrows = settings.load_arrows;
    d.force_arrow_m_per_n = settings.force_arrow_m_per_n;
    d.max_arrow_m = settings.max_arrow_m;
    d.max_arrow_view_share = settings.max_arrow_view_share;
    d.view = draw_view;
    d.targets = settings.targets.get();
    d.proxy = settings.proxy;
    return d;
  }

  // Draws the overlay of `snap`: the list is built without GL, then each item drawn in order.
  // Draws the overlay built for this frame (`overlay`).
  void drawOverlay() {
    if (overlay.items.empty()) return;
    overlay_vertices.upload(overlay.vertices);
    const GpuMesh* shapes[] = {&sphere, &dot_sphere, &cylinder, &cone};
    bool in_pass = false;
    DrawPass pass = DrawPass::kMarks;
    for (const DrawItem& item : overlay.items) {
      if (!in_pass || item.pass != pass) {
        if (in_pass) leavePass(pass);
        pass = item.pass;
        enterPass(pass);
        in_pass = true;
      }
      if (item.shape == DrawShape::kTriangles || item.shape == DrawShape::kLines) {
        setMatrices(Eigen::Matrix4f::Identity());
        setColour(item.colour, item.alpha);
        overlay_vertices.draw(item.shape == DrawShape::kTriangles ? GL_TRIANGLES : GL_LINES, item.first, item.count);
      } else {
        drawShape(*shapes[static_cast<int>(item.shape)], item.model, item.colour, item.alpha);
      }
    }
    leavePass(pass);
  }
};

SceneRenderer::SceneRenderer(const sim::SceneDesc& scene, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(scene, settings)) {
  setSettings(settings);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::setSettings(const RenderSettings& settings) {
  impl_->settings = settings;
  if (settings.shadows && !impl_->shadow) {
    impl_->shadow = std::make_unique<ShadowMap>(settings.shadow_map_size);
    impl_->body_shadow = std::make_unique<ShadowMap>(settings.shadow_map_size);
    impl_->shadow_valid = false;  // new maps: drawn at the next draw
  }
  if (!settings.shadows) {
    impl_->shadow.reset();
    impl_->body_shadow.reset();
  }
}

const RenderSettings& SceneRenderer::settings() const { return impl_->settings; }

const std::vector<std::shared_ptr<const sim::Mesh>>& SceneRenderer::surfaces() const { return impl_->surfaces; }

void SceneRenderer::redrawShadows() { impl_->shadow_valid = false; }

std::optional<HeldLayer> SceneRenderer::heldLayer() const { return impl_->held; }

PixelRect SceneRenderer::draw(const sim::Snapshot& snapshot, const view::Camera& camera, int width, int height) {
  GF_ASSERT_GL_THREAD();
  GLint target = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  const bool stale = !impl_->shadow_valid || !samePlaces(snapshot, impl_->shadow_state) ||
                     (impl_->settings.fingers && !impl_->shadow_has_fingers);
  if (impl_->shadow && stale) {
    impl_->shadowPass(snapshot);
    impl_->shadow_state = snapshot;
    impl_->shadow_valid = true;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
  glViewport(0, 0, width, height);
  impl_->beginSurfacePass(camera, width, height);
  impl_->held.reset();
  impl_->overlay_builder->build(snapshot, impl_->drawSettings(), impl_->overlay);
  impl_->drawBase(snapshot, camera, width, height);
  impl_->drawOverlay();
  return impl_->dynamicRect(snapshot, camera, width, height);
}

}  // namespace gf::render

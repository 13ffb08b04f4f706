#include "render/scene_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/geometry.hpp"
#include "render/gl.hpp"
#include "render/patch_mesh.hpp"
#include "render/shaders.hpp"

namespace gf::render {
namespace {

using sim::Vec3;

const Eigen::Vector3f kBackground(0.62f, 0.68f, 0.76f);  // linear RGB
const Eigen::Vector3f kGround(0.55f, 0.55f, 0.53f);
constexpr int kRoundSegments = 24;
constexpr float kGhostAlpha = 0.28f;
constexpr float kPatchAlpha = 0.55f;
constexpr float kProxyAlpha = 0.6f;

Eigen::Matrix4f modelMatrix(const Vec3& position, const Eigen::Quaterniond& orientation,
                            const Vec3& scale) {
  Eigen::Affine3d a = Eigen::Translation3d(position) * orientation * Eigen::Scaling(scale);
  return a.matrix().cast<float>();
}

// Rotation taking +y onto `direction` (unit).
Eigen::Quaterniond fromY(const Vec3& direction) {
  return Eigen::Quaterniond::FromTwoVectors(Vec3::UnitY(), direction);
}

// One body as the GPU sees it.
struct BodyDraw {
  std::shared_ptr<const sim::Mesh> mesh;  // render surface, description frame; null for planes
  std::unique_ptr<GpuMesh> gpu;
  Eigen::Vector3f colour;
  bool ground = false;
};

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

}  // namespace

Eigen::Vector3f fingerColour(int finger) {
  static const Eigen::Vector3f kPalette[] = {{0.10f, 0.35f, 0.95f}, {0.90f, 0.12f, 0.30f},
                                             {0.10f, 0.70f, 0.25f}, {0.85f, 0.65f, 0.05f}};
  return kPalette[static_cast<std::size_t>(finger) % 4];
}

struct SceneRenderer::Impl {
  sim::SceneDesc scene;
  RenderSettings settings;
  Program surface{"surface", shaders::kSurfaceVertex, shaders::kSurfaceFragment};
  Program depth{"depth", shaders::kDepthVertex, shaders::kDepthFragment};
  std::unique_ptr<ShadowMap> shadow;
  std::vector<BodyDraw> bodies;
  GpuMesh sphere{unitSphere()}, cylinder{unitCylinder(kRoundSegments)}, cone{unitCone(kRoundSegments)};
  GpuMesh ground_quad;
  GpuMesh patch_fill{{}, true}, patch_lines{{}, true}, spring_lines{{}, true};
  std::vector<Vertex> fill_vertices, line_vertices, spring_vertices;
  Vec3 centre = Vec3::Zero();
  double extent = 0.1;
  Eigen::Matrix4f view_proj, light_view_proj;
  Vec3 light_dir = Vec3(0.25, 1.0, 0.3).normalized();

  Impl(const sim::SceneDesc& s, const RenderSettings& r) : scene(s), settings(r) {
    for (const sim::BodyDesc& b : scene.bodies) {
      BodyDraw d;
      d.mesh = bodyRenderMesh(b);
      d.colour = b.colour.cast<float>();
      d.ground = b.shape == sim::ShapeKind::kPlane;
      if (d.mesh) d.gpu = std::make_unique<GpuMesh>(shadedTriangles(*d.mesh, 35.0));
      bodies.push_back(std::move(d));
    }
    std::tie(centre, extent) = sceneBounds(scene, bodies);
    // The ground: a square of 40 scene radii, fading into the background.
    const float h = static_cast<float>(40.0 * extent);
    const Vertex corners[4] = {{{-h, 0, -h}, {0, 1, 0}}, {{h, 0, -h}, {0, 1, 0}},
                               {{h, 0, h}, {0, 1, 0}}, {{-h, 0, h}, {0, 1, 0}}};
    ground_quad.upload({corners[0], corners[2], corners[1], corners[0], corners[3], corners[2]});
    // The key light is fixed: its view covers the scene's starting bounds.
    const Vec3 eye = centre + 3.0 * extent * light_dir;
    light_view_proj = orthographic(1.5 * extent, 1.5 * extent, 0.5 * extent, 6.0 * extent) *
                      lookAt(eye, centre, upFor(-light_dir));
  }

  void setMatrices(const Program& p, const Eigen::Matrix4f& model) const {
    glUniformMatrix4fv(p.uniform("u_model"), 1, GL_FALSE, model.data());
    const Eigen::Matrix3f normal = model.topLeftCorner<3, 3>().inverse().transpose();
    glUniformMatrix3fv(p.uniform("u_normal_matrix"), 1, GL_FALSE, normal.data());
  }

  void drawShape(const GpuMesh& mesh, const Eigen::Matrix4f& model, const Eigen::Vector3f& colour,
                 float alpha, int mode = 0) const {
    setMatrices(surface, model);
    glUniform4f(surface.uniform("u_colour"), colour.x(), colour.y(), colour.z(), alpha);
    glUniform1i(surface.uniform("u_mode"), mode);
    mesh.draw(GL_TRIANGLES);
  }

  // Each body's model matrix from the snapshot (ground planes included).
  Eigen::Matrix4f bodyModel(const sim::Snapshot& snap, std::size_t b) const {
    const sim::BodySnapshot& p = snap.bodies[b];
    return modelMatrix(p.position, p.orientation, Vec3::Ones());
  }

  void shadowPass(const sim::Snapshot& snap) {
    shadow->bindForDrawing();
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
      if (bodies[b].gpu) cast(*bodies[b].gpu, bodyModel(snap, b));
    }
    if (settings.fingers) {
      for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
        const double r = scene.fingers[i].proxy.radius;
        cast(sphere, modelMatrix(snap.fingers[i].proxy, Eigen::Quaterniond::Identity(), Vec3::Constant(r)));
      }
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  void beginSurfacePass(const Camera& camera, int width, int height) {
    const double far_m = 60.0 * extent + (camera.position - centre).norm();
    view_proj = perspective(camera.fov_deg, double(width) / height, 0.002, far_m) *
                lookAt(camera.position, camera.target, upFor(camera.target - camera.position));
    surface.use();
    glUniformMatrix4fv(surface.uniform("u_view_proj"), 1, GL_FALSE, view_proj.data());
    glUniformMatrix4fv(surface.uniform("u_light_view_proj"), 1, GL_FALSE, light_view_proj.data());
    const Eigen::Vector3f l = light_dir.cast<float>(), c = camera.position.cast<float>();
    glUniform3f(surface.uniform("u_light_dir"), l.x(), l.y(), l.z());
    glUniform3f(surface.uniform("u_camera"), c.x(), c.y(), c.z());
    glUniform3f(surface.uniform("u_background"), kBackground.x(), kBackground.y(), kBackground.z());
    glUniform1i(surface.uniform("u_use_shadow"), shadow ? 1 : 0);
    glUniform1i(surface.uniform("u_shadow"), 0);
    if (shadow) {
      shadow->bindTexture(0);
      glUniform1f(surface.uniform("u_shadow_texel"), 1.0f / shadow->size());
    }
    // Grid: 1 cm minor, 10 cm major lines for table-top scenes; scaled up for larger ones.
    const float minor = static_cast<float>(std::pow(10.0, std::floor(std::log10(extent * 0.5))));
    glUniform2f(surface.uniform("u_grid"), minor, 10.0f * minor);
    glUniform2f(surface.uniform("u_fog"), static_cast<float>(4.0 * extent), static_cast<float>(25.0 * extent));
  }

  void drawBodies(const sim::Snapshot& snap) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const BodyDraw& d = bodies[b];
      if (d.ground) {
        drawShape(ground_quad, bodyModel(snap, b), kGround.cwiseProduct(d.colour / 0.7f), 1.0f, 1);
      } else if (d.gpu) {
        drawShape(*d.gpu, bodyModel(snap, b), d.colour, 1.0f);
      }
    }
  }

  void drawArrow(const Vec3& from, const Vec3& vector, double radius, const Eigen::Vector3f& colour) {
    const double length = vector.norm();
    if (length < 1e-6) return;
    const Vec3 dir = vector / length;
    const double head = std::min(0.45 * length, 5.0 * radius);
    const Eigen::Quaterniond q = fromY(dir);
    drawShape(cylinder, modelMatrix(from, q, Vec3(radius, length - head, radius)), colour, 1.0f);
    drawShape(cone, modelMatrix(from + (length - head) * dir, q, Vec3(2.5 * radius, head, 2.5 * radius)),
              colour, 1.0f);
  }

  // Proxies are drawn after the patches and a little translucent: the patch under the finger
  // stays readable.
  void drawFingers(const sim::Snapshot& snap) {
    glEnable(GL_BLEND);
    for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
      const sim::FingerSnapshot& f = snap.fingers[i];
      const double r = scene.fingers[i].proxy.radius;
      drawShape(sphere, modelMatrix(f.proxy, Eigen::Quaterniond::Identity(), Vec3::Constant(r)),
                fingerColour(static_cast<int>(i)) * 0.8f + Eigen::Vector3f::Constant(0.15f), kProxyAlpha);
    }
    glDisable(GL_BLEND);
  }

  // Ghosts and springs see through bodies: the device sits inside the object while pressing.
  void drawDeviceGhosts(const sim::Snapshot& snap) {
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    spring_vertices.clear();
    for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
      const sim::FingerSnapshot& f = snap.fingers[i];
      const double r = scene.fingers[i].proxy.radius;
      drawShape(sphere, modelMatrix(f.device, Eigen::Quaterniond::Identity(), Vec3::Constant(r)),
                fingerColour(static_cast<int>(i)), kGhostAlpha);
      appendSpring(f.proxy, f.device, 0.5 * r);
    }
    spring_lines.upload(spring_vertices);
    setMatrices(surface, Eigen::Matrix4f::Identity());
    glUniform4f(surface.uniform("u_colour"), 0.1f, 0.1f, 0.1f, 0.85f);
    glUniform1i(surface.uniform("u_mode"), 2);
    spring_lines.draw(GL_LINES);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
  }

  // A coil of 8 turns from the proxy centre to the device.
  void appendSpring(const Vec3& a, const Vec3& b, double coil_radius) {
    const Vec3 axis = b - a;
    if (axis.norm() < 1e-4) return;
    const Eigen::Quaterniond q = fromY(axis.normalized());
    constexpr int kSegments = 96;
    Vec3 previous = a;
    for (int s = 1; s <= kSegments; ++s) {
      const double u = double(s) / kSegments, angle = 8 * 2 * std::numbers::pi * u;
      const double taper = std::min(1.0, std::min(u, 1 - u) * 12);
      const Vec3 p = a + u * axis + q * Vec3(taper * coil_radius * std::cos(angle), 0,
                                             taper * coil_radius * std::sin(angle));
      spring_vertices.push_back(makeVertex(previous, Vec3::UnitY()));
      spring_vertices.push_back(makeVertex(p, Vec3::UnitY()));
      previous = p;
    }
  }

  void drawPatches(const sim::Snapshot& snap) {
    // Translucent fills on the surface, then the walked paths and rim, then dots and arrows.
    for (std::size_t i = 0; i < snap.fingers.size(); ++i) {
      fill_vertices.clear();
      line_vertices.clear();
      for (const sim::ContactSnapshot& c : snap.fingers[i].contacts) {
        const std::size_t b = static_cast<std::size_t>(c.body);
        if (b < bodies.size() && bodies[b].mesh) {
          buildPatchMesh(c, *bodies[b].mesh, snap.bodies[b], {}, fill_vertices, line_vertices);
        }
      }
      const Eigen::Vector3f colour = fingerColour(static_cast<int>(i));
      glEnable(GL_BLEND);
      glDepthMask(GL_FALSE);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(-2.0f, -4.0f);
      patch_fill.upload(fill_vertices);
      drawShape(patch_fill, Eigen::Matrix4f::Identity(), colour, kPatchAlpha);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
      patch_lines.upload(line_vertices);
      glUniform4f(surface.uniform("u_colour"), colour.x() * 0.5f, colour.y() * 0.5f, colour.z() * 0.5f, 1.0f);
      glUniform1i(surface.uniform("u_mode"), 2);
      patch_lines.draw(GL_LINES);
      drawContactMarks(snap.fingers[i], static_cast<int>(i));
    }
  }

  void drawContactMarks(const sim::FingerSnapshot& f, int finger) {
    const Eigen::Vector3f colour = fingerColour(finger);
    const double dot = 0.12 * scene.fingers[static_cast<std::size_t>(finger)].proxy.radius;
    for (const sim::ContactSnapshot& c : f.contacts) {
      // The god-object's contact point; with n_SGO = 0 it is the whole patch.
      drawShape(sphere, modelMatrix(c.point, Eigen::Quaterniond::Identity(), Vec3::Constant(1.3 * dot)),
                Eigen::Vector3f(0.95f, 0.95f, 0.95f), 1.0f);
      for (const Vec3& s : c.sgos) {
        drawShape(sphere, modelMatrix(s, Eigen::Quaterniond::Identity(), Vec3::Constant(dot)), colour, 1.0f);
      }
    }
    glDisable(GL_DEPTH_TEST);  // arrows read through the proxy and the body
    for (const sim::ContactSnapshot& c : f.contacts) {
      const double length = std::max(c.radius, 0.6 * scene.fingers[static_cast<std::size_t>(finger)].patch.r_max);
      drawArrow(c.point, length * c.outward_normal, 0.3 * dot, Eigen::Vector3f(0.95f, 0.95f, 0.95f));
    }
    if (!f.contacts.empty()) {
      const double n = f.coupling_force.norm();
      const double length = std::min(settings.max_arrow_m, n * settings.force_arrow_m_per_n);
      if (n > 1e-9) drawArrow(f.proxy, length * f.coupling_force / n, 0.6 * dot, Eigen::Vector3f(1.0f, 0.75f, 0.1f));
    }
    glEnable(GL_DEPTH_TEST);
  }
};

SceneRenderer::SceneRenderer(const sim::SceneDesc& scene, const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(scene, settings)) {
  setSettings(settings);
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::setSettings(const RenderSettings& settings) {
  impl_->settings = settings;
  if (settings.shadows && !impl_->shadow) impl_->shadow = std::make_unique<ShadowMap>(settings.shadow_map_size);
  if (!settings.shadows) impl_->shadow.reset();
}

const RenderSettings& SceneRenderer::settings() const { return impl_->settings; }

void SceneRenderer::draw(const sim::Snapshot& snapshot, const Camera& camera, int width, int height) {
  GLint target = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
  glDisable(GL_CULL_FACE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  if (impl_->shadow) impl_->shadowPass(snapshot);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
  glViewport(0, 0, width, height);
  const Eigen::Vector3f bg = kBackground.cwiseSqrt();  // the shaders' display gamma
  glClearColor(bg.x(), bg.y(), bg.z(), 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  impl_->beginSurfacePass(camera, width, height);
  impl_->drawBodies(snapshot);
  if (impl_->settings.patch_highlight) impl_->drawPatches(snapshot);
  if (impl_->settings.fingers) impl_->drawFingers(snapshot);
  if (impl_->settings.fingers) impl_->drawDeviceGhosts(snapshot);
}

}  // namespace gf::render

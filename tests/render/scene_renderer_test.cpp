// Frames drawn by the scene renderer: anti-aliasing, the cached backdrop, close-ups without the
// proxies' shadows, the time stamp, bodies' stripes, and the overlay's layout in a 640x360 frame.
#include "render/scene/scene_renderer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "app/compare/screenshots.hpp"
#include "app/session/session.hpp"
#include "render/gl/context.hpp"
#include "render/gl/gpu.hpp"
#include "render/frames/image.hpp"
#include "render/frames/image_compare.hpp"
#include "render/overlay/overlay.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/render_thread.hpp"
#include "tests/render/still_layout.hpp"

namespace gf {
namespace {

// Frames of fig8 at t = 4 s, 320 x 180, drawn by one renderer into framebuffers of each kind.
class Frames : public ::testing::Test {
 protected:
  Frames()
      : session_(app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml")),
        snapshot_(app::snapshotAt(session_, 4.0)),
        settings_(app::frameSettings(session_, {})),
        renderer_(session_.scene, settings_.scene) {}

  render::Image draw(render::Framebuffer& frame, const view::Camera& camera) {
    frame.bind();
    frame.resolve(renderer_.draw(snapshot_, camera, frame.width(), frame.height()));
    render::Image image;
    frame.read(image);
    return image;
  }
  render::Image draw(view::Antialiasing aa) {
    render::Framebuffer frame(kWidth, kHeight, aa);
    return draw(frame, settings_.camera);
  }

  // The snapshot with every finger's patch (its SGOs and walked paths) scaled by `scale` about
  // its contact point.
  sim::Snapshot withPatchesScaled(double scale) const {
    sim::Snapshot s = snapshot_;
    for (sim::FingerSnapshot& f : s.fingers) {
      for (sim::ContactSnapshot& c : f.contacts) {
        for (sim::Vec3& p : c.sgos_world) p = c.point_world + scale * (p - c.point_world);
        for (sim::Vec3& p : c.path_points_world) p = c.point_world + scale * (p - c.point_world);
      }
    }
    return s;
  }

  // `s` drawn into `held`, resolved with the layer the renderer kept (into `a`), and into `whole`
  // filtered over its whole edge rectangle (into `b`); the edges and the kept layer.
  struct HeldDraw {
    render::PixelRect edges;
    std::optional<render::HeldLayer> layer;
  };
  HeldDraw drawHeldAndWhole(const sim::Snapshot& s, render::Framebuffer& held, render::Framebuffer& whole,
                            render::Image& a, render::Image& b) {
    held.bind();
    HeldDraw out{renderer_.draw(s, settings_.camera, kWidth, kHeight), renderer_.heldLayer()};
    held.resolve(out.edges, out.layer);
    held.read(a);
    whole.bind();
    whole.resolve(renderer_.draw(s, settings_.camera, kWidth, kHeight));
    whole.read(b);
    return out;
  }

  static constexpr int kWidth = 320, kHeight = 180;
  render::GlContext context_;
  app::SessionDesc session_;
  sim::Snapshot snapshot_;
  render::FrameOutputSettings settings_;
  render::SceneRenderer renderer_;
};

// Anti-aliasing only touches pixels at edges: a few percent of the frame change, and none in
// the top-left corner (sky and far ground, where the frame has no geometric edge).
TEST_F(Frames, AntialiasingChangesOnlyEdgePixels) {
  const render::Image none = draw(view::Antialiasing::kNone);
  for (const view::Antialiasing aa : {view::Antialiasing::kFxaa, view::Antialiasing::kMsaa}) {
    const render::Image smooth = draw(aa);
    ASSERT_EQ(smooth.rgb.size(), none.rgb.size());
    int changed = 0, changed_corner = 0;
    for (std::size_t i = 0; i < none.rgb.size(); i += 3) {
      const bool differs = std::abs(int(none.rgb[i]) - int(smooth.rgb[i])) > 2 ||
                           std::abs(int(none.rgb[i + 1]) - int(smooth.rgb[i + 1])) > 2 ||
                           std::abs(int(none.rgb[i + 2]) - int(smooth.rgb[i + 2])) > 2;
      changed += differs;
      const std::size_t x = i / 3 % kWidth, y = i / 3 / kWidth;
      changed_corner += differs && x < kWidth / 4 && y < kHeight / 2;
    }
    const double share = double(changed) / (kWidth * kHeight);
    EXPECT_GT(share, 0.002) << view::antialiasingName(aa);
    EXPECT_LT(share, 0.08) << view::antialiasingName(aa);
    EXPECT_EQ(changed_corner, 0) << view::antialiasingName(aa);
  }
}

// FXAA marks its edges in the stencil with a value per resolve and filters where the mark is
// this resolve's (the filter keeps its own contrast test, so a stale mark cannot filter a pixel
// that has no edge; a missing one would leave an edge unfiltered). Over 300 resolves of one
// framebuffer (the value wraps after 255 and the stencil is cleared), two views taking turns,
// each frame is the one a fresh framebuffer draws, which the filter changed.
TEST_F(Frames, FxaaOverManyResolvesDrawsWhatAFreshFramebufferDraws) {
  view::Camera other = settings_.camera;
  other.position += sim::Vec3(0.03, -0.01, 0.02);
  const view::Camera cameras[2] = {settings_.camera, other};
  render::Image fresh[2];
  for (int k = 0; k < 2; ++k) {
    render::Framebuffer frame(kWidth, kHeight, view::Antialiasing::kFxaa);
    fresh[k] = draw(frame, cameras[k]);
  }
  ASSERT_NE(fresh[0].rgb, fresh[1].rgb);
  ASSERT_NE(fresh[0].rgb, draw(view::Antialiasing::kNone).rgb);  // the filter changed something
  render::Framebuffer frame(kWidth, kHeight, view::Antialiasing::kFxaa);
  int differing = 0;
  for (int i = 0; i < 300; ++i) differing += draw(frame, cameras[i % 2]).rgb != fresh[i % 2].rgb;
  EXPECT_EQ(differing, 0);
}

// A frame over a kept layer is filtered only near its overlay and the last one's, the rest
// copied from the last resolve. Over 12 held frames with the same edge rectangle (so more than
// 30 % of it is copied), whose patches shrink to half and grow back in turn and whose dots
// change colour, each is the frame a framebuffer filtering its whole rectangle draws. (The
// overlay's bounds stay those of the proxies and arrows here; the next test moves them.)
TEST_F(Frames, HeldFramesFilterNearTheirOverlaysAsAWholeFilterWould) {
  render::Framebuffer held(kWidth, kHeight, view::Antialiasing::kFxaa);
  render::Framebuffer whole(kWidth, kHeight, view::Antialiasing::kFxaa);
  std::vector<std::vector<std::uint8_t>> frames;
  std::optional<render::PixelRect> first_edges;
  int held_draws = 0, same_edges = 0;
  double copied_share = 0.0;  // of the edge rectangle, taken from the last resolve
  std::optional<render::HeldLayer> last;
  for (int i = 0; i < 12; ++i) {
    sim::Snapshot s = withPatchesScaled(i % 2 ? 0.5 : 1.0);
    for (sim::FingerSnapshot& f : s.fingers) {
      for (sim::ContactSnapshot& c : f.contacts) {
        for (std::size_t k = 0; k < c.loads.size(); ++k) c.loads[k].normal *= 1.0 + 0.5 * std::sin(0.9 * i + 1.3 * k);
      }
    }
    render::Image a, b;
    const auto [edges, now] = drawHeldAndWhole(s, held, whole, a, b);
    if (!first_edges) first_edges = edges;
    same_edges += i > 0 && render::sameRect(edges, *first_edges);
    held_draws += now.has_value();
    if (now) {  // what resolve filters again: the overlays' bounds and their reach, inside the rectangle
      const render::PixelRect r = render::intersect(render::grow(edges, 2), {0, 0, kWidth, kHeight});
      const render::PixelRect f = render::intersect(render::grow(render::unite(now->overlay, last ? last->overlay : render::PixelRect{}), 6), r);
      copied_share = std::max(copied_share, 1.0 - double((f.x1 - f.x0) * (f.y1 - f.y0)) / ((r.x1 - r.x0) * (r.y1 - r.y0)));
    }
    last = now;
    EXPECT_EQ(a.rgb, b.rgb) << "frame " << i;
    frames.push_back(a.rgb);
  }
  EXPECT_GE(held_draws, 10);       // the layer is kept from the second frame
  EXPECT_EQ(same_edges, 11);       // so the last resolve's pixels are taken outside the overlays
  EXPECT_GT(copied_share, 0.3);    // a good part of the rectangle
  EXPECT_NE(frames[4], frames[5]);  // and the overlays changed
}

// The same when the overlay's bounds change: the fingers' patches three times as wide and back
// in turn over the held bodies (the overlay's bounds then reach 10 px further up and down than
// the proxies'). A frame filters again where the last overlay was as well as where its own is:
// filtering only near its own would leave the last overlay's filtered pixels in the picture.
TEST_F(Frames, HeldFramesFilterWhereTheLastOverlayWasAsWell) {
  render::Framebuffer held(kWidth, kHeight, view::Antialiasing::kFxaa);
  render::Framebuffer whole(kWidth, kHeight, view::Antialiasing::kFxaa);
  std::optional<render::HeldLayer> last;
  std::optional<render::PixelRect> last_edges;
  int reused = 0, moved = 0;
  for (int i = 0; i < 8; ++i) {
    render::Image a, b;
    const auto [edges, now] = drawHeldAndWhole(withPatchesScaled(i % 2 ? 3.0 : 1.0), held, whole, a, b);
    if (now && last && now->layer == last->layer && render::sameRect(edges, *last_edges)) {
      ++reused;
      // More than the filter's reach (6 px) apart, so the last overlay's pixels lie outside
      // this one's filtered bounds.
      moved += std::abs(now->overlay.y0 - last->overlay.y0) > 6 && std::abs(now->overlay.y1 - last->overlay.y1) > 6;
    }
    last = now;
    last_edges = edges;
    EXPECT_EQ(a.rgb, b.rgb) << "frame " << i;
  }
  EXPECT_GE(reused, 6);      // frames that took the last resolve's pixels outside the overlays
  EXPECT_EQ(moved, reused);  // each with its overlay's bounds well apart from the last one's
}

// The backdrop is cached per camera: drawing again gives the same frame, and a frame after a
// different camera's frame is the same as before (the cache was rebuilt for each view).
TEST_F(Frames, CachedBackdropFollowsTheCamera) {
  render::Framebuffer frame(kWidth, kHeight, view::Antialiasing::kFxaa);
  const render::Image first = draw(frame, settings_.camera);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
  view::Camera other = settings_.camera;
  other.position += sim::Vec3(0.05, 0.02, 0.0);
  const render::Image moved = draw(frame, other);
  EXPECT_NE(moved.rgb, first.rgb);
  EXPECT_EQ(draw(frame, settings_.camera).rgb, first.rgb);
}

// A view without the fingers shows no proxy shadow, even right after a frame of the same
// instant drew the proxies into the shadow map it reuses: the right finger's inset of Fig. 7's
// side pick (the proxy's shadow fell across the patch).
TEST(CloseUps, AViewWithoutFingersShowsNoProxyShadow) {
  render::GlContext context;
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig7-side-pick.toml");
  const sim::Snapshot snapshot = app::snapshotAt(session, 2.5);
  const render::FrameOutputSettings settings = app::frameSettings(session, {});
  render::SceneRenderer renderer(session.scene, settings.scene);
  render::Framebuffer frame(320, 180, view::Antialiasing::kNone);
  render::Framebuffer inset(120, 120, view::Antialiasing::kNone);
  sim::Snapshot only;
  view::Camera camera;
  ASSERT_TRUE(render::contactCloseUp(session.scene, snapshot, 1, only, camera));
  const auto close = [&] {
    render::RenderSettings s = settings.scene;
    s.fingers = false;
    s.ground = false;
    renderer.setSettings(s);
    inset.bind();
    inset.resolve(renderer.draw(only, camera, 120, 120));
    render::Image image;
    inset.read(image);
    renderer.setSettings(settings.scene);
    return image;
  };
  frame.bind();
  frame.resolve(renderer.draw(snapshot, settings.camera, 320, 180));  // the proxies in the shadow map
  const render::Image after_frame = close();
  renderer.redrawShadows();
  const render::Image alone = close();  // a map drawn without the fingers
  EXPECT_EQ(after_frame.rgb, alone.rgb);
}

// Every frame without the overlay carries its time in the bottom-left corner: two frames of
// one state at two times differ there only.
TEST(Stills, EveryFrameCarriesItsTime) {
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig5-push-ball.toml");
  render::FrameOutputSettings settings = app::frameSettings(session, {});
  settings.width = 640;
  settings.height = 360;
  sim::Snapshot a = app::snapshotAt(session, 0.0), b = a;
  b.time = 7.25;  // the same state: only the stamp differs
  const render::Image ia = render::renderStill(session.scene, a, settings), ib = render::renderStill(session.scene, b, settings);
  int corner = 0, elsewhere = 0;
  for (int y = 0; y < 360; ++y) {
    for (int x = 0; x < 640; ++x) {
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * 640 + static_cast<std::size_t>(x));
      if (ia.rgb[i] == ib.rgb[i] && ia.rgb[i + 1] == ib.rgb[i + 1] && ia.rgb[i + 2] == ib.rgb[i + 2]) continue;
      (x < 200 && y > 320 ? corner : elsewhere) += 1;
    }
  }
  EXPECT_GT(corner, 20);
  EXPECT_EQ(elsewhere, 0);
}

// Fig. 5's ball turned 120 degrees about z (a roll along x): striped (the default) the frames
// differ over much of the ball; with body_pattern "none" the ball looks the same (its mesh's
// facets alone move). The pictures go to <build>/visual-diff/ to be looked at.
TEST(Stills, StripesShowABallsTurnAndAreOffWithTheKey) {
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig5-push-ball.toml");
  render::FrameOutputSettings settings = app::frameSettings(session, {});
  EXPECT_EQ(settings.scene.body_pattern, view::BodyPattern::kStripes);
  settings.width = 320;
  settings.height = 180;
  settings.patch_insets = false;
  const sim::Snapshot flat = app::snapshotAt(session, 0.0);
  sim::Snapshot turned = flat;
  turned.bodies[1].orientation = Eigen::AngleAxisd(-2.0 * std::numbers::pi / 3.0, sim::Vec3::UnitZ()) * flat.bodies[1].orientation;
  const std::filesystem::path out = std::filesystem::path(GF_BINARY_DIR) / "visual-diff";
  std::filesystem::create_directories(out);
  double changed[2] = {0.0, 0.0};  // share of the pixels off by more than 12 levels
  for (const view::BodyPattern pattern : {view::BodyPattern::kStripes, view::BodyPattern::kNone}) {
    settings.scene.body_pattern = pattern;
    const render::Image a = render::renderStill(session.scene, flat, settings), b = render::renderStill(session.scene, turned, settings);
    const std::string name(view::kBodyPatternNames[static_cast<std::size_t>(pattern)]);
    render::writePng((out / ("ball-" + name + "-0.png")).string(), a);
    render::writePng((out / ("ball-" + name + "-120.png")).string(), b);
    changed[static_cast<int>(pattern)] = render::compareImages(a, b, 12).differing_share;
  }
  std::printf("share of pixels changed by the turn: striped %.5f, plain %.5f\n", changed[0], changed[1]);
  EXPECT_GT(changed[0], 0.02);
  EXPECT_LT(changed[1], 0.001);
}

// Fig. 8's squeeze with made-up per-point loads (growing around the left ring, one SGO slipping,
// the right finger without loads): the left inset shows the load scale's ends (viridis' dark
// purple and yellow, on the dots and in the colour bar), the right one neither. The pictures go
// to <build>/visual-diff/ to be looked at.
TEST(Stills, InsetsColourTheDotsByLoadWithAColourBar) {
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/fig8-pinch-oscillation.toml");
  sim::Snapshot snap = app::snapshotAt(session, 4.0);
  for (sim::FingerSnapshot& f : snap.fingers) {
    for (sim::ContactSnapshot& c : f.contacts) c.loads.clear();
  }
  sim::ContactSnapshot& c = snap.fingers[0].contacts.front();
  ASSERT_EQ(c.sgos_world.size(), 8u);
  c.loads.resize(8);
  for (std::size_t k = 0; k < 8; ++k) c.loads[k].normal = 0.1 * static_cast<double>(k);  // 0 to 0.7 N
  c.loads[7].slipping = true;
  c.point_load.normal = 0.4;
  render::FrameOutputSettings settings = app::frameSettings(session, {});
  const auto near = [](const std::uint8_t* p, int r, int g, int b) {
    return std::abs(p[0] - r) < 20 && std::abs(p[1] - g) < 20 && std::abs(p[2] - b) < 20;
  };
  const std::filesystem::path out = std::filesystem::path(GF_BINARY_DIR) / "visual-diff";
  std::filesystem::create_directories(out);
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
    settings.width = w;
    settings.height = h;
    const render::Image image = render::renderStill(session.scene, snap, settings);
    render::writePng((out / ("load-colours-" + std::to_string(h) + ".png")).string(), image);
    const test::StillLayout layout = test::stillLayout(session.scene, snap, settings);
    const std::vector<render::InsetRect> insets =
        render::insetRects(w, h, 2, layout.placement.insets, layout.placement.column);
    for (std::size_t f = 0; f < 2; ++f) {
      int yellow = 0, purple = 0;
      const render::InsetRect& r = insets[f];
      for (int y = r.y; y < r.y + r.size; ++y) {
        for (int x = r.x; x < r.x + r.size; ++x) {
          const std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x))];
          yellow += near(p, 253, 231, 37);
          purple += near(p, 68, 1, 84);
        }
      }
      if (f == 0) {
        EXPECT_GT(yellow, 4) << w << "x" << h;
        EXPECT_GT(purple, 4) << w << "x" << h;
      } else {
        EXPECT_EQ(yellow + purple, 0) << w << "x" << h << ": no loads, no load colours";
      }
    }
  }
}

// The overlay fits a 640x360 frame (the goldens' size) and a 1280x720 one: every panel and
// widget inside the frame, no two panels overlapping.
TEST(Stills, TheOverlayFitsTheFrame) {
  render::GlContext context;
  const app::SessionDesc session = app::loadSceneFile(std::string(GF_SOURCE_DIR) + "/assets/scenes/overlay-demo.toml");
  const sim::Snapshot snapshot = app::snapshotAt(session, 0.5);
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
    render::Framebuffer frame(w, h, view::Antialiasing::kNone);
    frame.bind();
    render::Overlay overlay(session.scene, {}, w, h);
    overlay.draw(snapshot, {});
    const std::map<std::string, render::OverlayRect> layout = overlay.layout();
    ASSERT_EQ(layout.count("panel/fingers"), 1u);
    ASSERT_EQ(layout.count("right/friction"), 1u);
    for (const auto& [id, r] : layout) {
      EXPECT_GE(r.x0, 0.0f) << id << " at " << w << "x" << h;
      EXPECT_GE(r.y0, 0.0f) << id << " at " << w << "x" << h;
      EXPECT_LE(r.x1, static_cast<float>(w)) << id << " at " << w << "x" << h;
      EXPECT_LE(r.y1, static_cast<float>(h)) << id << " at " << w << "x" << h;
      for (const auto& [other, o] : layout) {
        if (id >= other || id.rfind("panel/", 0) != 0 || other.rfind("panel/", 0) != 0) continue;
        const bool apart = r.x1 <= o.x0 || o.x1 <= r.x0 || r.y1 <= o.y0 || o.y1 <= r.y0;
        EXPECT_TRUE(apart) << id << " overlaps " << other << " at " << w << "x" << h;
      }
    }
  }
}

}  // namespace
}  // namespace gf

// Rendering benchmarks: one frame at 1280x720 (draw + read-back) for each paper scene, and PNG
// encoding of such a frame. Run by hand: build/release/gf_bench --benchmark_filter=Render|Png
#include <benchmark/benchmark.h>

#include <ctime>
#include <optional>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/compare/screenshots.hpp"
#include "app/session/session.hpp"
#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/imgui_layer.hpp"
#include "render/overlay/labels.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/scene/scene_renderer.hpp"

namespace {

using namespace gf;

struct Prepared {
  app::SessionDesc session;
  sim::Snapshot snapshot;
};

Prepared prepare(const std::string& scene, double time) {
  Prepared p{app::loadSceneFile(app::resolveScenePath(scene)), {}};
  p.snapshot = app::snapshotAt(p.session, time);
  return p;
}

// Draw + anti-aliasing + read-back of one frame, repeated; `aa` overrides the scene's choice.
void drawFrames(benchmark::State& state, const char* scene, double time,
                std::optional<view::Antialiasing> aa = std::nullopt) {
  const Prepared p = prepare(scene, time);
  render::GlContext context;
  const render::FrameOutputSettings f = app::frameSettings(p.session, {});
  render::SceneRenderer renderer(p.session.scene, f.scene);
  render::Framebuffer frame(1280, 720, aa.value_or(f.antialiasing), f.msaa_samples);
  render::Image image;
  for (auto _ : state) {
    frame.bind();
    frame.resolve(renderer.draw(p.snapshot, f.camera, 1280, 720));
    frame.read(image);
    benchmark::DoNotOptimize(image.rgb.data());
  }
}

void BM_RenderFrame1280x720(benchmark::State& state, const char* scene, double time) {
  drawFrames(state, scene, time);
}
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig5, "fig5-push-ball", 1.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig6, "fig6-lift-one-finger", 2.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig7_lift, "fig7-lift-two-fingers", 2.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig7_side, "fig7-side-pick", 2.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig8, "fig8-pinch-oscillation", 4.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, concave_mesh, "concave-mesh", 1.5)->Unit(benchmark::kMillisecond);

// What anti-aliasing costs: fig8 drawn without, with FXAA (the default) and with 4x MSAA.
void BM_RenderAntialiasing1280x720(benchmark::State& state, view::Antialiasing aa) {
  drawFrames(state, "fig8-pinch-oscillation", 4.0, aa);
}
BENCHMARK_CAPTURE(BM_RenderAntialiasing1280x720, none, view::Antialiasing::kNone)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderAntialiasing1280x720, fxaa, view::Antialiasing::kFxaa)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderAntialiasing1280x720, msaa4, view::Antialiasing::kMsaa)->Unit(benchmark::kMillisecond);

void BM_PngEncode1280x720(benchmark::State& state) {
  const Prepared p = prepare("fig8-pinch-oscillation", 4.0);
  render::Image image;
  {
    render::GlContext context;
    const render::FrameOutputSettings f = app::frameSettings(p.session, {});
    render::SceneRenderer renderer(p.session.scene, f.scene);
    render::Framebuffer frame(1280, 720, f.antialiasing, f.msaa_samples);
    frame.bind();
    frame.resolve(renderer.draw(p.snapshot, f.camera, 1280, 720));
    frame.read(image);
  }
  std::size_t bytes = 0;
  for (auto _ : state) bytes = render::encodePng(image, 1).size();
  state.counters["kB"] = static_cast<double>(bytes) / 1000.0;
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PngEncode1280x720)->Unit(benchmark::kMillisecond);

// CPU seconds of the whole process (llvmpipe's rasterizer threads included).
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Where a Fig. 8 frame's CPU goes, stage by stage, as an offline run draws it (1280x720, FXAA,
// shadows, patch insets) and encodes it: each stage is finished (glFinish) before the next
// starts, so llvmpipe's rasterizers are charged to the stage that queued their work. Counters:
// CPU ms of the process per frame for each stage.
void BM_FrameStages1280x720(benchmark::State& state) {
  const Prepared p = prepare("fig8-pinch-oscillation", 4.0);
  render::GlContext context;
  const render::FrameOutputSettings f = app::frameSettings(p.session, {});
  render::SceneRenderer renderer(p.session.scene, f.scene);
  render::Framebuffer frame(1280, 720, f.antialiasing, f.msaa_samples);
  render::PatchInsets insets(p.session.scene, 1280, 720, render::InsetCorner::kBottomRight, f.antialiasing,
                             f.msaa_samples);
  const float stamp_px = render::stampLabelPx(720);
  render::ImGuiLayer labels(1280, 720, stamp_px, {insets.labelPx()});  // the insets' captions and the time stamp
  render::Image image;
  sim::Snapshot snapshot = p.snapshot;
  double cpu[6] = {};  // scene (shadow map included), anti-aliasing, insets, their labels and the stamp, read-back, PNG
  for (auto _ : state) {
    snapshot.step += 1;  // a new instant that places everything alike: shadow map and bodies' layers kept, as in a hold
    double t = processCpuSeconds();
    const auto lap = [&](int stage) {
      const double now = processCpuSeconds();
      cpu[stage] += now - t;
      t = now;
    };
    frame.bind();
    const render::PixelRect edges = renderer.draw(snapshot, f.camera, 1280, 720);
    glFinish();
    lap(0);
    frame.resolve(edges);
    glFinish();
    lap(1);
    GLint target = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
    insets.draw(renderer, snapshot, static_cast<unsigned>(target));
    glFinish();
    lap(2);
    labels.beginFrame(1.0 / 60.0, {});
    insets.drawLabels(labels, snapshot);
    render::drawFrameStamp(labels, stamp_px, 10.0f, 680.0f, snapshot.time, f.scene.force_arrow_m_per_n);
    labels.render();
    glFinish();
    lap(3);
    frame.read(image);
    lap(4);
    benchmark::DoNotOptimize(render::encodePng(image, 1).size());
    lap(5);
  }
  const char* names[] = {"scene_ms", "aa_ms", "insets_ms", "labels_ms", "read_ms", "png_ms"};
  for (int i = 0; i < 6; ++i) state.counters[names[i]] = 1e3 * cpu[i] / static_cast<double>(state.iterations());
}
BENCHMARK(BM_FrameStages1280x720)->Unit(benchmark::kMillisecond);

}  // namespace

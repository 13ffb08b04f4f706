// Rendering benchmarks: one frame at 1280x720 (draw + read-back) for each paper scene, and PNG
// encoding of such a frame. Run by hand: build/release/gf_bench --benchmark_filter=Render|Png
#include <benchmark/benchmark.h>

#include "app/scene_file.hpp"
#include "app/screenshots.hpp"
#include "app/session.hpp"
#include "render/context.hpp"
#include "render/gpu.hpp"
#include "render/scene_renderer.hpp"

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

void BM_RenderFrame1280x720(benchmark::State& state, const char* scene, double time) {
  const Prepared p = prepare(scene, time);
  render::GlContext context;
  const render::FrameOutputSettings f = app::frameSettings(p.session, {});
  render::SceneRenderer renderer(p.session.scene, f.scene);
  render::Framebuffer frame(1280, 720, f.msaa_samples);
  render::Image image;
  for (auto _ : state) {
    frame.bind();
    renderer.draw(p.snapshot, f.camera, 1280, 720);
    frame.read(image);
    benchmark::DoNotOptimize(image.rgb.data());
  }
}
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig5, "fig5-push-ball", 1.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig6, "fig6-lift-one-finger", 2.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig7_lift, "fig7-lift-two-fingers", 2.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig7_side, "fig7-side-pick", 2.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, fig8, "fig8-pinch-oscillation", 4.0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RenderFrame1280x720, concave_mesh, "concave-mesh", 1.5)->Unit(benchmark::kMillisecond);

void BM_PngEncode1280x720(benchmark::State& state) {
  const Prepared p = prepare("fig8-pinch-oscillation", 4.0);
  render::Image image;
  {
    render::GlContext context;
    const render::FrameOutputSettings f = app::frameSettings(p.session, {});
    render::SceneRenderer renderer(p.session.scene, f.scene);
    render::Framebuffer frame(1280, 720, f.msaa_samples);
    frame.bind();
    renderer.draw(p.snapshot, f.camera, 1280, 720);
    frame.read(image);
  }
  std::size_t bytes = 0;
  for (auto _ : state) bytes = render::encodePng(image, 1).size();
  state.counters["kB"] = static_cast<double>(bytes) / 1000.0;
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PngEncode1280x720)->Unit(benchmark::kMillisecond);

}  // namespace

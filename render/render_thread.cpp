#include "render/render_thread.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <cstdio>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <future>
#include <mutex>
#include <thread>
#include <utility>

#include <malloc.h>
#include <pthread.h>

#include "render/chart/chart_file.hpp"
#include "render/gl/context.hpp"
#include "render/gl/gl.hpp"
#include "render/gl/gpu.hpp"
#include "render/gl/imgui_layer.hpp"
#include "render/overlay/labels.hpp"
#include "render/overlay/layout.hpp"
#include "render/state/same_picture.hpp"
#include "render/state/snapshot_queue.hpp"
#include "render/state/triple_buffer.hpp"
#include "render/state/view_layers.hpp"
#include "render/state/wake.hpp"
#include "sim/assert.hpp"

namespace gf::render {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kQueueDepth = 2;

// One piece of offline work.
struct Job {
  sim::Snapshot snapshot;
  std::string close_up_prefix;  // non-empty: close-ups instead of a frame
  std::unique_ptr<ChartSpec> chart;  // non-null: a chart to `chart_path` instead of a frame
  std::string chart_path;
  bool release = false;  // give back the frames' GL resources (releaseFrames), then reply
  std::promise<std::vector<sim::SettingsCommand>> reply;
  bool wants_reply = false;
};

// Everything GL, created and destroyed on the render thread. The context is the first member:
// it is made before and destroyed after every GL object (their destructors assert it).
struct Gpu {
  GlContext context;
  SceneRenderer scene;
  Framebuffer frame;
  std::unique_ptr<Overlay> overlay;
  std::unique_ptr<PatchInsets> insets;
  // The frame's 2D labels: the insets' captions and, without the overlay (whose panel shows the
  // time), the time stamp.
  std::unique_ptr<ImGuiLayer> labels;
  bool stamp = false;
  float stamp_px = kMinLabelPx;
  std::unique_ptr<Framebuffer> close_up_frame;
  std::unique_ptr<ImGuiLayer> close_up_labels;
  view::Antialiasing antialiasing;
  int close_up_px;
  sim::SceneDesc description;  // the fingers' sizes, for the layout
  int fingers;
  bool insets_beside_overlay;
  bool top_left_free;
  LabelPlacement placement;  // the last frame's: kept while it covers nothing
  std::vector<ScreenBox> subjects;  // this frame's, for the layout
  // The state, camera and label corners the frame's last drawn scene picture shows, and whether
  // `frame` keeps that picture for the frames that draw the same (drawScene).
  sim::Snapshot drawn;
  view::Camera drawn_camera;
  bool drawn_any = false, picture_kept = false;
  long pictures_reused = 0;
  Gpu(const sim::SceneDesc& desc, const FrameOutputSettings& s)
      : scene(desc, s.scene),
        frame(s.width, s.height, s.antialiasing, s.msaa_samples),
        stamp(s.time_stamp && !s.overlay),
        stamp_px(stampLabelPx(s.height)),
        antialiasing(s.antialiasing),
        close_up_px(s.close_up_px),
        description(desc),
        fingers(static_cast<int>(desc.fingers.size())),
        insets_beside_overlay(s.overlay),
        top_left_free(!s.top_left_taken) {
    if (s.overlay) {
      OverlaySettings o = s.overlay_settings;
      o.wall_clock = s.realtime;  // offline snapshots carry no haptic timings
      o.arrow_m_per_n = s.scene.patch_highlight ? s.scene.force_arrow_m_per_n : 0.0;
      overlay = std::make_unique<Overlay>(desc, o, s.width, s.height);
    }
    if (s.patch_insets) {
      // Beside the overlay's bottom-right panel when both are on.
      insets = std::make_unique<PatchInsets>(desc, s.width, s.height,
                                             s.overlay ? InsetCorner::kBottomLeft : InsetCorner::kBottomRight,
                                             s.antialiasing, s.msaa_samples);
    }
    if (insets || stamp) {
      labels = std::make_unique<ImGuiLayer>(s.width, s.height, stamp_px,
                                            std::vector<float>{insets ? insets->labelPx() : stamp_px});
    }
  }

  // The frame of `snap` from `camera`, with the insets and labels, into `frame` (the output bound
  // after). The insets and the stamp go in corners clear of the bodies, proxies and patches
  // (layout.hpp); beside the overlay's bottom-right panel the insets keep to the bottom left.
  // A frame whose scene draws as the picture drawn last (same_picture.hpp: nothing moved, same
  // camera and label corners) reuses that picture: only the labels are drawn again. The picture
  // is kept from the second frame of a still spell on, so moving frames copy nothing.
  void drawScene(const sim::Snapshot& snap, const view::Camera& camera, int width, int height) {
    const RenderSettings& r = scene.settings();
    const double arrow_m_per_n = r.patch_highlight && r.contact_arrows ? r.force_arrow_m_per_n : 0.0;
    const LabelSizes sizes = frameLabelSizes(width, height, fingers, insets != nullptr, stamp, snap.time, arrow_m_per_n);
    const bool free = !insets_beside_overlay;
    const std::array<bool, 4> allowed = {free, true, free, free && top_left_free};
    subjects = subjectBoxes(description, scene.surfaces(), snap, camera, width, height, arrow_m_per_n, r.proxy);
    const LabelPlacement placed =
        placeLabels(subjects, sizes, width, height, placement, allowed, {true, true, true, top_left_free});
    const bool still = drawn_any && placed == placement && sameView(camera, drawn_camera) && width == frame.width() &&
                       height == frame.height() && drawsTheSame(snap, drawn, r.load_arrows);
    placement = placed;
    if (still && picture_kept && frame.restorePicture()) {
      ++pictures_reused;
    } else {
      frame.bind();
      const PixelRect edges = scene.draw(snap, camera, width, height);
      frame.resolve(edges, scene.heldLayer());
      if (insets) {
        GLint output = 0;
        glGetIntegerv(GL_FRAMEBUFFER_BINDING, &output);
        insets->place(placement.insets, placement.column);
        insets->draw(scene, snap, static_cast<unsigned>(output));
      }
      picture_kept = still;
      if (picture_kept) frame.keepPicture();
      drawn = snap;
      drawn_camera = camera;
      drawn_any = true;
    }
    GLint target = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
    if (!labels) return;
    labels->beginFrame(1.0 / 60.0, {});
    if (insets) insets->drawLabels(*labels, snap);
    if (stamp) {
      const ScreenBox at = placedBoxes(placement, sizes, width, height)[1];
      drawFrameStamp(*labels, stamp_px, at.x0, at.y0, snap.time, arrow_m_per_n);
    }
    labels->render();
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
  }
};

// The close-up of each contact of `snap` as a PNG: the patch down its normal, with its caption
// (finger, model, time, F_n, F_t, radius, SGOs), scale bar, load colour bar and tangential arrow.
void drawCloseUps(Gpu& gpu, const sim::SceneDesc& desc, const sim::Snapshot& snap, const std::string& prefix) {
  const float px = contactLabelPx(gpu.close_up_px);
  if (!gpu.close_up_frame) {
    gpu.close_up_frame = std::make_unique<Framebuffer>(gpu.close_up_px, gpu.close_up_px, gpu.antialiasing);
    gpu.close_up_labels = std::make_unique<ImGuiLayer>(gpu.close_up_px, gpu.close_up_px, px);
  }
  RenderSettings settings = gpu.scene.settings();
  const RenderSettings saved = settings;
  settings.fingers = false;         // the proxy would hide the patch it stands on
  settings.ground = false;          // a camera under a lifted body is under the ground
  settings.contact_arrows = false;  // they point at the camera: the labels draw the forces in 2D
  settings.patch_highlight = true;
  settings.targets = nullptr;          // a target's ghost would cover the patch
  gpu.scene.setSettings(settings);
  // Close-ups draw a shadow map of their own (no fingers cast shadows) and leave none behind: the
  // frame of the same instant, drawn after them, draws its own.
  gpu.scene.redrawShadows();
  sim::Snapshot only;
  view::Camera camera;
  for (std::size_t f = 0; f < snap.fingers.size(); ++f) {
    if (!contactCloseUp(desc, snap, f, only, camera)) continue;
    gpu.close_up_frame->bind();
    gpu.close_up_frame->resolve(gpu.scene.draw(only, camera, gpu.close_up_px, gpu.close_up_px));
    ContactLabel label;
    label.finger = &desc.fingers[f];
    label.finger_index = static_cast<int>(f);
    label.state = &snap.fingers[f];
    label.contact = &snap.fingers[f].contacts.front();
    label.camera = camera;
    label.time = snap.time;
    label.arrow_m_per_n = saved.force_arrow_m_per_n;
    label.close_up = true;
    label.load_arrows = saved.load_arrows;
    gpu.close_up_labels->beginFrame(1.0 / 60.0, {});
    drawContactLabel(*ImGui::GetForegroundDrawList(), gpu.close_up_labels->font(px), px,
                     {0.0f, 0.0f, static_cast<float>(gpu.close_up_px)}, label);
    gpu.close_up_labels->render();
    Image image;
    gpu.close_up_frame->read(image);
    writePng(closeUpPath(prefix, desc.fingers[f].name), image);
  }
  gpu.scene.setSettings(saved);
  gpu.scene.redrawShadows();
}

// Close-ups and charts: work that is not a frame of the stream.
void drawSideJob(Gpu& gpu, const sim::SceneDesc& desc, const Job& job) {
  if (job.chart) return drawChartFile(*job.chart, job.chart_path);
  drawCloseUps(gpu, desc, job.snapshot, job.close_up_prefix);
}

}  // namespace

std::string closeUpPath(const std::string& prefix, const std::string& finger) {
  return finger.empty() ? prefix + ".png" : std::string(prefix).append("-").append(finger).append(".png");
}

struct RenderThread::Impl {
  sim::SceneDesc scene;
  FrameOutputSettings settings;
  std::unique_ptr<PngSequenceWriter> png;
  std::unique_ptr<VideoWriter> video;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Job> queue;
  bool closing = false;
  std::string error;
  TripleBuffer latest;
  // Realtime frames written to files with no viewer: every published state is drawn, in order
  // (a frame that falls behind is drawn late rather than lost), from a queue of
  // kQueuedSeconds of them; null otherwise (the newest is drawn, from `latest`).
  std::unique_ptr<SnapshotQueue> ordered;
  std::atomic<long> dropped{0};  // states published to a full queue: not drawn
  long queue_max = 0;            // the most states waiting when one was taken
  long drawn_after_end = 0;      // frames drawn after finish() was called
  long realtime_drawn = 0;       // under `mutex`: realtime frames drawn (waitFirstFrame)
  Wake wake;  // realtime: the render thread sleeps on it until a publish, finish() or its next frame
  std::atomic<bool> input_published{false};  // set before the publish of a viewer's input
  long hurried = 0;
  std::vector<Job> deferred;  // offline close-ups waiting for the frames' memory (defersCloseUps)

  std::mutex command_mutex;
  std::vector<sim::SettingsCommand> commands;
  std::vector<float> frame_ms;
  Clock::time_point start = Clock::now();
  std::string gl_description;
  long pictures_reused = 0;  // added from the Gpu when it is released and when the thread ends
  bool background_priority = false;  // the render thread runs at nice kBackgroundNice
  std::thread thread;

  // Queues a job set up by `fill` (under the lock; once the queue has room when `bounded`) and,
  // with `reply`, waits until it is done and returns its commands. Throws the thread's error.
  template <class Fill>
  std::vector<sim::SettingsCommand> submit(Fill&& fill, bool bounded, bool reply) {
    std::future<std::vector<sim::SettingsCommand>> done;
    {
      std::unique_lock lock(mutex);
      if (bounded) changed.wait(lock, [&] { return queue.size() < kQueueDepth || !error.empty(); });
      if (!error.empty()) throw GlError(error);
      if (closing) throw GlError("the render thread has finished");
      Job& job = queue.emplace_back();
      fill(job);
      job.wants_reply = reply;
      if (reply) done = job.reply.get_future();
      changed.notify_all();
    }
    if (!reply) return {};
    try {
      return done.get();
    } catch (const std::future_error&) {  // the thread failed before it got to the job
      std::lock_guard lock(mutex);
      throw GlError(error.empty() ? "render thread stopped" : error);
    }
  }

  void fail(const std::string& what) {
    std::lock_guard lock(mutex);
    if (error.empty()) error = what;
    closing = true;
    changed.notify_all();
  }

  // Draws one frame of the stream and hands it to the encoders; returns the overlay's commands.
  std::vector<sim::SettingsCommand> drawFrame(Gpu& gpu, const sim::Snapshot& snap) {
    const auto begin = Clock::now();
    // The insets and the overlay go on top of the anti-aliased scene.
    gpu.drawScene(snap, settings.camera, settings.width, settings.height);
    std::vector<sim::SettingsCommand> made;
    const double last_ms = frame_ms.empty() ? 0.0 : frame_ms.back();
    if (gpu.overlay) made = gpu.overlay->draw(snap, {last_ms});
    Image image = png ? png->spare() : Image{};
    gpu.frame.read(image);
    frame_ms.push_back(std::chrono::duration<float, std::milli>(Clock::now() - begin).count());
    if (settings.tap) settings.tap->frame(image, snap, frame_ms.back());
    if (video) video->push(image);
    if (png) png->push(std::move(image));
    return made;
  }

  // The frames' GL objects given back, the heap trimmed; then the close-ups deferred meanwhile.
  void releaseGpu(std::unique_ptr<Gpu>& gpu) {
    if (!gpu) return;
    pictures_reused += gpu->pictures_reused;
    gpu.reset();
    malloc_trim(0);
    drawDeferredCloseUps();
  }

  // An offline run drawing frames keeps its close-ups until the frames' GL memory is given back,
  // then draws them with a context sized for them: drawn among the frames, their framebuffer,
  // labels, layer and shader variants stayed in the frames' heap (docs/performance.md, "Memory").
  bool defersCloseUps() const {
    return settings.close_ups_after_frames && !settings.realtime && (png || video || settings.tap);
  }
  void drawDeferredCloseUps() {
    if (deferred.empty()) return;
    const std::vector<Job> jobs = std::exchange(deferred, {});
    FrameOutputSettings s = settings;
    s.width = s.height = settings.close_up_px;
    s.overlay = s.patch_insets = s.time_stamp = false;
    auto side = std::make_unique<Gpu>(scene, s);
    for (const Job& job : jobs) drawCloseUps(*side, scene, job.snapshot, job.close_up_prefix);
    side.reset();
    malloc_trim(0);
  }

  void runOffline(std::unique_ptr<Gpu>& gpu) {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return !queue.empty() || closing; });
        if (queue.empty()) break;
        job = std::move(queue.front());
        queue.pop_front();
        changed.notify_all();
      }
      if (job.release) {
        try {
          releaseGpu(gpu);
        } catch (const std::exception& e) {  // the error set before the reply breaks
          fail(e.what());
          throw;
        }
        job.reply.set_value({});
        continue;
      }
      if (job.chart) {
        // A chart comes after the session's last frame: the frames' buffers, layers and
        // programs are given back before it is drawn in a context of its own, so its memory
        // does not add to theirs (docs/performance.md, "Memory").
        releaseGpu(gpu);
        writeChartPng(*job.chart, job.chart_path);
        continue;
      }
      // A new Gpu would not have the released one's overlay history, labels and layers.
      if (!gpu) throw GlError("a frame or close-up was queued after the frames were released (releaseFrames, a chart)");
      if (!job.close_up_prefix.empty()) {
        if (defersCloseUps()) {
          deferred.push_back(std::move(job));
        } else {
          drawSideJob(*gpu, scene, job);
        }
        continue;
      }
      std::vector<sim::SettingsCommand> made = drawFrame(*gpu, job.snapshot);
      if (job.wants_reply) job.reply.set_value(std::move(made));
    }
    releaseGpu(gpu);  // finished without releaseFrames: the deferred close-ups are drawn still
  }

  // Draws each state the haptic thread publishes as it comes: its frame times are the clock, so
  // no frame is lost to a tick of the render thread's own falling just before a publish. A state
  // published within half a period of the last frame (a viewer's input on consecutive steps)
  // waits until then. With the ordered queue every state is drawn, the next at once when drawing
  // fell behind, and those still waiting when the run ends are drawn before the thread stops;
  // otherwise the newest is drawn and the ones it replaced are not.
  void runRealtime(Gpu& gpu) {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / settings.fps));
    auto last_draw = Clock::now() - period;
    bool ending = false;
    for (auto until = Clock::now() + period;;) {
      if (!ending) wake.sleepUntil(until);
      const auto now = Clock::now();
      // Close-ups and charts still come through the queue in realtime runs; they are drawn
      // outside the lock so the haptic thread never waits on a draw. They are looked at every
      // period at least.
      std::deque<Job> side;
      {
        std::lock_guard lock(mutex);
        side.swap(queue);
        ending = closing;
      }
      for (const Job& job : side) drawSideJob(gpu, scene, job);
      const std::size_t waiting = ordered ? ordered->waiting() : (latest.fresh() ? 1 : 0);
      if (ending && (!ordered || waiting == 0)) break;
      if (!ending && waiting > 0 && now < last_draw + period / 2) {
        until = last_draw + period / 2;
        continue;
      }
      until = now + period;
      if (!(ordered ? ordered->update() : latest.update())) continue;
      queue_max = std::max(queue_max, static_cast<long>(waiting));
      if (ending) ++drawn_after_end;
      last_draw = now;
      if (input_published.exchange(false)) ++hurried;
      std::vector<sim::SettingsCommand> made = drawFrame(gpu, ordered ? ordered->front() : latest.front());
      if (realtime_drawn == 0) {  // written only here; read under the lock by waitFirstFrame
        std::lock_guard lock(mutex);
        realtime_drawn = 1;
        changed.notify_all();
      }
      if (made.empty()) continue;
      std::lock_guard lock(command_mutex);
      commands.insert(commands.end(), made.begin(), made.end());
    }
  }

  void run(std::promise<void>& ready) {
    std::unique_ptr<Gpu> gpu;
    pthread_setname_np(pthread_self(), "gf-render");  // for top and perf
    try {
      // Lowered first: the encoders and llvmpipe's workers, started below, inherit it.
      if (settings.background_priority) background_priority = lowerToNice();
      if (!settings.frames_dir.empty()) png = std::make_unique<PngSequenceWriter>(settings.frames_dir);
      if (!settings.video_path.empty()) {
        video = std::make_unique<VideoWriter>(settings.video_path, settings.width, settings.height, settings.fps);
      }
      gpu = std::make_unique<Gpu>(scene, settings);
      gl_description = gpu->context.description();
    } catch (const std::exception& e) {
      ready.set_exception(std::current_exception());
      return;
    }
    ready.set_value();
    try {
      if (settings.realtime) {
        runRealtime(*gpu);
      } else {
        runOffline(gpu);
      }
    } catch (const std::exception& e) {
      fail(e.what());
      try {  // the close-ups kept while the frames went (a full disk) are drawn still
        releaseGpu(gpu);
      } catch (const std::exception& late) {
        std::fprintf(stderr, "[godfinger] close-ups: %s\n", late.what());
      }
    }
    if (gpu) pictures_reused += gpu->pictures_reused;  // realtime
    // Jobs left by a failure: their replies break, so a caller waiting on one throws the error.
    std::lock_guard lock(mutex);
    queue.clear();
  }
};

RenderThread::RenderThread(const sim::SceneDesc& scene, const FrameOutputSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& r = *impl_;
  r.scene = scene;
  r.settings = settings;
  if (settings.realtime && !settings.tap && (!settings.frames_dir.empty() || !settings.video_path.empty())) {
    r.ordered = std::make_unique<SnapshotQueue>(static_cast<std::size_t>(std::ceil(kQueuedSeconds * settings.fps)) + 1);
  }
  if (settings.width < 1 || settings.height < 1 || settings.width > 1920 || settings.height > 1080) {
    throw GlError("frame size must be 1..1920 x 1..1080 pixels");
  }
  keepFreedMemory();
  std::promise<void> ready;
  std::future<void> started = ready.get_future();
  r.thread = std::thread([&r, &ready] { r.run(ready); });
  try {
    started.get();
  } catch (...) {
    r.thread.join();
    throw;
  }
}

RenderThread::~RenderThread() {
  try {
    finish();
  } catch (const std::exception&) {
    // finish() already reported to an owner that called it.
  }
}

std::vector<sim::SettingsCommand> RenderThread::submitFrame(const sim::Snapshot& snapshot, bool wait_for_commands) {
  return impl_->submit([&](Job& job) { job.snapshot = snapshot; }, true, wait_for_commands);
}

void RenderThread::submitCloseUps(const sim::Snapshot& snapshot, const std::string& prefix) {
  impl_->submit([&](Job& job) { job.snapshot = snapshot, job.close_up_prefix = prefix; }, false, false);
}

void RenderThread::releaseFrames() {
  if (!impl_->settings.realtime) impl_->submit([](Job& job) { job.release = true; }, false, true);
}

void RenderThread::submitChart(const ChartSpec& chart, const std::string& path) {
  impl_->submit([&](Job& job) { job.chart = std::make_unique<ChartSpec>(chart), job.chart_path = path; }, false, false);
}

sim::Snapshot* RenderThread::freeSlot() {
  Impl& r = *impl_;
  if (!r.ordered) return &r.latest.back();
  sim::Snapshot* slot = r.ordered->back();
  if (!slot) r.dropped.fetch_add(1, std::memory_order_relaxed);
  return slot;
}

void RenderThread::publishSlot(bool input) {
  Impl& r = *impl_;
  if (input) r.input_published.store(true);
  if (r.ordered) {
    r.ordered->publish();
  } else {
    r.latest.publish();
  }
  r.wake.post();
}

bool RenderThread::waitFirstFrame(double seconds) {
  Impl& r = *impl_;
  std::unique_lock lock(r.mutex);
  return r.changed.wait_for(lock, std::chrono::duration<double>(seconds),
                            [&] { return r.realtime_drawn > 0 || r.closing || !r.error.empty(); }) &&
         r.realtime_drawn > 0;
}

std::vector<sim::SettingsCommand> RenderThread::takeCommands() {
  std::unique_lock lock(impl_->command_mutex, std::try_to_lock);
  std::vector<sim::SettingsCommand> out;
  if (lock.owns_lock() && !impl_->commands.empty()) out.swap(impl_->commands);
  return out;
}

RenderStats RenderThread::finish() {
  Impl& r = *impl_;
  {
    std::lock_guard lock(r.mutex);
    r.closing = true;
    r.changed.notify_all();
    r.wake.post();
  }
  if (r.thread.joinable()) r.thread.join();
  RenderStats stats;
  stats.gl = r.gl_description;
  stats.frame_ms = r.frame_ms;
  stats.pictures_reused = r.pictures_reused;
  stats.hurried = r.hurried;
  stats.dropped = r.dropped.load();
  stats.queue_max = r.queue_max;
  stats.drawn_after_end = r.drawn_after_end;
  stats.background_priority = r.background_priority;
  // Each sink is finished on its own: a PNG folder that fails does not cost the video.
  const auto finishSink = [&](auto& sink, SinkStats& out) {
    if (!sink) return;
    try {
      out = sink->finish();
    } catch (const ImageError& e) {
      if (r.error.empty()) r.error = e.what();
    }
  };
  finishSink(r.png, stats.png);
  finishSink(r.video, stats.video);
  stats.wall_seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
  if (!r.error.empty()) throw GlError(r.error);
  return stats;
}

void renderCloseUps(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, const std::string& prefix,
                    int size_px) {
  FrameOutputSettings settings;
  settings.width = settings.height = size_px;
  settings.close_up_px = size_px;
  Gpu gpu(scene, settings);
  drawCloseUps(gpu, scene, snapshot, prefix);
}

Image renderStill(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, const FrameOutputSettings& settings,
                  const std::vector<sim::Snapshot>& lead_in) {
  Gpu gpu(scene, settings);
  for (const sim::Snapshot& s : lead_in) {
    if (gpu.overlay) gpu.overlay->record(s);
  }
  gpu.drawScene(snapshot, settings.camera, settings.width, settings.height);
  if (gpu.overlay) gpu.overlay->draw(snapshot, {});
  Image image;
  gpu.frame.read(image);
  return image;
}

}  // namespace gf::render

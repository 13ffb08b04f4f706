// The render thread: the only owner of OSMesa, GL, ImGui and the frame encoders. The haptic
// thread hands it immutable Snapshots; offline through a short queue (every frame drawn, in
// order), realtime through a triple buffer (the latest state) or, for frames written to files
// with no viewer, a queue (every state, in order); neither ever blocks the haptic thread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/scene/camera.hpp"
#include "render/chart/chart.hpp"
#include "render/chart/chart_file.hpp"  // writeChartPng
#include "render/frames/frame_sinks.hpp"
#include "render/overlay/overlay.hpp"
#include "render/overlay/patch_insets.hpp"
#include "render/scene/scene_renderer.hpp"
#include "sim/scene/settings.hpp"
#include "sim/scene/snapshot.hpp"

namespace gf::render {

/// Realtime frames written to files with no viewer: how many seconds of published states may
/// wait to be drawn (a stretch of frames dearer than a period is drawn late, not lost).
inline constexpr double kQueuedSeconds = 6.0;

/// Receives every frame of the stream as it is drawn, with the Snapshot it shows (a browser
/// view, app/serve/). Called on the render thread right after the read-back: keep it short
/// (copy what is needed and return); it must not throw.
class FrameTap {
 public:
  virtual ~FrameTap() = default;
  virtual void frame(const Image& image, const sim::Snapshot& snapshot, float frame_ms) noexcept = 0;
};

/// What the render thread draws and where it writes it.
struct FrameOutputSettings {
  int width = 1280;               ///< pixels (1..1920 wide, 1..1080 high)
  int height = 720;
  view::Antialiasing antialiasing = view::Antialiasing::kFxaa;
  int msaa_samples = 4;           ///< with view::Antialiasing::kMsaa (2..8)
  double fps = 60.0;              ///< frame rate of the outputs (frames per simulated second)
  view::Camera camera;                  ///< the camera of the frame stream
  std::string frames_dir;         ///< PNG sequence folder; empty: none
  std::string video_path;         ///< MP4 file; empty: none
  RenderSettings scene;           ///< drawing switches (effects)
  bool patch_insets = false;      ///< the patch_insets effect (render/overlay/patch_insets.hpp)
  bool overlay = false;           ///< the ImGui overlay effect
  bool time_stamp = true;         ///< the time (and arrow scale) in the frame's corner; the overlay's panel shows them instead
  /// Something is drawn over the frame's top-left corner (a comparison's panel label): the
  /// insets and the stamp keep out of it.
  bool top_left_taken = false;
  OverlaySettings overlay_settings;
  int close_up_px = 480;          ///< side of contact close-up images (pixels)
  /// Offline with frames: close-ups are drawn once the frames' GL memory is given back
  /// (RenderThread::releaseFrames), in a context sized for them, so they add nothing to the
  /// frames' memory (docs/performance.md, "Memory"). False: each is drawn when it comes, among
  /// the frames, as realtime runs always do.
  bool close_ups_after_frames = true;
  /// Draw the states the haptic thread publishes as they come (publishLatest), not frames queued
  /// by submitFrame.
  bool realtime = false;
  /// Run the render thread, its encoders and llvmpipe's workers (made with the context, after
  /// the thread lowered itself) at nice kBackgroundNice: a realtime haptic loop at nice 0 without
  /// root wins the cores when it wakes, and the frames still get what it leaves.
  bool background_priority = false;
  FrameTap* tap = nullptr;        ///< also hands each frame of the stream here (not owned)
};

/// What the render thread did.
struct RenderStats {
  std::vector<float> frame_ms;    ///< draw + overlay + read-back of each frame drawn (ms)
  long hurried = 0;               ///< realtime frames that showed a viewer's input (publishLatest)
  /// Realtime frames written to files with no viewer are drawn in order, every state published
  /// (kQueuedSeconds of them may wait): states dropped because the queue was full, the most that
  /// waited when one was taken, and the frames drawn after finish() (the run had ended).
  long dropped = 0;
  long queue_max = 0;
  long drawn_after_end = 0;
  /// Frames whose scene picture was the one before's, not drawn again (only their labels and
  /// overlay were): nothing had moved (render/state/same_picture.hpp).
  long pictures_reused = 0;
  double wall_seconds = 0.0;      ///< from start to finish()
  SinkStats png, video;
  std::string gl;                 ///< GL version and renderer
  bool background_priority = false;  ///< it ran at nice kBackgroundNice
};

class RenderThread {
 public:
  /// Starts the thread and its GL context. Throws GlError (or sim::MeshLoadError) when it
  /// cannot render the scene, ImageError when an output cannot be opened.
  RenderThread(const sim::SceneDesc& scene, const FrameOutputSettings& settings);
  ~RenderThread();
  RenderThread(const RenderThread&) = delete;
  RenderThread& operator=(const RenderThread&) = delete;

  /// Offline: queues the frame of `snapshot` (blocks while two frames wait). With
  /// `wait_for_commands`, waits until it is drawn and returns the overlay's settings changes,
  /// so scripted input lands on the same haptic step in every run. Throws the thread's error.
  std::vector<sim::SettingsCommand> submitFrame(const sim::Snapshot& snapshot, bool wait_for_commands);
  /// Queues close-ups of every contact in `snapshot`, written as `<prefix>-<finger>.png`. An
  /// offline run with frames draws them when the frames' GL memory is given back (releaseFrames,
  /// a chart, finish()); the scene's switches are the run's (only patch settings change live).
  void submitCloseUps(const sim::Snapshot& snapshot, const std::string& prefix);
  /// Queues a chart, written as the PNG `path` and as SVG beside it (`path` with .svg for .png).
  void submitChart(const ChartSpec& chart, const std::string& path);
  /// Offline: waits until the queued frames are drawn, gives back the frames' GL buffers, layers
  /// and programs, so that what the caller runs next (the force chart's god-object rerun) takes
  /// their memory instead of adding to it, and draws the close-ups kept until then. No frame or
  /// close-up may follow; a chart may. Realtime: returns at once. Throws the thread's error.
  void releaseFrames();
  /// Realtime: `fill(snapshot)` writes the latest state into the free slot of the triple
  /// buffer, which is then handed to the render thread and wakes it: it draws the newest state
  /// at once, or half a period after its last frame if that is later (so input published on
  /// consecutive steps is one frame). `input`: the state shows a viewer's input (a move from the
  /// browser view; counted as `hurried`). The slot is the caller's only inside `fill`. Never
  /// blocks: an atomic exchange and a semaphore post (an atomic add, a futex wake when the
  /// thread sleeps); does not allocate once the slots have grown. Haptic thread only (one
  /// publishing thread).
  template <class Fill>
  void publishLatest(Fill&& fill, bool input = false) {
    if (sim::Snapshot* slot = freeSlot()) {
      fill(*slot);
      publishSlot(input);
    }
  }
  /// Realtime: waits (at most `seconds`) until the first state published is drawn, so that a
  /// loop started afterwards does not fall behind while the first frame compiles llvmpipe's
  /// shaders (0.7 s at 1280×720 here). False when it was not (the time ran out, an error).
  bool waitFirstFrame(double seconds);
  /// Realtime: settings changes made in the overlay since the last call; never blocks.
  std::vector<sim::SettingsCommand> takeCommands();
  /// Draws what is queued, stops the thread and the encoders, rethrows the first error.
  RenderStats finish();

 private:
  sim::Snapshot* freeSlot();  // null: the ordered queue is full (the state is dropped)
  void publishSlot(bool input);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Keeps the memory a renderer frees in the process (glibc: one malloc arena for all threads,
/// freed memory kept up to 256 MB, blocks under 32 MB from the heap), so frames stop giving pages
/// back and faulting them in again: each page fault costs CPU, and on a virtual machine can stall
/// the other CPU's timers (a 1 kHz loop woken late). Every RenderThread calls it; a program that
/// draws should call it first thing in main(), before it starts threads, as `godfinger` does:
/// threads that already have an arena of their own keep it. Process-wide, idempotent; any thread.
void keepFreedMemory();

/// Lowers the calling thread (only it) to nice kBackgroundNice; threads it starts afterwards
/// inherit it. Whether it now runs at kBackgroundNice or nicer (render/render_process.cpp).
bool lowerToNice();

/// Close-up file of finger `finger` (its scene name) for a snapshot written under `prefix`.
std::string closeUpPath(const std::string& prefix, const std::string& finger);

/// Draws close-ups of every contact of `snapshot` on the calling thread (which becomes the
/// render thread for its duration: it makes and destroys its own GL context). For commands
/// without a haptic loop, such as `godfinger patch`.
void renderCloseUps(const sim::SceneDesc& scene, const sim::Snapshot& snapshot,
                    const std::string& prefix, int size_px);

/// Draws one frame of `snapshot` as `settings` ask (size, camera, effects, overlay) on the
/// calling thread, with a GL context of its own: stills and visual-regression images.
/// `lead_in`: the snapshots of the frames a run would have drawn before it (oldest first), whose
/// forces the overlay's plot shows.
Image renderStill(const sim::SceneDesc& scene, const sim::Snapshot& snapshot, const FrameOutputSettings& settings,
                  const std::vector<sim::Snapshot>& lead_in = {});

}  // namespace gf::render

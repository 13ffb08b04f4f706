// What the browser view shows of a running session: the render thread hands it every frame of
// the stream (render::FrameTap), and it keeps the newest Snapshot, the newest JPEG (encoded on
// a thread of its own, only while someone watches) and, while recording, the frames as PNGs.
// The HTTP server reads it; the haptic thread never touches it.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include "app/scene/session_desc.hpp"
#include "render/frames/frame_sinks.hpp"
#include "render/frames/jpeg_stream.hpp"
#include "render/render_thread.hpp"

namespace gf::app {

class LiveView final : public render::FrameTap {
 public:
  /// `mode`: "realtime" (a `run --realtime`) or "live" (`godfinger live`, stepped on command).
  /// Recordings go to out_dir/frames/. `background`: the JPEG encoder runs at nice 10.
  LiveView(const SessionDesc& session, const view::Camera& camera, std::string mode, std::string out_dir, bool background);
  ~LiveView() override;

  /// Render thread: keeps the snapshot, hands the image to the JPEG encoder and the recording.
  void frame(const render::Image& image, const sim::Snapshot& snapshot, float frame_ms) noexcept override;

  render::JpegStream& jpeg() { return jpeg_; }
  /// The newest snapshot drawn into `out` (and its frame's number, as on the stream, into
  /// `frame`); false before the first frame. Any thread.
  bool latest(sim::Snapshot& out, long* frame = nullptr) const;
  /// /state.json: the `state` answer's JSON of the newest snapshot drawn, with its frame's
  /// number (`frame`), the device links (`devices`) and statsJson() (`view`); "{}" before the
  /// first frame. Any thread.
  std::string stateText() const;
  /// What the page needs once: the scene's name, mode, frame size, camera, fingers (name,
  /// colour, web or not), bodies and the live settings' widgets (render/view/view_desc.hpp). Any thread.
  const nlohmann::json& sceneJson() const { return scene_json_; }
  /// Makes this an experiment participant's view (before the server starts): /scene.json holds
  /// only the scene's name, the frame size, the camera, the fingers' names, colours and devices,
  /// and `participant` (the panel); /state.json only the time, the bodies' poses and each
  /// finger's proxy, device and force (participantState): nothing names the condition.
  void setParticipant(const nlohmann::json& panel);
  bool participant() const { return participant_; }
  /// A `state` answer's JSON cut down to what a participant's page may see, as text.
  static std::string participantState(const nlohmann::json& state);
  /// Frames drawn, the JPEG encoder's counts, the recording. Any thread.
  nlohmann::json statsJson() const;
  /// A provider of the device links' state (packets, stale, ramp) for /state.json. Any thread.
  void setDeviceState(std::function<nlohmann::json()> devices);
  nlohmann::json deviceState() const;

  /// `record start` / `record stop`: the answer ("ok ..."). Frames of the stream from then on
  /// go to out_dir/frames/NNNNNN.png, numbered on across recordings. Throws std::runtime_error
  /// when the folder cannot be made. Any thread.
  std::string record(bool on);
  /// Waits until a frame of haptic step `step` or later has been drawn and handed to the JPEG
  /// encoder, or `within` passes; false then. Any thread but the render thread.
  bool waitDrawn(long step, std::chrono::milliseconds within);
  /// Stops the encoder and finishes the recording (rethrows a PNG writer's error).
  void finish();

 private:
  const sim::SceneDesc& scene_;
  const std::string out_dir_;
  nlohmann::json scene_json_;
  bool participant_ = false;
  render::JpegStream jpeg_;
  std::function<nlohmann::json()> devices_;
  mutable std::mutex mutex_;
  std::condition_variable drawn_;
  long drawn_step_ = -1;  // the step of the newest frame handed to the encoder
  sim::Snapshot latest_;
  bool has_latest_ = false;
  long frames_ = 0;
  double frame_ms_sum_ = 0.0;
  std::shared_ptr<render::PngSequenceWriter> recorder_;  // pushed to outside the lock
  bool recording_ = false;
  long recorded_ = 0;
};

}  // namespace gf::app

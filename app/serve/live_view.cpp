#include "app/serve/live_view.hpp"

#include <filesystem>

#include "app/runs/run_folder.hpp"
#include "app/live/live_command.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/draw_list.hpp"

namespace gf::app {
namespace {

nlohmann::json vec(const sim::Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

// The live settings' controls, from the overlay's widget table: what each spans and shows.
nlohmann::json widgetsJson() {
  nlohmann::json out = nlohmann::json::array();
  for (const view::OverlayWidget& w : view::kOverlayWidgets) {
    nlohmann::json j = {{"field", w.field}, {"label", w.label}, {"lo", w.lo}, {"hi", w.hi},
                        {"shown_per_unit", w.shown_per_unit}};
    if (const sim::Setting<sim::FingerDesc>* s = sim::findSetting(sim::fingerSettings(), w.field)) {
      j["key"] = sim::jsonKey(*s);
      j["integer"] = s->kind == sim::SettingKind::kInteger;
    }
    out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json describeScene(const SessionDesc& session, const view::Camera& camera, const std::string& mode) {
  const sim::SceneDesc& scene = session.scene;
  nlohmann::json fingers = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.fingers.size(); ++i) {
    const Eigen::Vector3f c = render::fingerColour(static_cast<int>(i));
    bool web = false, udp = false;
    for (const WebDeviceDesc& d : session.web_devices) web = web || d.finger == static_cast<int>(i);
    for (const UdpDeviceDesc& d : session.udp_devices) udp = udp || d.finger == static_cast<int>(i);
    fingers.push_back({{"name", scene.fingers[i].name},
                       {"colour", {c.x(), c.y(), c.z()}},
                       {"device", web ? "web" : udp ? "udp" : "track"},
                       {"proxy_radius_m", scene.fingers[i].proxy.radius},
                       {"max_force_n", scene.fingers[i].coupling.max_force}});
  }
  nlohmann::json bodies = nlohmann::json::array();
  for (const sim::BodyDesc& b : scene.bodies) bodies.push_back({{"name", b.name}, {"dynamic", b.mass > 0.0}});
  const sim::Vec3 up = render::upFor(camera.target - camera.position);
  return {{"scene", scene.name},
          {"mode", mode},
          {"duration_s", scene.duration},
          {"haptic_rate_hz", scene.world.haptic_rate_hz},
          {"width", session.view.width},
          {"height", session.view.height},
          {"camera", {{"name", camera.name}, {"position", vec(camera.position)}, {"target", vec(camera.target)},
                      {"up", vec(up)}, {"fov_deg", camera.fov_deg}}},
          {"fingers", fingers},
          {"bodies", bodies},
          {"widgets", widgetsJson()}};
}

}  // namespace

LiveView::LiveView(const SessionDesc& session, const view::Camera& camera, std::string mode, std::string out_dir,
                   bool background)
    : scene_(session.scene), out_dir_(std::move(out_dir)), scene_json_(describeScene(session, camera, mode)), jpeg_(80, background) {}

LiveView::~LiveView() {
  try {
    finish();
  } catch (const std::exception&) {
    // finish() reported to an owner that called it
  }
}

void LiveView::frame(const render::Image& image, const sim::Snapshot& snapshot, float frame_ms) noexcept {
  try {
    long number = 0;
    std::shared_ptr<render::PngSequenceWriter> recorder;
    {
      std::lock_guard lock(mutex_);
      latest_ = snapshot;
      has_latest_ = true;
      number = ++frames_;
      frame_ms_sum_ += frame_ms;
      if (recording_) recorder = recorder_;
    }
    jpeg_.push(image, number, snapshot.time, snapshot.moves_taken, snapshot.moves_arrived);
    {
      std::lock_guard lock(mutex_);
      drawn_step_ = snapshot.step;
    }
    drawn_.notify_all();
    if (recorder) {  // outside the lock: push waits while the writer's queue is full
      render::Image copy = recorder->spare();
      copy.width = image.width;
      copy.height = image.height;
      copy.rgb.assign(image.rgb.begin(), image.rgb.end());
      recorder->push(std::move(copy));
      std::lock_guard lock(mutex_);
      ++recorded_;
    }
  } catch (const std::exception&) {
    std::lock_guard lock(mutex_);
    recording_ = false;  // a recording that fails stops; finish() reports why
  }
}

bool LiveView::waitDrawn(long step, std::chrono::milliseconds within) {
  std::unique_lock lock(mutex_);
  return drawn_.wait_for(lock, within, [&] { return drawn_step_ >= step; });
}

bool LiveView::latest(sim::Snapshot& out, long* frame) const {
  std::lock_guard lock(mutex_);
  if (has_latest_) out = latest_;
  if (frame) *frame = frames_;
  return has_latest_;
}

void LiveView::setDeviceState(std::function<nlohmann::json()> devices) {
  std::lock_guard lock(mutex_);
  devices_ = std::move(devices);
}

nlohmann::json LiveView::deviceState() const {
  std::lock_guard lock(mutex_);
  return devices_ ? devices_() : nlohmann::json::array();
}

void LiveView::setParticipant(const nlohmann::json& panel) {
  participant_ = true;
  // What the participant's page needs, nothing more: a setting a factor varies must not reach it.
  nlohmann::json fingers = nlohmann::json::array();
  for (const nlohmann::json& f : scene_json_["fingers"]) {
    fingers.push_back({{"name", f["name"]}, {"colour", f["colour"]}, {"device", f["device"]}});
  }
  scene_json_ = {{"scene", scene_json_["scene"]}, {"mode", scene_json_["mode"]},     {"width", scene_json_["width"]},
                 {"height", scene_json_["height"]}, {"camera", scene_json_["camera"]}, {"fingers", fingers},
                 {"participant", panel}};
}

std::string LiveView::participantState(const nlohmann::json& state) {
  nlohmann::json fingers = nlohmann::json::array();
  for (const nlohmann::json& f : state["fingers"]) {
    fingers.push_back({{"name", f["name"]}, {"proxy", f["proxy"]}, {"device", f["device"]}, {"force_n", f["force_n"]}});
  }
  nlohmann::json out = {{"t", state["t"]}, {"step", state["step"]}, {"bodies", state["bodies"]}, {"fingers", fingers}};
  if (state.contains("frame")) out["frame"] = state["frame"];
  return out.dump();
}

std::string LiveView::stateText() const {
  sim::Snapshot snap;
  long frame = 0;
  if (!latest(snap, &frame)) return "{}";
  nlohmann::json j = stateJson(snap, scene_);
  j["frame"] = frame;
  if (participant_) return participantState(j);
  j["devices"] = deviceState();
  j["view"] = statsJson();
  return j.dump();
}

nlohmann::json LiveView::statsJson() const {
  const render::JpegStats j = jpeg_.stats();
  std::lock_guard lock(mutex_);
  return {{"frames_drawn", frames_},
          {"frame_ms_mean", frames_ > 0 ? frame_ms_sum_ / static_cast<double>(frames_) : 0.0},
          {"jpeg_encoded", j.encoded},
          {"jpeg_ms_mean", j.encoded > 0 ? 1e3 * j.encode_seconds / static_cast<double>(j.encoded) : 0.0},
          {"jpeg_bytes_mean", j.encoded > 0 ? j.bytes / j.encoded : 0},
          {"recording", recording_},
          {"frames_recorded", recorded_}};
}

std::string LiveView::record(bool on) {
  const std::string folder = (std::filesystem::path(out_dir_) / kFramesFolder).string();
  std::lock_guard lock(mutex_);
  // Three frames of slack for the encoder beside the realtime loop and the stream.
  if (on && !recorder_) recorder_ = std::make_shared<render::PngSequenceWriter>(folder, 3);
  recording_ = on && recorder_;
  if (on) return "ok recording frames to " + folder + "/ (" + std::to_string(recorded_) + " so far)";
  return "ok recording stopped: " + std::to_string(recorded_) + " frames in " + folder + "/";
}

void LiveView::finish() {
  jpeg_.close();
  std::shared_ptr<render::PngSequenceWriter> recorder;
  {
    std::lock_guard lock(mutex_);
    recording_ = false;
    recorder.swap(recorder_);
  }
  if (recorder) recorder->finish();  // a frame() holding it meanwhile gets the writer's error
}

}  // namespace gf::app

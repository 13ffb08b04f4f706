// A realtime run watched and steered from a browser (`run --realtime --serve`): the LiveView the
// render thread feeds, the HTTP server, and the `live` commands it takes. Commands are checked
// on the server's threads; moves reach the haptic thread through each finger's SteeredDevice
// and settings through a queue it drains without waiting.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "app/serve/live_view.hpp"
#include "app/device/steered_device.hpp"
#include "app/serve/web_server.hpp"
#include "sim/world/world.hpp"

namespace gf::app {

class ServedRun {
 public:
  /// Binds the server now (throws when it cannot, before anything is written). `camera`: the
  /// frame stream's. `background`: the JPEG encoder at nice 10.
  ServedRun(const SessionDesc& session, const ServeOptions& options, const view::Camera& camera,
            const std::string& out_dir, bool background);
  ~ServedRun();
  ServedRun(const ServedRun&) = delete;
  ServedRun& operator=(const ServedRun&) = delete;

  render::FrameTap* tap() { return &view_; }
  const WebServer& server() const { return *server_; }
  /// The haptic loop's sources, one per finger: `udp`'s where it has one (may be empty), a
  /// SteeredDevice otherwise.
  std::span<sim::DeviceSource* const> sources(std::span<sim::DeviceSource* const> udp);
  /// A provider of the UDP links' state for /state.json (set before the loop).
  void setDeviceState(std::function<nlohmann::json()> devices) { view_.setDeviceState(std::move(devices)); }
  /// Haptic thread, after each step: applies the settings posted since (never waits; allocates
  /// only when there is one). The page's settings are the base of its next `set`: changes made
  /// meanwhile by a scene's `[[changes]]` or the overlay are not merged into them. Returns
  /// whether the step took the page's input: a move (its finger's device sampled it, or it
  /// reached its target) or settings, which the frames should show at once.
  bool afterStep(sim::World& world);
  /// Haptic thread, with the state the frames show: its moveMarks (Snapshot::moves_taken,
  /// moves_arrived), which the stream's parts carry to the page.
  void markMoves(sim::Snapshot& snapshot) const;
  /// Stops the server and the recording; returns what they did, for summary.json.
  nlohmann::json finish();

 private:
  std::string answer(const std::string& line);

  const SessionDesc& session_;
  const std::string out_dir_;
  LiveView view_;
  std::vector<std::unique_ptr<SteeredDevice>> devices_;
  std::vector<sim::DeviceSource*> sources_;
  std::vector<bool> udp_;  // finger i follows a UDP device
  std::mutex mutex_;       // the settings below and the queue
  std::vector<sim::PatchSettings> settings_;  // each finger's, as the page last set them
  std::vector<sim::SettingsCommand> posted_, taking_;
  std::atomic<bool> has_posted_{false};
  std::atomic<long> settings_applied_{0}, settings_refused_{0};
  long moves_seen_ = 0;  // haptic thread: the devices' moves taken and arrived, as of the last step
  std::atomic<long> moves_numbered_{0};  // the last number given to a move (server thread)
  bool participant_ = false;  // an experiment participant's page: no set, record or snapshot
  std::function<std::optional<std::string>(const std::string&)> participant_command_;
  std::unique_ptr<WebServer> server_;  // started last, stopped first
};

}  // namespace gf::app

// The serve tests' fixture: a LiveView of live-view fed frames by a thread standing in for the
// render thread, and a server in front of it on loopback.
#pragma once

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app/scene/data_folder.hpp"
#include "app/scene/scene_file.hpp"
#include "app/serve/live_view.hpp"
#include "app/serve/web_server.hpp"
#include "app/session/session.hpp"
#include "tests/scratch.hpp"

namespace gf::app::served {

// A LiveView of live-view fed frames (a flat grey changing each time) by a thread standing in for
// the render thread, as fast as it goes, until it is destroyed.
class FedView {
 public:
  explicit FedView(const std::string& out) : session_(loadSceneFile(resolveScenePath("live-view"))),
        view_(session_, sessionCamera(session_, ""), "realtime", out, false) {
    feeder_ = std::thread([this] {
      render::Image image{64, 36, std::vector<std::uint8_t>(64 * 36 * 3)};
      sim::Snapshot snap;
      for (int k = 0; !stop_.load(); ++k) {
        std::fill(image.rgb.begin(), image.rgb.end(), static_cast<std::uint8_t>(k));
        snap.time = 0.001 * k;
        snap.step = k;
        view_.frame(image, snap, 1.0f);
        std::this_thread::yield();
      }
    });
  }
  ~FedView() {
    stop_.store(true);
    feeder_.join();
  }
  LiveView& view() { return view_; }
  const SessionDesc& session() const { return session_; }

 private:
  SessionDesc session_;
  LiveView view_;
  std::atomic<bool> stop_{false};
  std::thread feeder_;
};

// A server on `host`:0 in front of `view`: commands echoed as "ok LINE".
inline std::unique_ptr<WebServer> serve(LiveView& view, const std::string& host, const std::string& token = "",
                                        const HttpLimits& limits = {}) {
  ServeOptions o;
  o.host = host;
  o.token = token;
  o.limits = limits;
  return std::make_unique<WebServer>(o, view, [](const std::string& line) { return "ok " + line; });
}

inline int portOf(const WebServer& server) {
  const std::string url = server.url();
  return std::stoi(url.substr(url.rfind(':') + 1));
}

inline std::string out(const std::string& name) {
  const std::filesystem::path dir = gf::test::scratchRoot() / name;
  std::filesystem::remove_all(dir);
  return dir.string();
}

}  // namespace gf::app::served

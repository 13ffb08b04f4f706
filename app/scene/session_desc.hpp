// What a scene file describes beyond the physics: recordings and cameras. Read-only once loaded.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "app/scene/expect_desc.hpp"
#include "sim/scene/scene_desc.hpp"
#include "render/view/view_desc.hpp"

namespace gf::app {

/// Hz: the lowest record.trace_rate (a row a minute).
inline constexpr double kMinTraceRateHz = 1.0 / 60.0;

/// What a session writes besides summary.json.
struct RecordSettings {
  bool trace = true;                         ///< trace.csv, one row per haptic step
  /// Hz: trace.csv rows a second of simulated time, a row every haptic_rate_hz / trace_rate
  /// steps (a whole number); 0 (the default): every haptic step.
  double trace_rate = 0.0;
  std::vector<double> contact_times;         ///< s: contacts/t<time>.json at these times
  std::vector<std::string> force_bodies;     ///< forces.csv: non-gravity force on these bodies
  /// forces.png: the y force on the first force body against time, this scene with god-fingers
  /// and again with every finger a god-object (the paper's Fig. 8)
  bool force_chart = false;
  /// The chart's title; empty: "<scene name>: y force on <body> (N, gravity removed)".
  std::string force_chart_title;
};

/// How the scene is drawn: the render effects and the [render] table.
struct ViewSettings {
  bool patch_highlight = false;  ///< effect: contact patches, SGOs, normals, force arrows
  bool shadows = false;          ///< effect: soft shadows from the key light
  bool patch_insets = false;     ///< effect: a close-up of each finger's patch in a corner of each frame
  bool overlay = false;          ///< effect: the ImGui overlay
  bool load_arrows = false;      ///< [render]: each point's normal load and friction drawn as arrows
  bool reserve_top_left = false; ///< [render]: the insets and time stamp keep out of the top-left corner
  int width = 1280;              ///< frame size (pixels, up to 1920 x 1080)
  int height = 720;
  view::Antialiasing antialiasing = view::Antialiasing::kFxaa;
  int msaa_samples = 4;          ///< samples with antialiasing = "msaa" (2..8)
  std::vector<view::WidgetAction> actions;  ///< scripted overlay input, by time
  view::BodyPattern body_pattern = view::BodyPattern::kStripes;  ///< rigid bodies striped in their own frames
  view::ProxyLook proxy = view::ProxyLook::kSphere;              ///< proxies as spheres or fingertips
};

/// A finger driven by a live device over UDP (docs/device-protocol.md); its sim track holds
/// the device at `start`, where the proxy starts and stays until the first packet.
struct UdpDeviceDesc {
  int finger = 0;                      ///< index into scene.fingers
  std::string host = "127.0.0.1";      ///< IPv4 address bound (loopback unless the scene says)
  int port = 0;                        ///< UDP port (0: any free port, printed at the start)
  int channel = 0;                     ///< packets' channel field for this finger (0..255)
  double workspace_scale = 1.0;        ///< scene m per device m
  sim::Vec3 workspace_offset = sim::Vec3::Zero();  ///< m: scene position of the device's origin
  sim::Vec3 start = sim::Vec3::Zero();  ///< m: scene position held until the first packet
  double force_scale = 1.0;            ///< device N per scene N of the force sent back
  double stale_after = 0.05;           ///< s without a packet before the device is stale
  double force_ramp = 0.1;             ///< s for the force sent back to ramp from 0 to full (or back)
  /// s: from this simulated time on the force sent back fades to zero at the ramp's rate and stays
  /// there (flag kEnding), so a run that ends leaves no device pushing. Not a scene field: an
  /// experiment's trial sets it to its time limit and runs force_ramp longer; any other run's
  /// devices fade after its last step (UdpDeviceBridge::endRun).
  double fade_out_at = HUGE_VAL;
  /// s: time constant of the low-pass filter on the velocity from successive packets (0: raw
  /// differences); the coupling damps on it.
  double velocity_smoothing = 0.005;
  /// The device table's tilt (`tilt_deg` about `tilt_axis`, device frame): follows every
  /// orientation the device sends (q * tilt).
  sim::Quat tilt = sim::Quat::Identity();
  std::string file;                    ///< where `udp` was given (the scene file, or a --set), for errors
  int line = 0, column = 0;
};

/// A finger whose device is the browser view's pointer (`[fingers.NAME.device] web = true`): its
/// sim track holds the device at `start` until the page moves it (app/serve/).
struct WebDeviceDesc {
  int finger = 0;        ///< index into scene.fingers
  std::string file;      ///< where `web` was given, for errors
  int line = 0, column = 0;
};

/// A loaded scene file: the physics description plus what to record and how to look at it.
struct SessionDesc {
  sim::SceneDesc scene;
  std::string summary;       ///< one line for `godfinger list`
  std::string source;        ///< the file it came from ("" for scenes made in code)
  std::vector<std::string> overrides;  ///< the --set FIELD=VALUE applied, in order
  RecordSettings record;
  ExpectDesc expect;  ///< [expect]: what the run must show
  ViewSettings view;
  std::vector<view::Camera> cameras;  ///< [cameras.NAME]: one is rendered per output stream
  /// [targets.NAME]: where a task wants a body (a ghost pose, a zone), drawn in the frames
  std::vector<view::Target> targets;
  std::vector<UdpDeviceDesc> udp_devices;  ///< fingers with a live UDP device
  std::vector<WebDeviceDesc> web_devices;  ///< fingers the browser view's pointer drives
};

}  // namespace gf::app

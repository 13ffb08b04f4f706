// The scene fields of a `udp` device (docs/device-protocol.md): their defaults and each bad value
// named, the ports and channels in use, and the runs that cannot take a live device. The
// protocol and the device link are tests/app/device/device_test.cpp.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "app/session/live.hpp"
#include "app/session/session.hpp"
#include "app/device/udp_device.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

const std::string kUdpScene = R"(name = "udp"
duration = 0.2
effects = ["gravity", "friction", "god_finger", "force_feedback"]
[bodies.ground]
shape = "plane"
[fingers.a]
n_sgo = 8
[fingers.a.device]
udp = "127.0.0.1:0"
start = [0, 0.05, 0]
[fingers.b]
n_sgo = 8
[fingers.b.device]
udp = "127.0.0.1:0"
channel = 1
start = [0.1, 0.05, 0]
)";

std::string withDevice(const std::string& fields) {
  std::string s = kUdpScene;
  const std::string from = "udp = \"127.0.0.1:0\"\nstart = [0, 0.05, 0]";
  return s.replace(s.find(from), from.size(), fields);
}

InputError sceneError(const std::string& text) {
  try {
    parseSceneText(text, "scene.toml", "");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return InputError("", 0, 0, "", "");
}

// The scene's `udp` device: its fields with their defaults, and each bad value named.
TEST(UdpDeviceScene, FieldsAreReadAndBadOnesNamed) {
  const SessionDesc s = parseSceneText(withDevice(R"(udp = 47011
workspace_scale = 0.5
workspace_offset = [0, 0.1, 0]
force_scale = 0.25
stale_after = 0.02
force_ramp = 0.2
velocity_smoothing = 0)"), "scene.toml", "");
  ASSERT_EQ(s.udp_devices.size(), 2u);
  const UdpDeviceDesc& a = s.udp_devices[0];
  EXPECT_EQ(a.finger, 0);
  EXPECT_EQ(a.host, "127.0.0.1");  // a bare port listens on loopback
  EXPECT_EQ(a.port, 47011);
  EXPECT_EQ(a.channel, 0);
  EXPECT_EQ(a.workspace_scale, 0.5);
  EXPECT_EQ(a.start, Vec3(0.0, 0.1, 0.0));  // the offset, when no start is given
  EXPECT_EQ(a.force_scale, 0.25);
  EXPECT_EQ(a.stale_after, 0.02);
  EXPECT_EQ(a.force_ramp, 0.2);
  EXPECT_EQ(a.velocity_smoothing, 0.0);
  EXPECT_EQ(a.line, 9);
  EXPECT_EQ(s.scene.fingers[0].device.sample(5.0).position, Vec3(0.0, 0.1, 0.0));  // held at start
  const UdpDeviceDesc& b = s.udp_devices[1];
  EXPECT_EQ(b.finger, 1);
  EXPECT_EQ(b.channel, 1);
  EXPECT_EQ(b.stale_after, 0.05);
  EXPECT_EQ(parseSceneText(withDevice("udp = \"localhost:5\""), "s", "").udp_devices[0].host, "127.0.0.1");
  EXPECT_EQ(parseSceneText(withDevice("udp = \"0.0.0.0:5\""), "s", "").udp_devices[0].host, "0.0.0.0");

  const auto field = [](const std::string& fields) { return sceneError(withDevice(fields)); };
  EXPECT_EQ(field("udp = \"example.org:5\"").field(), "fingers.a.device.udp");
  EXPECT_NE(std::string(field("udp = \"example.org:5\"").what()).find("not an IPv4 address"), std::string::npos);
  EXPECT_EQ(field("udp = \"127.0.0.1:70000\"").field(), "fingers.a.device.udp");
  EXPECT_EQ(field("udp = \"127.0.0.1\"").field(), "fingers.a.device.udp");
  EXPECT_EQ(field("udp = -1").field(), "fingers.a.device.udp");
  EXPECT_EQ(field("udp = 1.5").field(), "fingers.a.device.udp");
  EXPECT_EQ(field("udp = 5\nchannel = 256").field(), "fingers.a.device.channel");
  EXPECT_EQ(field("udp = 5\nworkspace_scale = 0").field(), "fingers.a.device.workspace_scale");
  EXPECT_EQ(field("udp = 5\nworkspace_offset = [2000, 0, 0]").field(), "fingers.a.device.workspace_offset");
  EXPECT_EQ(field("udp = 5\nstart = [0, -1001, 0]").field(), "fingers.a.device.start");
  EXPECT_EQ(field("udp = 5\nforce_scale = -1").field(), "fingers.a.device.force_scale");
  EXPECT_EQ(field("udp = 5\nstale_after = 0.001").field(), "fingers.a.device.stale_after");
  EXPECT_EQ(field("udp = 5\nforce_ramp = 0").field(), "fingers.a.device.force_ramp");
  EXPECT_EQ(field("udp = 5\nvelocity_smoothing = 1").field(), "fingers.a.device.velocity_smoothing");
  EXPECT_EQ(field("udp = 5\ninterpolation = \"linear\"").field(), "fingers.a.device.interpolation");
  const InputError both = field("udp = 5\nkeyframes = [ { t = 0.0, p = [0, 0.1, 0] } ]");
  EXPECT_NE(std::string(both.what()).find("exactly one of keyframes, csv, udp and web"), std::string::npos) << both.what();
  const InputError stray = field("keyframes = [ { t = 0.0, p = [0, 0.1, 0] } ]\nchannel = 2");
  EXPECT_EQ(stray.field(), "fingers.a.device.channel");
  EXPECT_NE(std::string(stray.what()).find("belongs to a UDP device"), std::string::npos) << stray.what();
}

// Two fingers on one socket must read different channels; a port another program holds is
// named with the scene line.
TEST(UdpDeviceScene, ChannelsAndPortsInUseAreErrorsNamingTheField) {
  std::string same = kUdpScene;
  same.replace(same.find("channel = 1"), 11, "channel = 0");
  const SessionDesc s = parseSceneText(same, "same.toml", "");
  try {
    UdpDeviceBridge bridge(s);
    ADD_FAILURE() << "two fingers on channel 0 of one socket";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "fingers.b.device.channel");
    EXPECT_EQ(e.file(), "same.toml");
    EXPECT_EQ(e.line(), 14);  // the finger's udp line
  }
  const SessionDesc ok = parseSceneText(kUdpScene, "ok.toml", "");
  std::optional<UdpDeviceBridge> first(std::in_place, ok);
  const std::string address = first->address(0);
  EXPECT_EQ(address, first->address(1));  // one socket, two channels
  const std::string port = address.substr(address.find(':') + 1);
  EXPECT_NE(port, "0");
  const SessionDesc taken = parseSceneText(withDevice("udp = " + port), "taken.toml", "");
  try {
    UdpDeviceBridge second(taken);
    ADD_FAILURE() << "port " << port << " bound twice";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "fingers.a.device.udp");
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + port), std::string::npos) << e.what();
  }
  first.reset();  // the port is free again
  // One port, two addresses in one scene: both fields named, not "in use by another program".
  std::string mixed = kUdpScene;
  mixed.replace(mixed.find("udp = \"127.0.0.1:0\""), 19, "udp = \"0.0.0.0:" + port + "\"");
  mixed.replace(mixed.find("udp = \"127.0.0.1:0\""), 19, "udp = \"127.0.0.1:" + port + "\"");
  try {
    UdpDeviceBridge third(parseSceneText(mixed, "mixed.toml", ""));
    ADD_FAILURE() << "two addresses on one port";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "fingers.b.device.udp");
    EXPECT_NE(std::string(e.what()).find("fingers.a.device.udp (0.0.0.0:" + port + ")"), std::string::npos) << e.what();
  }
}

// Offline runs and `live` step on their own clock: a UDP device there is an error that says so,
// before any output is touched.
TEST(UdpDeviceScene, OfflineRunsAndLiveRefuseIt) {
  const SessionDesc s = parseSceneText(kUdpScene, "udp.toml", "");
  SessionOptions options;
  options.out_dir = std::string(GF_BINARY_DIR) + "/test-outputs/udp-offline";
  options.progress = false;
  try {
    runSession(s, options);
    ADD_FAILURE() << "an offline run with a UDP device";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "udp.toml");
    EXPECT_EQ(e.line(), 9);
    EXPECT_EQ(e.field(), "fingers.a.device.udp");
    EXPECT_NE(std::string(e.what()).find("--realtime"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(options.out_dir));
  // Given on the command line: the error names the --set, not the scene file's line.
  const std::vector<std::string> set = {"fingers.a.device.udp=5000"};
  try {
    runSession(parseSceneText(kUdpScene, "udp.toml", "", set), options);
    ADD_FAILURE() << "an offline run with a UDP device from --set";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--set fingers.a.device.udp=5000") << e.what();
    EXPECT_EQ(e.field(), "fingers.a.device.udp");
  }
  const std::string path = std::string(GF_BINARY_DIR) + "/test-outputs/udp-live.toml";
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << kUdpScene;
  LiveOptions live;
  live.scene_path = path;
  std::istringstream in("step 1\n");
  std::ostringstream out;
  try {
    runLive(live, in, out);
    ADD_FAILURE() << "live with a UDP device";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "fingers.a.device.udp");
    EXPECT_NE(std::string(e.what()).find("godfinger run --realtime"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gf::app

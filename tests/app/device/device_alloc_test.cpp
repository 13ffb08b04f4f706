// A live UDP device must not allocate on the haptic thread: reading the socket, taking packets
// (garbage included), sampling, and sending the replies, once the bridge is built.
#include <gtest/gtest.h>

#include <array>

#include <sys/socket.h>
#include <unistd.h>

#include "app/scene/scene_file.hpp"
#include "app/device/device_protocol.hpp"
#include "app/device/udp_device.hpp"
#include "tests/alloc_counter.hpp"
#include "tests/app/device/loopback.hpp"

namespace gf::app {
namespace {

TEST(DeviceAllocation, NoHeapAllocationPerStep) {
  const SessionDesc session = parseSceneText(R"(name = "alloc"
duration = 1.0
effects = ["gravity"]
[bodies.ground]
shape = "plane"
[fingers.f]
[fingers.f.device]
udp = "127.0.0.1:0"
start = [0, 0.1, 0]
stale_after = 0.005
)", "alloc.toml", "");
  UdpDeviceBridge bridge(session);
  sim::DeviceSource* source = bridge.sources()[0];
  const sockaddr_in server = gf::test::loopback(gf::test::portOf(bridge.address(0)));
  const int device = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(device, 0);
  const sim::DeviceFeedback feedback{sim::Vec3(0.0, 4.0, 0.0), 0.004, 8, true};
  std::array<std::uint8_t, DevicePacket::kSize> bytes;
  std::array<std::uint8_t, 128> reply;
  double t = 0.0;
  // A packet (and every 7th step a short datagram), a step, the reply read back; every 100
  // steps a 20-step silence, so the stale hold and both ramps run too.
  const auto steps = [&](int n) {
    for (int k = 0; k < n; ++k) {
      const bool silent = k % 100 >= 80;
      if (!silent) {
        DevicePacket p;
        p.seq = static_cast<std::uint32_t>(k);
        p.time = t;
        p.position = sim::Vec3(0.0, 0.1 - 1e-5 * (k % 50), 0.0);
        encodeDevicePacket(p, bytes);
        sendto(device, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&server), sizeof server);
        if (k % 7 == 0) sendto(device, bytes.data(), 10, 0, reinterpret_cast<const sockaddr*>(&server), sizeof server);
      }
      source->sample(t);
      t += 0.001;
      source->feedback(t, feedback);
      recv(device, reply.data(), reply.size(), MSG_DONTWAIT);
    }
  };
  steps(200);  // warm
  const long before = test::allocations();
  steps(1000);
  EXPECT_EQ(test::allocations() - before, 0);
  close(device);
}

}  // namespace
}  // namespace gf::app

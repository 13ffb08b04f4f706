// What a UDP device adds to each haptic step (docs/device-protocol.md): one packet read and one
// reply sent on loopback. BM_UdpDeviceStep times a device program's send, the source's sample
// (drain the socket, take the packet) and feedback (encode and send the reply), and the device
// program's receive: an upper bound of the haptic thread's share, both ends included.
#include <benchmark/benchmark.h>

#include <array>

#include <sys/socket.h>
#include <unistd.h>

#include "app/scene/scene_file.hpp"
#include "app/device/device_protocol.hpp"
#include "app/device/udp_device.hpp"
#include "tests/app/device/loopback.hpp"

namespace {

using gf::sim::Vec3;

void BM_UdpDeviceStep(benchmark::State& state) {
  const gf::app::SessionDesc session = gf::app::parseSceneText(R"(name = "bench"
duration = 1.0
effects = ["gravity"]
[bodies.ground]
shape = "plane"
[fingers.f]
[fingers.f.device]
udp = "127.0.0.1:0"
start = [0, 0.1, 0]
)", "bench.toml", "");
  gf::app::UdpDeviceBridge bridge(session);
  gf::sim::DeviceSource* source = bridge.sources()[0];
  const sockaddr_in server = gf::test::loopback(gf::test::portOf(bridge.address(0)));
  const int device = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  gf::app::DevicePacket packet;
  packet.position = Vec3(0.0, 0.1, 0.0);
  std::array<std::uint8_t, gf::app::DevicePacket::kSize> bytes;
  std::array<std::uint8_t, 128> reply;
  const gf::sim::DeviceFeedback feedback{Vec3(0.0, 4.0, 0.0), 0.004, 8, true};
  double t = 0.0;
  for (auto _ : state) {
    ++packet.seq;
    packet.time = t;
    gf::app::encodeDevicePacket(packet, bytes);
    sendto(device, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&server), sizeof server);
    benchmark::DoNotOptimize(source->sample(t));
    t += 0.001;
    source->feedback(t, feedback);
    benchmark::DoNotOptimize(recv(device, reply.data(), reply.size(), 0));
  }
  close(device);
}
BENCHMARK(BM_UdpDeviceStep)->Unit(benchmark::kMicrosecond);

}  // namespace

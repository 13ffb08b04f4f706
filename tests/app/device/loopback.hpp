// A device program's end of a UDP device on loopback, for the tests and the benchmark that play
// one (docs/device-protocol.md).
#pragma once

#include <array>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <arpa/inet.h>
#include <netinet/in.h>

#include "app/device/device_protocol.hpp"

namespace gf::test {

/// A reply not here by then means the run is gone: a hang guard of the UDP tests (ms), never a
/// timing check.
constexpr int kGuardMs = 20000;

/// The port of an address "HOST:PORT" (as UdpDeviceBridge::address and a run's "listening on"
/// line give it), or 0.
inline int portOf(const std::string& address) {
  const std::size_t colon = address.rfind(':');
  return colon == std::string::npos ? 0 : std::atoi(address.c_str() + colon + 1);
}

/// 127.0.0.1:port, to send packets to.
inline sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

/// The bytes of a device packet with this seq, channel and position (m); time 0, no buttons.
inline std::vector<std::uint8_t> packetBytes(std::uint32_t seq, std::uint32_t channel, const sim::Vec3& p) {
  app::DevicePacket packet;
  packet.seq = seq;
  packet.channel = channel;
  packet.position = p;
  std::array<std::uint8_t, app::DevicePacket::kSize> bytes;
  app::encodeDevicePacket(packet, bytes);
  return {bytes.begin(), bytes.end()};
}

}  // namespace gf::test

// A device program's end of a UDP device on loopback, for the tests and the benchmark that play
// one (docs/device-protocol.md).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <string>

#include <arpa/inet.h>
#include <netinet/in.h>

namespace gf::test {

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

}  // namespace gf::test

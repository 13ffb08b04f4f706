// Live devices over UDP (docs/device-protocol.md): the sockets of a session's `udp` fingers and
// the DeviceSource the haptic loop samples for each of them.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "app/scene/session_desc.hpp"
#include "sim/scene/device.hpp"

namespace gf::app {

/// Datagrams one socket reads at most per haptic step (the rest wait for the next step), so a
/// flood cannot stretch a step.
inline constexpr int kMaxDatagramsPerStep = 64;
/// Receive buffer asked for each socket (bytes; the kernel caps it at net.core.rmem_max).
inline constexpr int kReceiveBufferBytes = 1 << 20;

/// Binds one non-blocking socket per distinct host:port of the session's UDP devices (fingers
/// sharing one differ by channel). Each step the haptic loop samples a finger's source, which
/// drains its socket without blocking, takes the newest valid packet of its channel and holds
/// the position when none has come for stale_after; after the step the source sends the reply
/// (the force ramped by the stale gain) to the address of the channel's newest packet. Everything
/// but construction and json() runs on the haptic thread; nothing there blocks or allocates.
class UdpDeviceBridge {
 public:
  /// Binds the sockets now. Throws InputError naming the scene file (or --set), line and field
  /// when a socket cannot be bound, two fingers give one port different addresses, or two on
  /// one socket read one channel.
  explicit UdpDeviceBridge(const SessionDesc& session);
  ~UdpDeviceBridge();
  UdpDeviceBridge(const UdpDeviceBridge&) = delete;
  UdpDeviceBridge& operator=(const UdpDeviceBridge&) = delete;

  /// One entry per finger of the scene: its UDP source, or nullptr for a finger on a track.
  std::span<sim::DeviceSource* const> sources() const { return sources_; }
  /// The address and port finger i listens on ("127.0.0.1:47001"; the port is the bound one,
  /// also when the scene asked for port 0).
  std::string address(int finger) const;
  /// What each device and socket received and sent, for summary.json (after the run).
  nlohmann::json json() const;
  /// Each device's link as of the last step: packets taken, stale, ramping and the ramp's gain.
  /// Any thread (the browser view reads it while the loop runs).
  nlohmann::json liveJson() const;
  /// One warning per socket bound beyond loopback (any host but 127.x.x.x): anyone who can
  /// reach that address can drive its fingers. After construction, any thread; allocates.
  std::vector<std::string> bindWarnings() const;
  /// One line per UDP finger for stderr after the run: its address and channel, the packets
  /// taken, those rejected by kind (its channel's and its socket's), the simulated seconds
  /// stale and the replies sent. After the run (not during it); allocates.
  std::vector<std::string> report() const;
  /// After the run: one warning per finger that took no packet, saying whether nothing came to
  /// its socket or what every datagram was rejected for. Allocates.
  std::vector<std::string> runWarnings() const;

  struct Socket;
  class Device;

 private:
  std::vector<std::unique_ptr<Socket>> sockets_;
  std::vector<std::unique_ptr<Device>> devices_;
  std::vector<sim::DeviceSource*> sources_;
  double dt_;  // s: the haptic step
};

}  // namespace gf::app

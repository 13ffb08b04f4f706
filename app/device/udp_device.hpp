// Live devices over UDP (docs/device-protocol.md): the sockets of a session's `udp` fingers and
// the DeviceSource the haptic loop samples for each of them.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
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
/// but construction, the ending (endRun) and the reports after the run runs on the haptic thread;
/// nothing there blocks or allocates.
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

  /// The run's last step ended at simulated time t (its duration, a Ctrl-C, a failure): from
  /// here a thread of the bridge's goes on at the haptic rate in real time, reading the sockets
  /// and answering every device after every step's time, each reply flagged ending and its force
  /// fading from the last step's to zero at the ramp's rate (DeviceLink::endAt). So no device is
  /// left pushing, and none goes unanswered while the run writes its outputs. Packets are read
  /// and dropped then: what json() and report() count stands as the last step left it, the
  /// ending's replies apart (`ending_replies`). Once.
  void endRun(double t);
  /// Waits until every device is told zero force: the fade, at most twice the longest
  /// force_ramp, 20 steps and 0.5 s, or until `cut_short` says so (looked at every 20 ms).
  /// `say`: a line on stderr when there is a fade to wait for. A run calls it before its
  /// summary; the devices go on being answered (zero, flagged ending) until the bridge is
  /// destroyed, which waits the same way, silently (after endRun from the last reply's time,
  /// when the run never called it and a device is still told a force).
  void awaitFade(bool say = true, const std::function<bool()>& cut_short = {});

  struct Socket;
  class Device;

 private:
  std::vector<std::unique_ptr<Socket>> sockets_;
  std::vector<std::unique_ptr<Device>> devices_;
  std::vector<sim::DeviceSource*> sources_;
  double dt_;  // s: the haptic step
  std::string name_;  // the scene's, for the line said while the force fades
  double longest_ramp_ = 0.0;  // s: the devices' largest force_ramp
  // After the run: the thread answering the devices while their forces fade (endRun), and what
  // it shares with the summary's readers and awaitFade.
  std::thread ending_;
  mutable std::mutex ending_mutex_;
  std::condition_variable ending_changed_;
  bool ended_ = false, stop_ending_ = false;
  void answerWhileEnding(double t);
  void stopEnding();
  bool toldNothing() const;  // no device is told a force (callers hold the ending's lock once it runs)
};

}  // namespace gf::app

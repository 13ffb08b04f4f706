// The UDP device protocol (docs/device-protocol.md): a device sends its position, godfinger
// answers every haptic step with the force to render. Fixed-size little-endian datagrams, and
// the state of one device's link (newest packet, staleness, force ramp) without the socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "app/scene/session_desc.hpp"
#include "sim/coupling.hpp"
#include "sim/device.hpp"
#include "sim/settings.hpp"

namespace gf::app {

/// A device's packet to godfinger (48 bytes).
struct DevicePacket {
  static constexpr std::uint32_t kMagic = 0x31444647;  ///< bytes "GFD1"
  static constexpr std::size_t kSize = 48;
  std::uint32_t seq = 0;      ///< increases by one per packet (wraps around)
  std::uint32_t channel = 0;  ///< which finger of those sharing the socket
  std::uint32_t buttons = 0;  ///< device buttons, bit i = button i
  double time = 0.0;          ///< s: the device's own clock when it read the position
  sim::Vec3 position = sim::Vec3::Zero();  ///< m, in the device's frame
};

/// godfinger's reply to a device, sent after every haptic step (64 bytes).
struct DeviceReply {
  static constexpr std::uint32_t kMagic = 0x31524647;  ///< bytes "GFR1"
  static constexpr std::size_t kSize = 64;
  static constexpr std::uint32_t kStale = 1u << 0;     ///< no packet for stale_after: position held
  static constexpr std::uint32_t kTouching = 1u << 1;  ///< the proxy touches a body
  static constexpr std::uint32_t kRamping = 1u << 2;   ///< force rate-limited: ramping at the start or after a dropout
  std::uint32_t seq = 0;      ///< the newest packet's seq taken for this channel
  std::uint32_t channel = 0;
  std::uint32_t flags = 0;
  double time = 0.0;             ///< s: simulated time at the end of the step
  sim::Vec3 force = sim::Vec3::Zero();     ///< N, in the device's frame: what the device should render
  double radius = 0.0;           ///< m: mean contact patch radius (Eq. 1); 0 without a patch
  std::uint32_t sgo_count = 0;   ///< sub-god-objects in the finger's patches
  float gain = 0.0f;             ///< 0..1: share of the coupling force sent (the stale ramp)
};

/// Why a datagram was not taken as a DevicePacket.
enum class PacketError {
  kNone,
  kSize,       ///< not exactly DevicePacket::kSize bytes
  kMagic,      ///< wrong first four bytes (another protocol or version)
  kBadValue,   ///< time not finite, or a coordinate not finite or beyond kMaxDeviceCoordinate
};

/// m: the largest device coordinate taken (a device's workspace is well under a metre).
inline constexpr double kMaxDeviceCoordinate = 100.0;
/// The stale ramp's gain snaps to 0 or 1 within this of either (the steps' sum is rounded).
inline constexpr double kGainRounding = 1e-9;
/// s: successive packets' device times closer than this do not update the velocity estimate.
inline constexpr double kMinVelocityInterval = 1e-5;

/// Decodes a datagram; `out` is written only when the result is kNone. Any bytes.
PacketError parseDevicePacket(std::span<const std::uint8_t> bytes, DevicePacket& out);
/// Encodes into exactly DevicePacket::kSize bytes.
void encodeDevicePacket(const DevicePacket& packet, std::span<std::uint8_t, DevicePacket::kSize> out);

/// Decodes a reply (for clients and tests); false unless the size and magic are right.
bool parseDeviceReply(std::span<const std::uint8_t> bytes, DeviceReply& out);
/// Encodes into exactly DeviceReply::kSize bytes.
void encodeDeviceReply(const DeviceReply& reply, std::span<std::uint8_t, DeviceReply::kSize> out);

/// One live device: what its packets say and what is sent back. Steps call sample(t), then
/// reply(t_end, feedback); take() any packets read in between. Deterministic (times are the
/// simulated ones), so the stale ramp is tested without sockets. Does not allocate.
class DeviceLink {
 public:
  struct Counters {
    long taken = 0;               ///< packets used
    long out_of_order = 0;        ///< seq not newer than the last taken (ignored)
    long lost = 0;                ///< seqs skipped between packets taken (lost or never sent)
    long out_of_range = 0;        ///< mapped outside the scene's coordinate range (ignored)
    long superseded = 0;          ///< taken, then replaced by a newer one before a step used it
    long stale_periods = 0;       ///< dropouts: the device went stale after a first packet
    long stale_steps = 0;         ///< steps sampled while stale (before the first packet too)
    long takeovers = 0;           ///< packets taken from another sender than the last one's
  };

  /// `max_force`: the finger's coupling clamp (N), the full scale of the force ramp.
  explicit DeviceLink(const UdpDeviceDesc& desc, double max_force = sim::CouplingSettings{}.max_force);

  /// A packet of this link's channel read before the step starting at t: false (and counted)
  /// when its seq is not newer than the last taken, or its position maps outside the scene's
  /// coordinate range (sim::kMaxSceneCoordinate). Seqs compare with wrap-around; the first
  /// packet after a dropout is taken whatever its seq (a restarted device is followed at once),
  /// the ones after it are ordered again. `sender` names where it came from (an address and
  /// port): a packet taken from another sender than the last is a takeover, faded in like a
  /// device back from a dropout (the gain and the force sent start again from zero, the
  /// velocity estimate too).
  bool take(const DevicePacket& packet, double t, std::uint64_t sender = 0);
  /// The device for the step starting at t: the newest packet's position in the scene
  /// (workspace_offset + workspace_scale * position) and a low-pass velocity from successive
  /// packets; while stale (no packet for stale_after) the position held, velocity 0; before the
  /// first packet, the start position.
  sim::DeviceSample sample(double t);
  /// The reply after the step that ended at t. The target is the feedback force times
  /// force_scale times the gain, which ramps at 1 / force_ramp per second towards 0 while stale
  /// and towards 1 otherwise. From the first stale step (and the start) until the gain is back
  /// to 1 and the force sent has caught up with the target, the force sent moves towards the
  /// target by at most max_force * force_scale * dt / force_ramp a step: a device that comes
  /// back elsewhere gets the new force faded in, never a step.
  DeviceReply reply(double t, const sim::DeviceFeedback& feedback);

  bool heard() const { return heard_; }  ///< a packet has been taken
  bool stale() const { return stale_; }   ///< as of the last sample
  bool ramping() const { return ramping_; }  ///< the force sent is rate-limited (see reply)
  double gain() const { return gain_; }
  double firstPacketTime() const { return first_packet_at_; }
  std::uint32_t buttons() const { return buttons_; }
  std::uint32_t lastSeq() const { return seq_; }
  const Counters& counters() const { return counters_; }

 private:
  UdpDeviceDesc desc_;
  double max_force_;
  bool heard_ = false, stale_ = true, resync_ = true, ramping_ = true;
  sim::Vec3 sent_ = sim::Vec3::Zero();  // the force of the last reply
  std::uint32_t seq_ = 0, buttons_ = 0;
  std::uint64_t sender_ = 0;
  double received_at_ = 0.0, device_time_ = 0.0, sample_time_ = 0.0, first_packet_at_ = 0.0, gain_ = 0.0;
  double interval_ = 0.0;  // s: device-clock gap between the last two packets of one stream
  sim::Vec3 position_, velocity_ = sim::Vec3::Zero();  // scene frame
  Counters counters_;
};

}  // namespace gf::app

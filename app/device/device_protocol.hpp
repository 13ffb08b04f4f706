// The UDP device protocol (docs/device-protocol.md): a device sends its position, godfinger
// answers every haptic step with the force to render. Fixed-size little-endian datagrams, and
// the state of one device's link (newest packet, staleness, force ramp) without the socket.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "app/scene/session_desc.hpp"
#include "sim/scene/coupling.hpp"
#include "sim/scene/device.hpp"
#include "sim/scene/settings.hpp"

namespace gf::app {

/// A device's packet to godfinger: "GFD1" (48 bytes, a position) or "GFD2" (64 bytes: the same
/// fields, then the device's orientation as 4 x f32 w, x, y, z at offset 48).
struct DevicePacket {
  static constexpr std::uint32_t kMagic = 0x31444647;  ///< bytes "GFD1"
  static constexpr std::size_t kSize = 48;
  static constexpr std::uint32_t kOrientedMagic = 0x32444647;  ///< bytes "GFD2"
  static constexpr std::size_t kOrientedSize = 64;
  std::uint32_t seq = 0;      ///< increases by one per packet (wraps around)
  std::uint32_t channel = 0;  ///< which finger of those sharing the socket
  std::uint32_t buttons = 0;  ///< device buttons, bit i = button i
  double time = 0.0;          ///< s: the device's own clock when it read the position
  sim::Vec3 position = sim::Vec3::Zero();  ///< m, in the device's frame
  bool oriented = false;  ///< a GFD2 packet: `orientation` was sent
  /// GFD2: rotates the device frame into the scene's axes (unit; normalised when parsed).
  sim::Quat orientation = sim::Quat::Identity();
};

/// godfinger's reply to a device, sent after every haptic step (64 bytes).
struct DeviceReply {
  static constexpr std::uint32_t kMagic = 0x31524647;  ///< bytes "GFR1"
  static constexpr std::size_t kSize = 64;
  static constexpr std::uint32_t kStale = 1u << 0;     ///< no packet for stale_after: position held
  static constexpr std::uint32_t kTouching = 1u << 1;  ///< the proxy touches a body
  static constexpr std::uint32_t kRamping = 1u << 2;   ///< force rate-limited: ramping at the start or after a dropout
  /// Another sender took the channel over: this sender's force fades to zero and stays there
  /// (its next packet takes the channel back, its force fading in again).
  static constexpr std::uint32_t kDisplaced = 1u << 3;
  /// The run is ending (an experiment's trial): the force fades to zero at the ramp's rate and
  /// stays there until the run's last reply.
  static constexpr std::uint32_t kEnding = 1u << 4;
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
  kSize,       ///< neither DevicePacket::kSize nor kOrientedSize bytes
  kMagic,      ///< wrong first four bytes for the size (another protocol or version)
  /// time not finite, a coordinate not finite or beyond kMaxDeviceCoordinate, or (GFD2) an
  /// orientation not finite or further than kMaxOrientationError from unit length
  kBadValue,
};

/// A GFD2 orientation's |q| may differ from 1 by this much (it is then normalised).
inline constexpr double kMaxOrientationError = 1e-3;

/// m: the largest device coordinate taken (a device's workspace is well under a metre).
inline constexpr double kMaxDeviceCoordinate = 100.0;
/// The stale ramp's gain snaps to 0 or 1 within this of either (the steps' sum is rounded).
inline constexpr double kGainRounding = 1e-9;
/// s: successive packets' device times closer than this do not update the velocity estimate.
inline constexpr double kMinVelocityInterval = 1e-5;

/// Decodes a datagram; `out` is written only when the result is kNone. Any bytes.
PacketError parseDevicePacket(std::span<const std::uint8_t> bytes, DevicePacket& out);
/// Encodes a GFD1 packet (the orientation left out) into exactly DevicePacket::kSize bytes.
void encodeDevicePacket(const DevicePacket& packet, std::span<std::uint8_t, DevicePacket::kSize> out);
/// Encodes a GFD2 packet (with the orientation) into exactly DevicePacket::kOrientedSize bytes.
void encodeOrientedDevicePacket(const DevicePacket& packet, std::span<std::uint8_t, DevicePacket::kOrientedSize> out);

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
    long displaced_replies = 0;   ///< replies made to senders another one displaced
  };

  /// At most this many displaced senders are answered (the oldest is dropped for a new one).
  static constexpr int kMaxDisplaced = 4;
  /// A sender another one took the channel from: what it was last told, faded to zero.
  struct Displaced {
    std::uint64_t sender = 0;
    std::uint32_t seq = 0;           ///< its newest packet's seq taken
    sim::Vec3 sent = sim::Vec3::Zero();  ///< its last reply's force (device frame, N)
  };

  /// `max_force`: the finger's coupling clamp (N), the full scale of the force ramp.
  explicit DeviceLink(const UdpDeviceDesc& desc, double max_force = sim::CouplingSettings{}.max_force);

  /// A packet of this link's channel read before the step starting at t: false (and counted)
  /// when its seq is not newer than the last taken, or its position maps outside the scene's
  /// coordinate range (sim::kMaxSceneCoordinate). Seqs compare with wrap-around; the first
  /// packet after a dropout is taken whatever its seq (a restarted device is followed at once),
  /// the ones after it are ordered again. A GFD2 packet's orientation (then the device's tilt)
  /// becomes the device's; a GFD1 packet moves the position only, the orientation staying the
  /// last GFD2 packet's of the same stream (identity for a stream that sent none). `sender` names where it came from (an address and
  /// port): a packet taken from another sender than the last is a takeover, faded in like a
  /// device back from a dropout (the gain and the force sent start again from zero, the
  /// velocity estimate too). The sender displaced keeps being answered (displacedReply); a
  /// displaced sender that takes the channel back starts from what it was last told.
  bool take(const DevicePacket& packet, double t, std::uint64_t sender = 0);
  /// The device for the step starting at t: the newest packet's position in the scene
  /// (workspace_offset + workspace_scale * position) and a low-pass velocity from successive
  /// packets; while stale (no packet for stale_after) the position held, velocity 0; before the
  /// first packet, the start position. The orientation is held likewise (the tilt alone
  /// before any GFD2 packet).
  sim::DeviceSample sample(double t);
  /// The reply after the step that ended at t. The target is the feedback force times
  /// force_scale times the gain, which ramps at 1 / force_ramp per second towards 0 while stale
  /// and towards 1 otherwise. From the first stale step (and the start) until the gain is back
  /// to 1 and the force sent has caught up with the target, the force sent moves towards the
  /// target by at most max_force * force_scale * dt / force_ramp a step: a device that comes
  /// back elsewhere gets the new force faded in, never a step.
  DeviceReply reply(double t, const sim::DeviceFeedback& feedback);
  /// The force of the last reply in the scene's frame (N; its force over force_scale): what the
  /// device renders until the next one.
  sim::Vec3 sentInScene() const;
  /// Senders another one displaced (after reply(t, ...) for this step): each gets, every step,
  /// a reply flagged kDisplaced whose force fades from what it was last told to zero at the ramp's
  /// rate (max_force * force_scale * dt / force_ramp a step) and then stays zero.
  int displacedCount() const { return displaced_count_; }
  const Displaced& displaced(int i) const { return displaced_[static_cast<std::size_t>(i)]; }
  /// Displaced sender i's reply for the step that ended at t (fades its force one step).
  DeviceReply displacedReply(int i, double t);

  /// The run ends at simulated time t: every reply after t is flagged kEnding and its force
  /// fades to zero at the ramp's rate, then stays zero (as after an experiment's trial).
  /// Samples after it are not the run's steps: they count no stale time.
  void endAt(double t) {
    desc_.fade_out_at = std::min(desc_.fade_out_at, t);
    run_over_ = true;
  }
  /// No sender is told a force: the last reply's, and every displaced sender's, is zero.
  bool toldNothing() const;

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
  bool resumed_ = false;  // a new stream after a dropout or a takeover, not sampled yet
  bool run_over_ = false;  // endAt was called: the samples are the ending's, not steps
  sim::Vec3 sent_ = sim::Vec3::Zero();  // the force of the last reply
  std::uint32_t seq_ = 0, buttons_ = 0;
  std::uint64_t sender_ = 0;
  std::array<Displaced, kMaxDisplaced> displaced_{};
  int displaced_count_ = 0;
  double ramp_step_ = 0.0;  // the last reply's step of the ramp (s / force_ramp)
  double received_at_ = 0.0, device_time_ = 0.0, sample_time_ = 0.0, first_packet_at_ = 0.0, gain_ = 0.0;
  double interval_ = 0.0;  // s: device-clock gap between the last two packets of one stream
  sim::Vec3 position_, velocity_ = sim::Vec3::Zero();  // scene frame
  sim::Quat orientation_;  // the newest GFD2 orientation, then the tilt
  Counters counters_;
};

}  // namespace gf::app

#include "app/device/device_protocol.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace gf::app {
namespace {

// Little-endian fields at fixed offsets, whatever the host's byte order.
std::uint32_t readU32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint32_t>(b[at]) | static_cast<std::uint32_t>(b[at + 1]) << 8 |
         static_cast<std::uint32_t>(b[at + 2]) << 16 | static_cast<std::uint32_t>(b[at + 3]) << 24;
}

double readF64(std::span<const std::uint8_t> b, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(b[at + i]) << (8 * i);
  return std::bit_cast<double>(v);
}

double readF32(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<double>(std::bit_cast<float>(readU32(b, at)));
}

void writeU32(std::span<std::uint8_t> b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

void writeF64(std::span<std::uint8_t> b, std::size_t at, double d) {
  const auto v = std::bit_cast<std::uint64_t>(d);
  for (std::size_t i = 0; i < 8; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

}  // namespace

PacketError parseDevicePacket(std::span<const std::uint8_t> b, DevicePacket& out) {
  if (b.size() != DevicePacket::kSize && b.size() != DevicePacket::kOrientedSize) return PacketError::kSize;
  DevicePacket p;
  p.oriented = b.size() == DevicePacket::kOrientedSize;
  if (readU32(b, 0) != (p.oriented ? DevicePacket::kOrientedMagic : DevicePacket::kMagic)) return PacketError::kMagic;
  p.seq = readU32(b, 4);
  p.channel = readU32(b, 8);
  p.buttons = readU32(b, 12);
  p.time = readF64(b, 16);
  p.position = sim::Vec3(readF64(b, 24), readF64(b, 32), readF64(b, 40));
  if (!std::isfinite(p.time) || !p.position.allFinite() || p.position.cwiseAbs().maxCoeff() > kMaxDeviceCoordinate) {
    return PacketError::kBadValue;
  }
  if (p.oriented) {
    const sim::Quat q(readF32(b, 48), readF32(b, 52), readF32(b, 56), readF32(b, 60));
    if (!q.coeffs().allFinite() || !(std::abs(q.norm() - 1.0) <= kMaxOrientationError)) return PacketError::kBadValue;
    p.orientation = q.normalized();
  }
  out = p;
  return PacketError::kNone;
}

void encodeDevicePacket(const DevicePacket& p, std::span<std::uint8_t, DevicePacket::kSize> out) {
  writeU32(out, 0, DevicePacket::kMagic);
  writeU32(out, 4, p.seq);
  writeU32(out, 8, p.channel);
  writeU32(out, 12, p.buttons);
  writeF64(out, 16, p.time);
  for (int i = 0; i < 3; ++i) writeF64(out, 24 + 8 * static_cast<std::size_t>(i), p.position[i]);
}

void encodeOrientedDevicePacket(const DevicePacket& p, std::span<std::uint8_t, DevicePacket::kOrientedSize> out) {
  encodeDevicePacket(p, out.first<DevicePacket::kSize>());
  writeU32(out, 0, DevicePacket::kOrientedMagic);
  const sim::Quat& q = p.orientation;
  std::size_t at = DevicePacket::kSize;
  for (double c : {q.w(), q.x(), q.y(), q.z()}) {
    writeU32(out, at, std::bit_cast<std::uint32_t>(static_cast<float>(c)));
    at += 4;
  }
}

bool parseDeviceReply(std::span<const std::uint8_t> b, DeviceReply& out) {
  if (b.size() != DeviceReply::kSize || readU32(b, 0) != DeviceReply::kMagic) return false;
  out.seq = readU32(b, 4);
  out.channel = readU32(b, 8);
  out.flags = readU32(b, 12);
  out.time = readF64(b, 16);
  out.force = sim::Vec3(readF64(b, 24), readF64(b, 32), readF64(b, 40));
  out.radius = readF64(b, 48);
  out.sgo_count = readU32(b, 56);
  out.gain = std::bit_cast<float>(readU32(b, 60));
  return true;
}

void encodeDeviceReply(const DeviceReply& r, std::span<std::uint8_t, DeviceReply::kSize> out) {
  writeU32(out, 0, DeviceReply::kMagic);
  writeU32(out, 4, r.seq);
  writeU32(out, 8, r.channel);
  writeU32(out, 12, r.flags);
  writeF64(out, 16, r.time);
  for (int i = 0; i < 3; ++i) writeF64(out, 24 + 8 * static_cast<std::size_t>(i), r.force[i]);
  writeF64(out, 48, r.radius);
  writeU32(out, 56, r.sgo_count);
  writeU32(out, 60, std::bit_cast<std::uint32_t>(r.gain));
}

DeviceLink::DeviceLink(const UdpDeviceDesc& desc, double max_force)
    : desc_(desc), max_force_(max_force), position_(desc.start), orientation_(desc.tilt) {}

bool DeviceLink::take(const DevicePacket& p, double t, std::uint64_t sender) {
  const auto ahead = static_cast<std::int32_t>(p.seq - seq_);  // serial-number order
  if (heard_ && !resync_ && ahead <= 0) {
    ++counters_.out_of_order;
    return false;
  }
  const sim::Vec3 position = desc_.workspace_offset + desc_.workspace_scale * p.position;
  if (position.cwiseAbs().maxCoeff() > sim::kMaxSceneCoordinate) {
    ++counters_.out_of_range;
    return false;
  }
  const bool takeover = heard_ && sender != sender_;
  if (takeover) {  // another hand on this channel: it gets the force faded in from zero
    ++counters_.takeovers;
    // The sender displaced keeps being answered, its force fading from what it was told; the
    // new one starts from what it was last told itself (zero, unless displaced a moment ago).
    sim::Vec3 told = sim::Vec3::Zero();
    for (int i = 0; i < displaced_count_; ++i) {
      if (displaced_[static_cast<std::size_t>(i)].sender != sender) continue;
      told = displaced_[static_cast<std::size_t>(i)].sent;
      std::copy(displaced_.begin() + i + 1, displaced_.begin() + displaced_count_, displaced_.begin() + i);
      --displaced_count_;
      break;
    }
    if (displaced_count_ == kMaxDisplaced) {  // the oldest is dropped
      std::copy(displaced_.begin() + 1, displaced_.end(), displaced_.begin());
      --displaced_count_;
    }
    displaced_[static_cast<std::size_t>(displaced_count_++)] = {sender_, seq_, sent_};
    gain_ = 0.0;
    sent_ = told;
    ramping_ = true;
  }
  const double gap = p.time - device_time_;
  // How long the hand took to move here: unknown for a new stream (its first move is a jump if
  // it is a far one), the device clock's gap otherwise.
  const bool new_stream = !heard_ || takeover || gap < 0.0 || gap > desc_.stale_after;
  interval_ = new_stream ? 0.0 : gap;
  // A GFD1 packet keeps its stream's orientation; a new stream starts from the device's own.
  if (p.oriented) orientation_ = (p.orientation * desc_.tilt).normalized();
  else if (new_stream) orientation_ = desc_.tilt;
  if (new_stream) {
    velocity_.setZero();  // a new stream: no estimate yet
  } else if (gap >= kMinVelocityInterval) {
    const sim::Vec3 raw = (position - position_) / gap;
    const double a = desc_.velocity_smoothing > 0.0 ? 1.0 - std::exp(-gap / desc_.velocity_smoothing) : 1.0;
    velocity_ += a * (raw - velocity_);
  }
  if (heard_ && received_at_ == t) ++counters_.superseded;  // the previous one was never used
  if (heard_ && !resync_ && !takeover) counters_.lost += ahead - 1;
  resumed_ = heard_ && new_stream;  // the first packet of all is the device's first position, no resume
  if (!heard_) first_packet_at_ = t;
  resync_ = false;
  position_ = position;
  device_time_ = p.time;
  seq_ = p.seq;
  sender_ = sender;
  buttons_ = p.buttons;
  received_at_ = t;
  heard_ = true;
  ++counters_.taken;
  return true;
}

sim::DeviceSample DeviceLink::sample(double t) {
  sample_time_ = t;
  const bool stale = !heard_ || t - received_at_ > desc_.stale_after;
  if (stale && !stale_ && heard_ && !run_over_) ++counters_.stale_periods;
  stale_ = stale;
  if (stale_) resync_ = ramping_ = true;
  if (stale_ && !run_over_) ++counters_.stale_steps;
  sim::DeviceSample out{position_, stale_ ? sim::Vec3::Zero() : velocity_, interval_};
  out.orientation = orientation_;
  out.resumed = resumed_ && !stale_;
  if (!stale_) resumed_ = false;
  return out;
}

DeviceReply DeviceLink::reply(double t, const sim::DeviceFeedback& f) {
  const double step = (t - sample_time_) / desc_.force_ramp;  // of the gain's 0..1
  ramp_step_ = step;
  const bool ending = t > desc_.fade_out_at;
  if (ending) ramping_ = true;  // rate-limited to zero, however large the force
  gain_ = stale_ || ending ? gain_ - step : gain_ + step;
  // Whole steps of the ramp add up to 1 only within rounding: the ends are exact.
  if (gain_ < kGainRounding) gain_ = 0.0;
  if (gain_ > 1.0 - kGainRounding) gain_ = 1.0;
  const sim::Vec3 target = (gain_ * desc_.force_scale) * f.force;
  if (ramping_) {
    const double limit = max_force_ * desc_.force_scale * step;
    const sim::Vec3 change = target - sent_;
    const double size = change.norm();
    sent_ = size > limit ? sim::Vec3(sent_ + (limit / size) * change) : target;
    ramping_ = !(gain_ == 1.0 && size <= limit);  // caught up: the force follows the coupling again
  } else {
    sent_ = target;
  }
  DeviceReply r;
  r.seq = seq_;
  r.channel = static_cast<std::uint32_t>(desc_.channel);
  r.flags = (stale_ ? DeviceReply::kStale : 0u) | (f.touching ? DeviceReply::kTouching : 0u) |
            (ramping_ ? DeviceReply::kRamping : 0u) | (ending ? DeviceReply::kEnding : 0u);
  r.time = t;
  r.force = sent_;
  r.radius = f.radius;
  r.sgo_count = static_cast<std::uint32_t>(std::max(0, f.sgo_count));
  r.gain = static_cast<float>(gain_);
  return r;
}

bool DeviceLink::toldNothing() const {
  for (int i = 0; i < displaced_count_; ++i) {
    if (!displaced_[static_cast<std::size_t>(i)].sent.isZero(0.0)) return false;
  }
  return sent_.isZero(0.0);
}

sim::Vec3 DeviceLink::sentInScene() const {
  return desc_.force_scale > 0.0 ? sim::Vec3(sent_ / desc_.force_scale) : sim::Vec3::Zero();
}

DeviceReply DeviceLink::displacedReply(int i, double t) {
  Displaced& d = displaced_[static_cast<std::size_t>(i)];
  const double limit = max_force_ * desc_.force_scale * ramp_step_;
  const double size = d.sent.norm();
  d.sent = size > limit ? sim::Vec3(d.sent * (1.0 - limit / size)) : sim::Vec3::Zero();
  if (!run_over_) ++counters_.displaced_replies;  // the ending's are counted with its replies
  DeviceReply r;
  r.seq = d.seq;
  r.channel = static_cast<std::uint32_t>(desc_.channel);
  r.flags = DeviceReply::kDisplaced | (d.sent.isZero(0.0) ? 0u : DeviceReply::kRamping) |
            (t > desc_.fade_out_at ? DeviceReply::kEnding : 0u);
  r.time = t;
  r.force = d.sent;
  return r;
}

}  // namespace gf::app

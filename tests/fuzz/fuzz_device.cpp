// Fuzzes the UDP device protocol: the input is a stream of datagrams, each read as a packet
// (app::parseDevicePacket) and as a reply (app::parseDeviceReply); the packets taken drive a
// device link (app::DeviceLink) stepped at 1 kHz, with settings taken from the input within the
// scene validator's ranges and the feedback of a coupling spring to a fixed proxy (so the force
// follows the packets' positions). Whatever the bytes, every sample and reply must be finite, the
// gain within [0, 1] and never changing by more than a step of the ramp, the force sent at most
// max_force times force_scale, and while ramping never changing by more than the ramp's rate.
//
// Input: 8 bytes of settings, then records of [length byte][steps byte][length bytes]: the
// datagram, then that many haptic steps (0..3) before the next one.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "app/device/device_protocol.hpp"

namespace {

// A value in [lo, hi] from a byte.
double within(std::uint8_t b, double lo, double hi) { return lo + (hi - lo) * b / 255.0; }

void require(bool ok) {
  if (!ok) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 8) return 0;
  gf::app::UdpDeviceDesc d;
  d.workspace_scale = within(data[0], 0.01, 100.0);
  d.workspace_offset = gf::sim::Vec3(within(data[1], -1000.0, 1000.0), 0.0, -within(data[1], -1000.0, 1000.0));
  d.start = gf::sim::Vec3(0.0, within(data[2], -1000.0, 1000.0), 0.0);
  d.force_scale = within(data[3], 0.0, 100.0);
  d.stale_after = within(data[4], 0.005, 1.0);
  d.force_ramp = within(data[5], 0.005, 10.0);
  d.velocity_smoothing = within(data[6], 0.0, 0.1);
  d.channel = data[7];
  constexpr double kMaxForce = 40.0, kStiffness = 800.0, kDt = 0.001;
  gf::app::DeviceLink link(d, kMaxForce);
  // The coupling of a proxy held at (0.01, 0.02, 0) in the scene, clamped as the World clamps it.
  const auto coupling = [&](const gf::sim::DeviceSample& s) {
    gf::sim::Vec3 f = -kStiffness * (s.position - gf::sim::Vec3(0.01, 0.02, 0.0));
    if (f.norm() > kMaxForce) f *= kMaxForce / f.norm();
    return gf::sim::DeviceFeedback{f, 0.01, 8, true};
  };
  double t = 0.0, gain = link.gain();
  gf::sim::Vec3 sent = gf::sim::Vec3::Zero();
  bool was_ramping = true;
  const double rate_limit = kMaxForce * d.force_scale * kDt / d.force_ramp;
  const auto step = [&] {
    const gf::sim::DeviceSample s = link.sample(t);
    require(s.position.allFinite() && s.velocity.allFinite());
    require(s.position.cwiseAbs().maxCoeff() <= gf::sim::kMaxSceneCoordinate);
    require(s.orientation.coeffs().allFinite() && std::abs(s.orientation.norm() - 1.0) <= 1e-9);  // GFD2: unit
    t += kDt;
    const gf::app::DeviceReply r = link.reply(t, coupling(s));
    require(r.force.allFinite() && r.gain >= 0.0f && r.gain <= 1.0f);
    require(r.force.norm() <= kMaxForce * d.force_scale * (1.0 + 1e-12));
    require(std::abs(link.gain() - gain) <= kDt / d.force_ramp * (1.0 + 1e-9) + gf::app::kGainRounding);
    if (was_ramping || link.ramping()) require((r.force - sent).norm() <= rate_limit * (1.0 + 1e-9) + 1e-12);
    gain = link.gain();
    sent = r.force;
    was_ramping = link.ramping();
  };
  std::size_t at = 8;
  while (at + 2 <= size) {
    const std::size_t length = std::min<std::size_t>(data[at], size - at - 2);
    const int steps = data[at + 1] % 4;
    const std::span<const std::uint8_t> datagram(data + at + 2, length);
    at += 2 + length;
    gf::app::DeviceReply reply;
    (void)gf::app::parseDeviceReply(datagram, reply);
    gf::app::DevicePacket p;
    if (gf::app::parseDevicePacket(datagram, p) == gf::app::PacketError::kNone && p.channel == static_cast<std::uint32_t>(d.channel)) {
      link.take(p, t);
    }
    for (int i = 0; i < steps; ++i) step();
  }
  step();
  return 0;
}

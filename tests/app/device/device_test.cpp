// The UDP device protocol without a network: the documented byte layout, datagrams that must be
// ignored, and one device link's state (newest packet, staleness, the force ramp, the workspace
// mapping, takeovers and dropouts) stepped on simulated time. The scene fields of a `udp` device
// are tests/app/device/device_scene_test.cpp, the loopback run tests/app/device/device_udp_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <vector>

#include "app/scene/scene_file.hpp"
#include "app/device/device_protocol.hpp"
#include "app/session/live.hpp"
#include "app/session/session.hpp"
#include "app/device/udp_device.hpp"
#include "sim/world/world.hpp"
#include "tests/app/device/wire_bytes.hpp"

namespace gf::app {
namespace {

using sim::Vec3;

constexpr double kDt = 0.001;  // s: the haptic step of these tests

using gf::test::putF64;
using gf::test::putU32;

std::vector<std::uint8_t> packetBytes(std::uint32_t magic, std::uint32_t seq, std::uint32_t channel, double x) {
  std::vector<std::uint8_t> b;
  putU32(b, magic);
  putU32(b, seq);
  putU32(b, channel);
  putU32(b, 0x5);  // buttons
  putF64(b, 12.5);
  putF64(b, x);
  putF64(b, -0.25);
  putF64(b, 0.125);
  return b;
}

// docs/device-protocol.md: "GFD1", seq, channel, buttons, time, x, y, z at offsets 0..47.
TEST(DeviceProtocol, APacketIsReadAsDocumented) {
  const std::vector<std::uint8_t> b = packetBytes(0x31444647, 0x01020304, 3, 0.5);
  ASSERT_EQ(b.size(), 48u);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "GFD1");
  DevicePacket p;
  ASSERT_EQ(parseDevicePacket(b, p), PacketError::kNone);
  EXPECT_EQ(p.seq, 0x01020304u);
  EXPECT_EQ(p.channel, 3u);
  EXPECT_EQ(p.buttons, 5u);
  EXPECT_EQ(p.time, 12.5);
  EXPECT_EQ(p.position, Vec3(0.5, -0.25, 0.125));
  std::array<std::uint8_t, DevicePacket::kSize> again;
  encodeDevicePacket(p, again);
  EXPECT_TRUE(std::equal(again.begin(), again.end(), b.begin()));
}

// The reply: "GFR1", seq, channel, flags, time, force, radius, n_sgo, gain (f32) at 0..63.
TEST(DeviceProtocol, AReplyIsWrittenAsDocumented) {
  DeviceReply r;
  r.seq = 7;
  r.channel = 1;
  r.flags = DeviceReply::kTouching | DeviceReply::kRamping;
  r.time = 2.0;
  r.force = Vec3(1.0, -2.0, 3.0);
  r.radius = 0.004;
  r.sgo_count = 8;
  r.gain = 0.5f;
  std::array<std::uint8_t, DeviceReply::kSize> b;
  encodeDeviceReply(r, b);
  std::vector<std::uint8_t> expected;
  putU32(expected, 0x31524647);
  putU32(expected, 7);
  putU32(expected, 1);
  putU32(expected, 6);
  putF64(expected, 2.0);
  putF64(expected, 1.0);
  putF64(expected, -2.0);
  putF64(expected, 3.0);
  putF64(expected, 0.004);
  putU32(expected, 8);
  putU32(expected, 0x3f000000);  // 0.5f
  ASSERT_EQ(expected.size(), 64u);
  EXPECT_TRUE(std::equal(b.begin(), b.end(), expected.begin()));
  DeviceReply back;
  ASSERT_TRUE(parseDeviceReply(b, back));
  EXPECT_EQ(back.force, r.force);
  EXPECT_EQ(back.gain, 0.5f);
  EXPECT_FALSE(parseDeviceReply(std::span<const std::uint8_t>(b.data(), 63), back));
}

// Short, long, foreign, non-finite and out-of-range datagrams are each told apart, never taken.
TEST(DeviceProtocol, BadDatagramsAreRejectedWithTheirReason) {
  DevicePacket p;
  p.seq = 99;
  std::vector<std::uint8_t> b = packetBytes(0x31444647, 1, 0, 0.1);
  EXPECT_EQ(parseDevicePacket(std::span<const std::uint8_t>(b.data(), 0), p), PacketError::kSize);
  EXPECT_EQ(parseDevicePacket(std::span<const std::uint8_t>(b.data(), 47), p), PacketError::kSize);
  b.push_back(0);
  EXPECT_EQ(parseDevicePacket(b, p), PacketError::kSize);
  EXPECT_EQ(parseDevicePacket(packetBytes(0x32444647, 1, 0, 0.1), p), PacketError::kMagic);  // "GFD2"
  EXPECT_EQ(parseDevicePacket(packetBytes(0x31444647, 1, 0, std::nan("")), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(packetBytes(0x31444647, 1, 0, HUGE_VAL), p), PacketError::kBadValue);
  EXPECT_EQ(parseDevicePacket(packetBytes(0x31444647, 1, 0, kMaxDeviceCoordinate * 1.01), p), PacketError::kBadValue);
  EXPECT_EQ(p.seq, 99u);  // untouched
}

DevicePacket packet(std::uint32_t seq, double time, const Vec3& position) {
  DevicePacket p;
  p.seq = seq;
  p.time = time;
  p.position = position;
  return p;
}

sim::DeviceFeedback pressing(double fy) { return {Vec3(0.0, fy, 0.0), 0.004, 8, true}; }

// A device sends for 0.2 s, falls silent for 0.2 s, and comes back. The force sent back rises
// from 0 to full over force_ramp at the start, holds, ramps to 0 over force_ramp once no packet
// came for stale_after, and ramps back up: it never changes by more than dt / force_ramp of the
// full force between two steps. Meanwhile the position is held and the velocity is zero.
TEST(DeviceLink, AStaleDeviceRampsItsForceToZeroAndBack) {
  UdpDeviceDesc d;
  d.stale_after = 0.05;
  d.force_ramp = 0.1;
  d.start = Vec3(0.0, 0.2, 0.0);
  DeviceLink link(d);
  const double full = 5.0, per_step = kDt / d.force_ramp;
  double previous_gain = 0.0;
  long first_stale = -1, first_zero = -1, back_to_full = -1;
  const Vec3 hold(0.01, 0.05, 0.0);
  for (long k = 0; k < 700; ++k) {
    const double t = static_cast<double>(k) * kDt;
    const bool sending = k < 200 || k >= 400;
    if (sending) { ASSERT_TRUE(link.take(packet(static_cast<std::uint32_t>(k), t, hold), t)); }
    const sim::DeviceSample s = link.sample(t);
    EXPECT_EQ(s.position, hold) << k;  // held while silent
    if (!sending) { EXPECT_EQ(s.velocity, Vec3::Zero()) << k; }
    const DeviceReply r = link.reply(t + kDt, pressing(full));
    EXPECT_LE(std::abs(link.gain() - previous_gain), per_step * (1.0 + 1e-9)) << "force step at k = " << k;
    EXPECT_NEAR(r.force.y(), full * link.gain(), 1e-12);  // a constant force: the limit never bites
    EXPECT_EQ(r.gain, static_cast<float>(link.gain()));
    EXPECT_EQ((r.flags & DeviceReply::kStale) != 0, link.stale());
    EXPECT_EQ((r.flags & DeviceReply::kRamping) != 0, link.ramping());
    if (link.gain() < 1.0) {
      EXPECT_TRUE(link.ramping()) << k;
    }
    EXPECT_TRUE(r.flags & DeviceReply::kTouching);
    if (k < 200) { EXPECT_NEAR(link.gain(), std::min(1.0, static_cast<double>(k + 1) * per_step), 1e-9) << k; }
    if (link.stale() && first_stale < 0 && k > 0) first_stale = k;
    if (first_stale >= 0 && first_zero < 0 && link.gain() == 0.0) first_zero = k;
    if (k >= 400 && back_to_full < 0 && link.gain() == 1.0) back_to_full = k;
    previous_gain = link.gain();
  }
  // Last packet taken at k = 199: stale once more than 50 ms passed (k = 249 or 250 by rounding).
  EXPECT_GE(first_stale, 249);
  EXPECT_LE(first_stale, 250);
  EXPECT_GE(first_zero - first_stale, 98);  // 0.1 s of ramp at 0.01 a step
  EXPECT_LE(first_zero - first_stale, 100);
  EXPECT_GE(back_to_full - 400, 98);
  EXPECT_LE(back_to_full - 400, 101);
  EXPECT_EQ(link.counters().stale_periods, 1);
  EXPECT_EQ(link.counters().taken, 500);
}

// The coupling spring of a proxy held at the origin, felt by the device (N).
sim::DeviceFeedback spring(const sim::DeviceSample& s) {
  const Vec3 f = -800.0 * s.position;
  return {f.norm() > 40.0 ? Vec3(40.0 * f.normalized()) : f, 0.004, 8, true};
}

// A 10 cm box on the ground (`box_field`: static, or its mass) under one finger whose UDP device
// (port 0, channel 0) starts 20 cm up, with `device_fields` more.
SessionDesc boxUnderAUdpFinger(const std::string& box_field, const std::string& device_fields) {
  return parseSceneText("name = \"box\"\nduration = 1.0\n"
                        "effects = [\"gravity\", \"friction\", \"god_finger\", \"force_feedback\"]\n"
                        "[bodies.ground]\nshape = \"plane\"\n"
                        "[bodies.box]\nshape = \"box\"\nhalf_extents = [0.05, 0.05, 0.05]\n" + box_field +
                            "\nposition = [0, 0.05, 0]\n"
                            "[fingers.f]\nn_sgo = 8\n[fingers.f.device]\nudp = 0\nstart = [0, 0.2, 0]\n" +
                            device_fields,
                        "box.toml", "");
}

// A UDP finger over a static box: its link and its World, stepped as a session steps them.
struct LinkedBox {
  SessionDesc session = boxUnderAUdpFinger("static = true", "");
  const UdpDeviceDesc& d = session.udp_devices.at(0);
  DeviceLink link{d, session.scene.fingers[0].coupling.max_force};
  sim::World world{session.scene};
  double limit = 40.0 * d.force_scale * kDt / d.force_ramp;  // N a step (0.4 at the defaults)
  std::vector<sim::DeviceSample> samples = std::vector<sim::DeviceSample>(1);
  // The step at t with what the link samples (`jump_back`: as before resumes held the device,
  // it jumps to the hand), and the link's reply after it.
  DeviceReply step(double t, bool jump_back = false) {
    samples[0] = link.sample(t);
    if (jump_back) samples[0].resumed = false;
    world.step(kDt, samples);
    return link.reply(world.time(), {world.feedbackForce(0), world.contactRadius(0), world.sgoCount(0), world.touching(0)});
  }
};

// A device that falls silent a little longer than stale_after and comes back 6 mm away: the
// gain is still near 1, but the new force is faded in at the ramp's rate (max_force / force_ramp),
// never stepped; once caught up, the force follows the coupling again exactly.
TEST(DeviceLink, ADeviceThatComesBackElsewhereGetsItsForceFadedIn) {
  UdpDeviceDesc d;
  d.stale_after = 0.05;
  d.force_ramp = 0.1;
  DeviceLink link(d, 40.0);
  const double limit = 40.0 * kDt / d.force_ramp;  // N a step
  Vec3 previous = Vec3::Zero();
  bool was_ramping = true, caught_up_after_resume = false;
  double largest_resume_change = 0.0;
  for (long k = 0; k < 600; ++k) {
    const double t = static_cast<double>(k) * kDt;
    const Vec3 at = k < 300 ? Vec3(0.0, -0.001, 0.0) : Vec3(0.0, -0.007, 0.0);  // 0.8 N, then 5.6 N
    if (k < 240 || k >= 300) link.take(packet(static_cast<std::uint32_t>(k), t, at), t);  // silent 60 ms
    const sim::DeviceSample s = link.sample(t);
    const DeviceReply r = link.reply(t + kDt, spring(s));
    const double change = (r.force - previous).norm();
    if (was_ramping || link.ramping()) {
      EXPECT_LE(change, limit * (1.0 + 1e-9)) << "force step at k = " << k;
    }
    if (k >= 300 && k < 320) largest_resume_change = std::max(largest_resume_change, change);
    if (k >= 300 && !link.ramping()) {
      caught_up_after_resume = true;
      EXPECT_TRUE(r.force.isApprox(spring(s).force, 1e-12)) << k;  // follows the coupling exactly
    }
    was_ramping = link.ramping();
    previous = r.force;
  }
  EXPECT_EQ(link.counters().stale_periods, 1);
  EXPECT_TRUE(caught_up_after_resume);
  EXPECT_NEAR(largest_resume_change, limit, 1e-9);  // 4.8 N more, at 0.4 N a step
}

// A second sender takes the channel over with a newer seq and a position 45 mm deeper in the box
// (past the coupling's 40 N clamp where the first pressed with about 12 N): the new hand gets
// its force faded in from zero, and no two successive replies to one sender differ by more than
// max_force force_scale dt / force_ramp (0.4 N), the World's own max_force_rate included.
TEST(DeviceLink, ASenderThatTakesOverGetsItsForceFadedInFromZero) {
  LinkedBox box;
  DeviceLink& link = box.link;
  sim::World& world = box.world;
  const double limit = box.limit;
  std::uint64_t last_sender = 0;
  Vec3 previous = Vec3::Zero();
  double before_takeover = 0.0, first_to_new = -1.0, largest_step = 0.0;
  for (long k = 0; k < 1000; ++k) {
    const double t = static_cast<double>(k) * kDt;
    // The first hand presses 15 mm into the box's top (about 12 N); from 0.5 s another one,
    // 60 mm in (past the 40 N clamp), with seqs far ahead.
    const bool second = k >= 500;
    const Vec3 at = second ? Vec3(0.0, 0.108 - 0.06, 0.0) : Vec3(0.0, 0.108 - 0.015, 0.0);
    const std::uint64_t sender = second ? 2 : 1;
    link.take(packet(static_cast<std::uint32_t>(second ? 100000 + k : k + 1), t, at), t, sender);
    const DeviceReply r = box.step(t);
    if (sender != last_sender) {  // the first reply to a new sender
      if (second) first_to_new = r.force.norm();
    } else {
      largest_step = std::max(largest_step, (r.force - previous).norm());
    }
    if (k == 499) before_takeover = r.force.norm();
    last_sender = sender;
    previous = r.force;
  }
  RecordProperty("largest_step_n", std::to_string(largest_step));
  RecordProperty("first_reply_to_new_sender_n", std::to_string(first_to_new));
  EXPECT_EQ(link.counters().takeovers, 1);
  EXPECT_NEAR(before_takeover, 12.0, 0.5) << "the first hand's steady press";
  EXPECT_LE(first_to_new, limit * 1.05);
  EXPECT_LE(largest_step, limit * 1.05);
  // Held still 45 mm deeper, the new hand does no work: the World keeps its device where the
  // first hand's was and washes the 45 mm out only with the energy the port holds, none here
  // (the first hand came in with a jump, whose work is counted apart): it is faded in to the
  // first hand's press, and its stillness pays for no more.
  EXPECT_NEAR(previous.norm(), before_takeover, 1e-4) << "the new hand feels the press it took over";
  EXPECT_GE(world.portEnergy(0), -1e-3);
}

// Two programs on one channel. Hand 1 presses 15 mm into the box (about 12 N); at 0.5 s hand 2
// takes the channel (newer seqs), 60 mm in (the 40 N clamp); hand 1 goes on sending its own,
// older seqs, which are not taken; at 0.9 s hand 2 falls silent, and once it is stale hand 1's
// next packet takes the channel back. Every step each program hears: the one holding the
// channel its force, a displaced one (flag kDisplaced) its force fading to zero and then zero.
// Over the whole run no two successive replies to one program differ by more than max_force
// force_scale dt / force_ramp (0.4 N), and none waits a step for one.
TEST(DeviceLink, ADisplacedSenderHearsItsForceFadeToZeroAndTakesItBack) {
  LinkedBox box;
  DeviceLink& link = box.link;
  sim::World& world = box.world;
  const UdpDeviceDesc& d = box.d;
  const double limit = box.limit;
  std::array<std::vector<DeviceReply>, 3> heard;  // per sender 1 and 2, each step's replies
  std::uint64_t holder = 1;
  long taken_back = -1;
  for (long k = 0; k < 1400; ++k) {
    const double t = static_cast<double>(k) * kDt;
    link.take(packet(static_cast<std::uint32_t>(k + 1), t, Vec3(0.0, 0.108 - 0.015, 0.0)), t, 1);
    if (k >= 500 && k < 900) link.take(packet(static_cast<std::uint32_t>(100000 + k), t, Vec3(0.0, 0.108 - 0.06, 0.0)), t, 2);
    const DeviceReply r = box.step(t);
    const long takeovers = link.counters().takeovers;
    const std::uint64_t now = takeovers == 0 || takeovers == 2 ? 1 : 2;
    if (now == 1 && holder == 2) taken_back = k;
    holder = now;
    heard[holder].push_back(r);
    EXPECT_EQ(r.flags & DeviceReply::kDisplaced, 0u) << k;
    for (int i = 0; i < link.displacedCount(); ++i) {
      const std::uint64_t who = link.displaced(i).sender;
      ASSERT_NE(who, holder);
      const DeviceReply displaced = link.displacedReply(i, world.time());
      EXPECT_NE(displaced.flags & DeviceReply::kDisplaced, 0u) << k;
      heard[who].push_back(displaced);
    }
    ASSERT_EQ(heard[1].size(), static_cast<std::size_t>(k + 1)) << "hand 1 hears every step";
    if (k >= 500) {
      ASSERT_EQ(heard[2].size(), static_cast<std::size_t>(k - 499)) << "hand 2 from its first packet on";
    }
  }
  EXPECT_EQ(link.counters().takeovers, 2);
  EXPECT_NEAR(taken_back * kDt, 0.9 + d.stale_after, 0.002) << "hand 1 back once hand 2 is stale";
  for (int who : {1, 2}) {
    double largest = 0.0;
    for (std::size_t i = 1; i < heard[who].size(); ++i) {
      largest = std::max(largest, (heard[who][i].force - heard[who][i - 1].force).norm());
    }
    RecordProperty("largest_step_hand" + std::to_string(who) + "_n", std::to_string(largest));
    EXPECT_LE(largest, limit * (1.0 + 1e-9)) << "hand " << who;
  }
  EXPECT_NEAR(heard[1][499].force.norm(), 12.0, 0.5) << "hand 1's steady press";
  EXPECT_EQ(heard[1][700].force, Vec3::Zero()) << "displaced, hand 1 is told nothing";
  EXPECT_NE(heard[1][700].flags & DeviceReply::kDisplaced, 0u);
  EXPECT_NEAR(heard[1].back().force.norm(), 12.0, 0.5) << "hand 1 feels its press again";
  EXPECT_EQ(heard[2].back().force, Vec3::Zero()) << "displaced, hand 2 ends told nothing";
}

// The end of a run (DeviceLink::endAt, which UdpDeviceBridge::endRun calls after the last step,
// its thread then answering with the last step's feedback). Hand 1 presses 15 mm into the box
// (about 12 N) and goes on sending: from the first reply after the end every reply is flagged
// kEnding, no two successive ones differ by more than max_force force_scale dt / force_ramp
// (0.4 N), and the force reaches zero after force_ramp (the gain's fade: 12 N / 0.1 s is below that rate),
// then stays zero. With a takeover 10 steps before the end, the hand displaced (still told about
// 8 N) and the new one (fading in) are both told nothing at last, and only then.
TEST(DeviceLink, TheEndOfARunFadesTheLastForceToZeroAndKeepsItThere) {
  for (const bool takeover : {false, true}) {
    LinkedBox box;
    DeviceLink& link = box.link;
    DeviceReply r;
    for (long k = 0; k < 500; ++k) {
      const double t = static_cast<double>(k) * kDt;
      link.take(packet(static_cast<std::uint32_t>(k + 1), t, Vec3(0.0, 0.108 - 0.015, 0.0)), t, 1);
      if (takeover && k >= 490) link.take(packet(static_cast<std::uint32_t>(100000 + k), t, Vec3(0.0, 0.093, 0.0)), t, 2);
      r = box.step(t);
    }
    const sim::World& w = box.world;
    const sim::DeviceFeedback last{w.feedbackForce(0), w.contactRadius(0), w.sgoCount(0), w.touching(0)};
    if (!takeover) {
      EXPECT_NEAR(r.force.norm(), 12.0, 0.5) << "the press when the run ends";
    }
    EXPECT_FALSE(link.toldNothing());
    const double end = w.time();
    link.endAt(end);
    double t = end;
    long zero_at = -1, nothing_at = -1;
    std::vector<Vec3> displaced(1, link.displacedCount() > 0 ? link.displaced(0).sent : Vec3::Zero());
    for (long k = 0; k < 400; ++k) {
      link.take(packet(static_cast<std::uint32_t>(1000 + k), t, Vec3(0.0, 0.093, 0.0)), t, 1);
      link.sample(t);
      t += kDt;
      const DeviceReply e = link.reply(t, last);
      EXPECT_NE(e.flags & DeviceReply::kEnding, 0u) << k;
      EXPECT_LE((e.force - r.force).norm(), box.limit * (1.0 + 1e-9)) << "a step at " << k;
      if (link.displacedCount() > 0) {
        const Vec3 was = displaced.back();
        displaced.push_back(link.displacedReply(0, t).force);
        EXPECT_LE((displaced.back() - was).norm(), box.limit * (1.0 + 1e-9)) << "the displaced hand at " << k;
      }
      if (zero_at < 0 && e.force.isZero(0.0)) zero_at = k;
      if (zero_at >= 0) {
        EXPECT_TRUE(e.force.isZero(0.0)) << "zero stays zero, " << k;
      }
      if (nothing_at < 0 && link.toldNothing()) nothing_at = k;
      if (nothing_at >= 0) {
        EXPECT_TRUE(link.toldNothing()) << k;
      }
      r = e;
    }
    ASSERT_GE(zero_at, 0);
    if (!takeover) {
      EXPECT_NEAR(static_cast<double>(zero_at + 1) * kDt, box.d.force_ramp, 1.5 * kDt) << "faded over force_ramp";
      EXPECT_EQ(nothing_at, zero_at);
    } else {
      ASSERT_EQ(link.displacedCount(), 1);
      EXPECT_GT(displaced.front().norm(), 6.0) << "the displaced hand was still told a press";
      const long displaced_zero = std::find(displaced.begin(), displaced.end(), Vec3::Zero()) - displaced.begin() - 1;
      EXPECT_EQ(nothing_at, std::max(zero_at, displaced_zero)) << "told nothing once both are";
    }
  }
}

// Passivity through dropouts: a device pressing into a box and moving (a 12 mm, 1 Hz stroke from
// 2 mm above the box to 10 mm into it) drops out at random for 0.05 to 2 s (its packets lost; it goes on moving),
// 26 times in 60 s (fixed seed). While stale its force fades; at a resume the World keeps the
// device where it was and washes the difference out only as the port's energy allows, and the
// observer prices each move with the force the device was told (World::setToldForce): the port
// energy never falls below -1 mJ. As it was (the device jumping back to the hand, a jump deeper
// into the box storing energy no one put in, and every move priced with the World's own force),
// the same run went below it (the second pass prints how far).
TEST(DeviceLink, ThePortStaysPassiveThroughRandomDropoutsWhileMoving) {
  for (const bool told : {true, false}) {
    LinkedBox box;
    DeviceLink& link = box.link;
    sim::World& world = box.world;
    std::mt19937 random(48);
    std::uniform_real_distribution<double> length(0.05, 2.0), gap(0.5, 2.0);
    double next_drop = gap(random), drop_end = -1.0;
    long dropouts = 0;
    for (long k = 0; k < 60000; ++k) {
      const double t = static_cast<double>(k) * kDt;
      if (t >= next_drop && drop_end < t) {
        drop_end = t + length(random);
        next_drop = drop_end + gap(random);
        ++dropouts;
      }
      const double depth = 0.004 - 0.006 * std::cos(2.0 * M_PI * t);  // from 2 mm above the surface
      const Vec3 at(0.0, 0.108 - depth, 0.0);
      if (t >= drop_end) link.take(packet(static_cast<std::uint32_t>(k + 1), t, at), t);
      box.step(t, !told);  // as before: the device jumps to the hand at a resume
      if (told) world.setToldForce(0, link.sentInScene());
    }
    const double lowest = world.portObserver(0).min_energy;
    RecordProperty(told ? "lowest_port_energy_j" : "lowest_port_energy_jumping_back_priced_with_the_world_force_j",
                   std::to_string(lowest));
    EXPECT_GE(dropouts, 15);
    if (told) {
      EXPECT_GE(lowest, -1e-3) << dropouts << " dropouts";
    }
    std::printf("%s: lowest port energy %.3g J over %ld dropouts\n",
                told ? "resumed in place, priced with the force told" : "jumping back, priced with the World's force", lowest,
                dropouts);
  }
}

// After a dropout only the first packet skips the order check: a reordered burst does not move
// the device back. Seqs skipped between packets taken are counted as lost.
TEST(DeviceLink, OnlyTheFirstPacketAfterADropoutSkipsTheOrder) {
  DeviceLink link(UdpDeviceDesc{});
  double t = 0.0;
  EXPECT_TRUE(link.take(packet(10, t, Vec3(0.0, 0.1, 0.0)), t));
  link.sample(t);
  t = 0.001;
  EXPECT_TRUE(link.take(packet(14, t, Vec3(0.0, 0.1, 0.0)), t));  // 11, 12, 13 lost
  EXPECT_EQ(link.counters().lost, 3);
  link.sample(t);
  t = 0.2;  // silent: stale
  link.sample(t);
  EXPECT_TRUE(link.stale());
  t = 0.201;
  EXPECT_TRUE(link.take(packet(300, t, Vec3(0.01, 0.1, 0.0)), t));
  EXPECT_TRUE(link.take(packet(301, t, Vec3(0.02, 0.1, 0.0)), t));
  EXPECT_FALSE(link.take(packet(250, t, Vec3(0.03, 0.1, 0.0)), t));
  EXPECT_EQ(link.sample(t).position.x(), 0.02);
  EXPECT_EQ(link.counters().out_of_order, 1);
  EXPECT_EQ(link.counters().lost, 3);  // the jump to 300 starts a new stream
}

// Sequence numbers compare with wrap-around; an older one is ignored and counted, unless the
// device went stale first (a restarted device program starts its count again).
TEST(DeviceLink, OlderPacketsAreIgnoredExceptAfterADropout) {
  DeviceLink link(UdpDeviceDesc{});
  double t = 0.0;
  const auto at = [&](std::uint32_t seq, double x) { return link.take(packet(seq, t, Vec3(x, 0.1, 0.0)), t); };
  EXPECT_TRUE(at(0xFFFFFFFEu, 0.0));
  link.sample(t);
  t += kDt;
  EXPECT_TRUE(at(0xFFFFFFFFu, 0.001));
  EXPECT_TRUE(at(0u, 0.002));  // wraps
  EXPECT_EQ(link.counters().superseded, 1);  // 0xFFFFFFFF never reached a step
  EXPECT_EQ(link.sample(t).position.x(), 0.002);
  t += kDt;
  EXPECT_FALSE(at(0xFFFFFFFFu, 0.5));
  EXPECT_FALSE(at(0u, 0.5));  // not newer either
  EXPECT_EQ(link.counters().out_of_order, 2);
  EXPECT_EQ(link.sample(t).position.x(), 0.002);
  t += 0.06;  // silent for longer than stale_after
  EXPECT_TRUE(link.sample(t).velocity.isZero());
  EXPECT_TRUE(link.stale());
  EXPECT_TRUE(at(5u, 0.003));  // older, but a new stream
  EXPECT_EQ(link.sample(t).position.x(), 0.003);
  EXPECT_EQ(link.lastSeq(), 5u);
}

// Scene position = workspace_offset + workspace_scale * device position; the velocity is the
// packets' difference over their device times, low-pass filtered with velocity_smoothing.
// A sample says how long the hand took to get there: the device clock's gap between the last
// two packets of one stream (4 ms at 250 Hz, lost packets included), 0 for a new stream (the
// first packet, one after a dropout, another sender's), whose first move the World may call a
// jump.
TEST(DeviceLink, ASampleCarriesTheIntervalItsHandTook) {
  UdpDeviceDesc d;
  d.stale_after = 0.05;
  DeviceLink link(d);
  EXPECT_TRUE(link.take(packet(1, 10.000, Vec3(0.0, 0.1, 0.0)), 0.000, 7));
  EXPECT_EQ(link.sample(0.000).interval, 0.0) << "a first packet";
  EXPECT_TRUE(link.take(packet(2, 10.004, Vec3(0.0, 0.1, 0.012)), 0.004, 7));
  EXPECT_NEAR(link.sample(0.004).interval, 0.004, 1e-12);
  EXPECT_NEAR(link.sample(0.005).interval, 0.004, 1e-12) << "held between packets";
  EXPECT_TRUE(link.take(packet(4, 10.012, Vec3(0.0, 0.1, 0.036)), 0.012, 7));  // packet 3 lost
  EXPECT_NEAR(link.sample(0.012).interval, 0.008, 1e-12);
  EXPECT_TRUE(link.take(packet(5, 10.016, Vec3(0.0, 0.1, 0.5)), 0.016, 8));  // another sender
  EXPECT_EQ(link.sample(0.016).interval, 0.0);
  EXPECT_TRUE(link.take(packet(9, 10.2, Vec3(0.0, 0.1, 0.5)), 0.2, 8));  // after a dropout
  EXPECT_EQ(link.sample(0.2).interval, 0.0);
}

TEST(DeviceLink, TheWorkspaceMapsPositionsAndVelocities) {
  UdpDeviceDesc d;
  d.workspace_scale = 2.0;
  d.workspace_offset = Vec3(1.0, 0.5, 0.0);
  d.velocity_smoothing = 0.0;
  DeviceLink raw(d);
  d.velocity_smoothing = 0.005;
  DeviceLink smooth(d);
  for (int k = 0; k <= 100; ++k) {
    const double t = k * kDt;
    const DevicePacket p = packet(static_cast<std::uint32_t>(k), 100.0 + t, Vec3(0.1 * t, 0.0, -0.02));
    raw.take(p, t);
    smooth.take(p, t);
    const sim::DeviceSample a = raw.sample(t), b = smooth.sample(t);
    EXPECT_TRUE(a.position.isApprox(Vec3(1.0 + 0.2 * t, 0.5, -0.04), 1e-12)) << k;
    if (k >= 1) { EXPECT_NEAR(a.velocity.x(), 0.2, 1e-9) << k; }
    if (k == 50) { EXPECT_NEAR(b.velocity.x(), 0.2, 0.2 * std::exp(-10.0) * 1.01); }  // 50 ms = 10 time constants
  }
}

// At the validator's limits and beyond: coordinates mapped outside the scene's range are
// ignored, a device clock that jumps back or repeats does not make a velocity, and a World
// driven by the wildest packets the link takes (±100 m at 10 us apart) stays finite.
TEST(DeviceLink, ExtremePacketsKeepTheWorldFinite) {
  const SessionDesc session = boxUnderAUdpFinger("mass = 0.5", "workspace_scale = 100\nvelocity_smoothing = 0\n");
  DeviceLink link(session.udp_devices.at(0), session.scene.fingers[0].coupling.max_force);  // the largest scale taken
  EXPECT_FALSE(link.take(packet(1, 0.0, Vec3(10.1, 0.0, 0.0)), 0.0));  // 1010 m in the scene
  EXPECT_EQ(link.counters().out_of_range, 1);
  sim::World world(session.scene);
  std::vector<sim::DeviceSample> samples(1);
  double device_time = 0.0;
  for (long k = 0; k < 2000; ++k) {
    const double t = static_cast<double>(k) * kDt;
    // Alternating ends of the range, device times 10 us apart, sometimes repeated or going back.
    const double x = (k % 2 == 0 ? 1.0 : -1.0) * 9.99;
    device_time += (k % 7 == 0) ? -0.5 : (k % 5 == 0 ? 0.0 : kMinVelocityInterval);
    link.take(packet(static_cast<std::uint32_t>(k + 2), device_time, Vec3(x, 0.001 * (k % 3), -x)), t);
    samples[0] = link.sample(t);
    ASSERT_TRUE(samples[0].position.allFinite() && samples[0].velocity.allFinite()) << k;
    world.step(kDt, samples);
    const DeviceReply r = link.reply(world.time(), {world.feedbackForce(0), world.contactRadius(0), world.sgoCount(0),
                                                    world.touching(0)});
    ASSERT_TRUE(r.force.allFinite()) << k;
    ASSERT_LE(r.force.norm(), session.scene.fingers[0].coupling.max_force + 1e-9) << k;
    ASSERT_TRUE(world.proxyPosition(0).allFinite()) << k;
  }
  EXPECT_EQ(world.counters().nan_recoveries, 0);
}

}  // namespace
}  // namespace gf::app
